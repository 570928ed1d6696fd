"""Direct DEM footing runs (tools/direct_dem.py) against the multiscale runs of the same case:
one table, the load curves and the eps_q fields at one settlement.

usage: direct_dem_compare.py RUN_DIR [RUN_DIR ...] [--multiscale-table docs/footing_dem_e0187.md]
                             [--rows "DEM, h = B/4, flip 0.99" ...]
                             [--multiscale-runs MPM_DIR ...] [--multiscale-case CASE]
                             [--at 0.5] [--pictures B4.png B8.png] [-o PREFIX] [--dpi N]

Each RUN_DIR is a direct-DEM output (summary.json, history.csv, results.h5). The multiscale
numbers are read from their one home, the load table of --multiscale-table (the rows whose first
cell starts with a --rows text; columns: first peak, plateau over s/B 0.1-0.4, mean over
0.4-1.0, which a table that stops at s/B 0.4 lacks), never copied; or, with --multiscale-runs,
from the multiscale runs' own histories (mpm_lig output folders: history.csv with the footing's
settlement [m] and q [Pa], normalised by the B and q_s of the folder's case.json, or of
--multiscale-case for folders without one), with the direct DEM's definitions of the peak and
the windows, their curves drawn beside the grains'; --rows is then read only when given. Prints one row per run:
grains, B/d, particle-steps, core-hours, peak q/q_s (at s/B), plateau 0.1-0.4, mean 0.4-1.0 (a window the run did not reach: '-') and the
difference of each (first peak: the running maximum before the load first drops 10 % below it) against every multiscale row; writes PREFIX_load.png (q/q_s against s/B of
every run, the table rows' peak and window means as marks, the multiscale runs' own curves) and PREFIX_fields.png (eps_q of each
run at s/B = --at beside the --pictures of the multiscale fields), and PREFIX.json.
Exit 2 on bad input (a folder without a summary, a row not in the table).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py", "matplotlib")

import json  # noqa: E402
import os  # noqa: E402
import re  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import checkout, cli, figures, footing, size_effect  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import need, read_history, read_json, require_columns  # noqa: E402

WINDOWS = (("plateau", 0.1, 0.4), ("mean", 0.4, 1.0), ("plateau_0.1_0.3", 0.1, 0.3))
COMPARED = ("peak", "plateau_0.1_0.3", "plateau", "mean")  # against each multiscale row


def first_number(cell):
    m = re.search(r"[-+]?\d+(\.\d+)?", cell)
    return float(m.group(0)) if m else None


def multiscale_rows(path, prefixes):
    """{row name: {"peak", "plateau", "mean"}} from the load table of the study page."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    rows = {}
    for line in open(path):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 4:
            continue
        for prefix in prefixes:
            if cells[0].startswith(prefix):
                # A table that stops at s/B 0.4 has no post-peak column: no mean.
                rows[prefix] = {"peak": first_number(cells[1]), "plateau": first_number(cells[3]),
                                "mean": first_number(cells[4]) if len(cells) > 4 else None}
    for prefix in prefixes:
        if prefix not in rows:
            raise InputError(f"{path}: no table row starting with '{prefix}'")
    return rows


def first_peak(sB, q, drop=0.10):
    """(q, s/B) of the first peak: the running maximum (from s/B 0.02) just before the load
    first falls `drop` below it; the highest value when it never does."""
    best, at = -np.inf, 0.0
    for s, v in zip(sB, q):
        if s < 0.02:
            continue
        if v > best:
            best, at = v, s
        elif v < (1.0 - drop) * best:
            break
    return float(best), float(at)


SUMMARY_KEYS = ("grains", "B_over_d", "seed", "speed_factor", "particle_steps", "loading_steps",
                "core_seconds", "wall_seconds")


def windows(sB, q):
    """{"peak", "peak_at", and each WINDOWS mean (None where the curve stops short)}."""
    row = {}
    row["peak"], row["peak_at"] = first_peak(sB, q)
    for name, a, b in WINDOWS:
        inside = (sB >= a) & (sB <= b)
        row[name] = float(q[inside].mean()) if inside.any() and sB[-1] >= b - 1e-6 else None
    return row


def multiscale_run(directory, fallback_case=None):
    """(row, s/B, q/q_s) of an mpm_lig footing run: its history's settlement and q over the B
    and q_s of its case (DIR/case.json, else `fallback_case`); InputError naming what is
    missing."""
    case_path = os.path.join(directory, "case.json")
    if not os.path.isfile(case_path):
        if fallback_case is None:
            raise InputError(f"{directory}: no case.json (give the case with --multiscale-case)")
        case_path = fallback_case
    case = read_json(case_path)
    width = footing.width(case, case_path)
    qs = footing.surcharge(case, case_path)
    if not width > 0 or not qs:
        raise InputError(f"{case_path}: needs a footing width > 0 and a surface surcharge "
                         "(a traction) to normalise the load")
    path = os.path.join(directory, "history.csv")
    table = read_history(path)
    require_columns(table, ("settlement", "q"), path)
    sB, q = table["settlement"] / width, table["q"] / qs
    if not (np.all(np.isfinite(sB)) and np.all(np.isfinite(q))):
        raise InputError(f"{path}: settlement or q is not finite")
    row = {"run": directory, "reached": float(sB[-1])}
    row.update(windows(sB, q))
    return row, sB, q


def run_row(directory):
    path = os.path.join(directory, "summary.json")
    summary = read_json(path)
    for key in SUMMARY_KEYS:
        need(summary, key, path, number=True)
    path = os.path.join(directory, "history.csv")
    table = read_history(path)
    require_columns(table, ("s_over_B", "q_over_qs"), path)
    sB, q = table["s_over_B"], table["q_over_qs"]
    if len(sB) == 0:
        raise InputError(f"{path}: no rows")
    row = {"run": directory, "grains": summary["grains"], "B_over_d": summary["B_over_d"],
           "seed": summary["seed"], "speed_factor": summary["speed_factor"],
           "footing_column": summary.get("footing_column", 0.0),  # older summaries: none
           "particle_steps": summary["particle_steps"],
           "loading_particle_steps": summary["loading_steps"] * summary["grains"],
           "core_hours": summary["core_seconds"] / 3600.0,
           "wall_hours": summary["wall_seconds"] / 3600.0,
           "reached": float(sB[-1]), "highest": float(q.max()),
           "highest_at": float(sB[int(np.argmax(q))]),
           "void_ratio": (summary.get("preparation") or {}).get("void_ratio")}
    row.update(windows(sB, q))
    return row, sB, q


def read_picture(path):
    """A multiscale field picture (--pictures), read before the work."""
    import matplotlib.image as mpimg

    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    try:
        return mpimg.imread(path)
    except (OSError, ValueError, SyntaxError) as e:  # Pillow: OSError, a bad PNG: SyntaxError
        raise InputError(f"{path}: not a picture ({e})") from None


def greys(n):
    """n (colour, line style): shades from near black to light grey and four dash patterns,
    so that the multiscale curves stay apart from each other and from the grains'."""
    styles = ("--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))
    return [(str(round(0.1 + 0.55 * k / max(1, n - 1), 3)), styles[k % len(styles)])
            for k in range(n)]


def fmt(v, spec=".2f"):
    return "-" if v is None else format(v, spec)


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="+", metavar="RUN_DIR")
    p.add_argument("--multiscale-table", default=checkout.path("docs", "footing_dem_e0187.md"))
    p.add_argument("--rows", nargs="*", default=None,
                   help="table rows (default, without --multiscale-runs: the two flip-0.99 rows)")
    p.add_argument("--multiscale-runs", nargs="*", default=[], metavar="MPM_DIR",
                   help="multiscale run folders whose histories are compared")
    p.add_argument("--multiscale-case", metavar="CASE",
                   help="the case of --multiscale-runs folders that hold no case.json")
    p.add_argument("--at", type=cli.non_negative, default=0.5,
                   help="s/B of the field comparison")
    p.add_argument("--pictures", nargs="*", default=[], help="multiscale field pictures to set beside")
    p.add_argument("-o", "--output", metavar="PREFIX", default="direct_dem_compare",
                   help="writes PREFIX.json, PREFIX_load.png, PREFIX_fields.png")
    p.add_argument("--sizes", action="store_true",
                   help="also the size effect: per B/d the mean +- std over packings, a fit "
                   "against d/B extrapolated to B/d -> infinity (PREFIX_sizes.png)")
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    if os.path.isdir(a.output) or a.output.endswith(os.sep):
        raise InputError(f"-o {a.output}: a folder, not a prefix (e.g. "
                         f"{os.path.join(a.output, 'direct_dem_compare')})")
    cli.writable_file(a.output + ".json", "-o file")
    for suffix in ("_load.png", "_fields.png", "_sizes.png"):
        cli.picture_file(a.output + suffix)
    for d in a.runs:
        if not os.path.isfile(os.path.join(d, "summary.json")):
            raise InputError(f"{d}: no summary.json (not a direct_dem.py output)")
    images = [read_picture(picture) for picture in a.pictures]
    if a.rows is None:
        a.rows = [] if a.multiscale_runs else ["DEM, h = B/4, flip 0.99", "DEM, h = B/8, flip 0.99"]
    multi = multiscale_rows(a.multiscale_table, a.rows) if a.rows else {}
    multi_curves = []
    for d in a.multiscale_runs:
        m, sB, q = multiscale_run(d, a.multiscale_case)
        name = os.path.basename(os.path.normpath(d))
        if name in multi:
            raise InputError(f"{d}: two multiscale runs named {name}")
        multi[name] = m
        multi_curves.append((name, sB, q))
    rows, curves = [], []
    for d in a.runs:
        row, sB, q = run_row(d)
        for name, m in multi.items():
            for key in COMPARED:
                if row[key] is not None and m.get(key):
                    row[f"{key} vs {name}"] = row[key] / m[key] - 1.0
        rows.append(row)
        curves.append((d, sB, q, row))
    panels = [c for c in curves if c[1][-1] >= a.at - 1e-6]
    for d, *_ in panels:
        if not os.path.isfile(os.path.join(d, "results.h5")):
            raise InputError(f"{d}: no results.h5 for the fields at s/B = {a.at} (see --at)")
    head = (f"{'run':34s} {'grains':>7s} {'B/d':>5s} {'particle-steps':>14s} {'core-h':>7s} "
            f"{'first peak':>12s} {'highest':>12s} {'0.1-0.4':>8s} {'0.4-1.0':>8s}")
    print(head)
    for r in rows:
        print(f"{os.path.basename(os.path.normpath(r['run'])):34s} {r['grains']:7.0f} "
              f"{r['B_over_d']:5.0f} {r['particle_steps']:14.3g} {r['core_hours']:7.3f} "
              f"{r['peak']:6.2f} ({r['peak_at']:.2f}) {r['highest']:6.2f} ({r['highest_at']:.2f}) "
              f"{fmt(r['plateau']):>8s} {fmt(r['mean']):>8s}")
        for name in multi:
            diffs = [f"{key} {100 * r[f'{key} vs {name}']:+.0f} %" for key in
                     COMPARED if f"{key} vs {name}" in r]
            print(f"    against {name}: {', '.join(diffs)}")
    sizes = size_table(rows, multi, a.output, a.dpi) if a.sizes else None
    with open(a.output + ".json", "w") as f:
        json.dump({"runs": rows, "multiscale": multi, "table": a.multiscale_table,
                   "sizes": sizes}, f, indent=1)
    print(f"wrote {a.output}.json")

    fig, ax = figures.subplots(figsize=(7.5, 4.6))
    for d, sB, q, r in curves:
        ax.plot(sB, q, lw=1.0, label=f"direct DEM, B/d = {r['B_over_d']:.0f}, seed {r['seed']}"
                + (f", speed x{r['speed_factor']:g}" if r["speed_factor"] != 1 else "")
                + (f", on a column of {r['footing_column']:g} B" if r["footing_column"] else ""))
    for (name, sB, q), (colour, style) in zip(multi_curves, greys(len(multi_curves))):
        ax.plot(sB, q, color=colour, lw=1.6, ls=style, label=f"multiscale {name}")
    tabled = [(name, m) for name, m in multi.items() if name in a.rows]
    for (name, m), colour in zip(tabled, ("k", "0.45", "0.7")):
        ax.plot([0.1, 0.4], [m["plateau"]] * 2, "-", color=colour, lw=3, alpha=0.6)
        if m["mean"] is not None:
            ax.plot([0.4, 1.0], [m["mean"]] * 2, "--", color=colour, lw=3, alpha=0.6)
        ax.axhline(m["peak"], color=colour, lw=0.8, ls=":", label=f"{name}: peak (dotted), "
                   "window means (bars)")
    ax.set_xlabel("settlement s/B")
    ax.set_ylabel(r"footing pressure $q/q_s$")
    ax.set_xlim(0, max([1.0] + [c[1][-1] for c in curves] + [c[1][-1] for c in multi_curves]))
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1, frameon=False, fontsize=8)
    figures.save(fig, a.output + "_load.png", a.dpi)

    if not panels:
        return
    from mpm_lig_post.commands import plot_fields

    n = len(panels) + len(a.pictures)
    fig, axes = figures.subplots(1, n, figsize=(5.2 * n, 5.0), squeeze=False)
    for ax, (d, sB, q, r) in zip(axes[0], panels):
        fields = FieldFile(os.path.join(d, "results.h5"))
        step = fields.step(min(fields.steps, key=lambda s: abs(s / 1000.0 - a.at)))
        xy = step["positions"][:, :2]
        spacing = plot_fields.point_spacing(step, 2, len(xy))
        tri = plot_fields.triangulation(xy, spacing)
        eq = step["deviatoric_strain"]
        plot_fields.contour(fig, ax, tri, eq, r"$\varepsilon_q$", "viridis",
                            float(np.percentile(eq, 99)))
        ax.set_title(f"direct DEM B/d = {r['B_over_d']:.0f}, s/B = {step.step / 1000:.2f}")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        fields.close()
    for ax, picture, image in zip(axes[0][len(panels):], a.pictures, images):
        ax.imshow(image)
        ax.set_axis_off()
        ax.set_title(os.path.basename(picture), fontsize=9)
    figures.save(fig, a.output + "_fields.png", a.dpi)


def size_table(rows, multi, prefix, dpi):
    """The size effect of the highest load and the plateaus: printed, drawn, returned."""
    keys = ("highest", "plateau_0.1_0.3", "plateau")
    voids = [r["void_ratio"] for r in rows if r.get("void_ratio") is not None]
    e0 = round(float(np.mean(voids)), 4) if voids else None
    print("\nsize effect (plateau: s/B 0.1-0.4):")
    for line in size_effect.table(rows, keys, e0):
        print(line)
    fig, axes = figures.subplots(1, 2, figsize=(11, 4.2), squeeze=False)
    size_effect.plot(axes[0][0], rows, "highest", {k: m["peak"] for k, m in multi.items()},
                     r"highest $q/q_s$")
    size_effect.plot(axes[0][1], rows, "plateau_0.1_0.3", {}, r"mean $q/q_s$ over s/B 0.1-0.3")
    axes[0][0].legend(fontsize=7, frameon=False)
    figures.save(fig, prefix + "_sizes.png", dpi)
    return {k: {"by_size": size_effect.summary(rows, k), "fit": size_effect.fit(rows, k, e0)}
            for k in keys}


def entry():
    """The command: tools/direct_dem_compare.py in a checkout, mpm-lig-direct-dem-compare installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
