"""The RVE against the grains on the grains' own path: each probe of a direct DEM
(tools/direct_dem.py --probes) replayed on RVEs of the same grains, stress beside stress.

usage: replay_direct_dem.py CASE.json RUN_DIR -o OUT_DIR [--mpm-lig build/mpm_lig]
                            [--probes NAME ...] [--seeds 11 12 13] [--upto S] [--at S ...]
                            [--volume recorded|free|cells] [--dpi N]

RUN_DIR/probes.csv holds, for each probe (a window of the RVE's size that follows its grains),
the window's deformation gradient F from the start of loading and its grains' own stress
(Love-Weber) every few s/B. For each probe and each RVE packing seed this tool writes F as a
recorded path (OUT_DIR/paths/PROBE.csv), an element test of "test": "recorded_path" on CASE's
rve node with that seed (OUT_DIR/cases/PROBE_sSEED.json) and runs it with mpm_lig
(OUT_DIR/runs/PROBE_sSEED/): the RVE goes through the grains' deformation with the coupling's
increments and sub-step rule, from its own prepared packing. With --volume free the RVE takes
only the isochoric part of the window's F and its volume follows the grains' mean stress (the
path's column p): the RVE's dilatancy and stress ratio beside the grains' on their shear path,
without the volumetric stiffness that turns a small error of the window's det F into a large
one of p. With --volume cells the RVE takes the window's F scaled to its grains' own volume
(probes.csv's cells_volumetric: det F = exp(cells_volumetric), the isochoric part the
window's). It then prints, per probe, the
grains' and the RVEs' largest stress ratio q/p (2D: Mohr-circle radius over in-plane mean
stress) and where, the RVEs' mean over seeds and its spread, and the mean and largest
difference of p and of q/p along the path (p over the preparation pressure p0), and with --at
the grains' p/p0, q/p and volume beside the RVEs' mean ± std at the rows nearest those s/B
(the grains' volume two ways: ln det F of the window's least-squares F, and where probes.csv
has it the change of their summed Voronoi cells, cells_volumetric, their own volume); writes
OUT_DIR/replay.json and OUT_DIR/replay.png (q/p and p/p0 against s/B, grains and RVEs).
Exit 0 done, 1 an element test failed (its log named), 2 bad input (before anything runs).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import copy  # noqa: E402
import json  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.direct_dem.case import problem  # noqa: E402
from mpm_lig_post.direct_dem.probes import read_probes  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.mpm_run import run_case  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_MPM_LIG = os.path.normpath(os.path.join(HERE, "..", "..", "..", "build", "mpm_lig"))
def write_path(path, table, rows, volume):
    """The probe's F (and, for a free volume, the grains' mean stress p) as a recorded path;
    for the cells' volume F scaled so that det F is exp(cells_volumetric)."""
    columns = ("time", "F11", "F12", "F21", "F22") + (("p",) if volume == "free" else ())
    values = {c: np.asarray(table[c][:rows], float) for c in columns}
    if volume == "cells":
        scale = np.sqrt(np.exp(table["cells_volumetric"][:rows]) / window_det(table)[:rows])
        for c in ("F11", "F12", "F21", "F22"):
            values[c] = values[c] * scale
    with open(path, "w") as f:
        f.write("# the deformation gradient of a direct-DEM probe window (replay_direct_dem.py)\n")
        f.write(",".join(columns) + "\n")
        for k in range(rows):
            f.write(",".join("%.17g" % values[c][k] for c in columns) + "\n")


def path_rows(name, table, upto, volume):
    """The probe's rows to replay (to --upto), checked before anything is written: a window
    its grains have torn (det F <= 0), for a free volume one that carries no compression, and
    for the cells' volume one whose grains' cells are not known cannot be replayed."""
    rows = len(table["time"]) if upto is None else \
        int(np.count_nonzero(table["s_over_B"] <= upto + 1e-9))
    rows = max(rows, 2)
    bad = [(window_det({k: v[:rows] for k, v in table.items()}),
            "det F <= 0: its grains no longer hold together")]
    if volume == "free":
        bad.append((table["p"][:rows], "p <= 0: its grains carry no compression"))
    if volume == "cells":
        if "cells_volumetric" not in table:
            raise InputError(f"--volume cells: probe {name} has no cells_volumetric (probes.csv "
                             "of a direct DEM from before it was written: run it again)")
        bad.append((np.where(np.isfinite(table["cells_volumetric"][:rows]), 1.0, -1.0),
                    "no closed cells: its grains' volume is not known"))
    for values, why in bad:
        if not np.all(values > 0):
            at = table["s_over_B"][int(np.argmax(~(values > 0)))]
            raise InputError(f"probe {name}: {why} at s/B {at:.3f}; replay it to a smaller "
                             "--upto")
    return rows


def element_case(rve, seed, path_csv, title, free_volume):
    node = copy.deepcopy(rve)
    node["seed"] = seed
    node.pop("restart_file", None)
    path = {"csv": path_csv, "volume": "free" if free_volume else "recorded"}
    return {"title": title, "rve": node,
            "analysis": {"type": "element_test", "test": "recorded_path",
                         "path": path, "save_restart": False}}


def replay(mpm_lig, case_path, out):
    """Run one element test; its history (exit 1 naming the log when it fails)."""
    run_case(mpm_lig, case_path, out, out + ".log")
    history = read_history(os.path.join(out, "history.csv"))
    require_columns(history, ("s_xx", "s_yy", "s_xy", "p", "q", "e_vol"), out)
    return history


def ratio(p, q):
    return np.where(p > 0, q / np.maximum(p, 1e-300), np.nan)


def window_det(grains):
    """det F of the grains' window, row by row."""
    return grains["F11"] * grains["F22"] - grains["F12"] * grains["F21"]


def volumetric(grains):
    """The grains' volumetric log strain, ln det F of their window."""
    return np.log(window_det(grains))


def states_at(grains, rves, p0, at):
    """{s/B: grains' and RVEs' (mean, std) p/p0, q/p and volumetric strain} at the rows nearest
    each `at`."""
    out = {}
    g_vol = volumetric(grains)
    for s in at:
        k = int(np.argmin(np.abs(grains["s_over_B"] - s)))
        rows = [(h["p"][k] / p0, ratio(h["p"][k], h["q"][k]), h["e_vol"][k])
                for h in rves.values() if len(h["p"]) > k]
        if not rows:
            continue
        p, r, v = np.array(rows, float).T
        out[f"{s:g}"] = {"s_over_B": float(grains["s_over_B"][k]),
                         "grains_p_over_p0": float(grains["p"][k] / p0),
                         "grains_ratio": float(ratio(grains["p"][k], grains["q"][k])),
                         "grains_volumetric": float(g_vol[k]),
                         "grains_cells_volumetric": float(grains["cells_volumetric"][k])
                         if "cells_volumetric" in grains else None,
                         "rve_p_over_p0": float(p.mean()), "rve_p_over_p0_std": sample_std(p),
                         "rve_ratio": float(r.mean()), "rve_ratio_std": sample_std(r),
                         "rve_volumetric": float(v.mean()), "rve_volumetric_std": sample_std(v)}
    return out


def sample_std(values):
    """The spread over RVE seeds (0 for one seed)."""
    return float(np.std(values, ddof=1)) if len(values) > 1 else 0.0


def compare(grains, rves, p0, at=()):
    """The numbers of one probe: the grains' and each RVE's peak q/p, differences on the path,
    and the states at the s/B of `at`."""
    g_ratio = ratio(grains["p"], grains["q"])
    k = int(np.nanargmax(g_ratio))
    row = {"grains_peak_ratio": float(g_ratio[k]), "grains_peak_at": float(grains["s_over_B"][k]),
           "grains_final_p_over_p0": float(grains["p"][-1] / p0), "seeds": {}}
    peaks = []
    for seed, h in rves.items():
        n = min(len(h["p"]), len(grains["p"]))
        r_ratio = ratio(h["p"][:n], h["q"][:n])
        j = int(np.nanargmax(r_ratio))
        dp = np.abs(h["p"][:n] - grains["p"][:n]) / p0
        dr = np.abs(r_ratio - g_ratio[:n])
        row["seeds"][seed] = {"peak_ratio": float(r_ratio[j]),
                              "peak_at": float(grains["s_over_B"][j]),
                              "final_p_over_p0": float(h["p"][n - 1] / p0),
                              "mean_abs_dp_over_p0": float(np.nanmean(dp)),
                              "max_abs_dp_over_p0": float(np.nanmax(dp)),
                              "mean_abs_d_ratio": float(np.nanmean(dr)),
                              "max_abs_d_ratio": float(np.nanmax(dr))}
        peaks.append(r_ratio[j])
    row["rve_peak_ratio_mean"] = float(np.mean(peaks))
    row["rve_peak_ratio_std"] = sample_std(peaks)
    row["at"] = states_at(grains, rves, p0, at)
    return row


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("case", metavar="CASE.json", help="the footing case the direct DEM ran")
    p.add_argument("run", metavar="RUN_DIR", help="a direct-DEM run with probes.csv")
    p.add_argument("-o", "--output", required=True, metavar="OUT_DIR")
    p.add_argument("--mpm-lig", default=DEFAULT_MPM_LIG, help="the mpm_lig executable "
                   "(default: build/mpm_lig of this checkout)")
    p.add_argument("--probes", nargs="+", help="which probes (default: all in probes.csv)")
    p.add_argument("--seeds", type=cli.non_negative_int, nargs="+",
                   help="RVE packing seeds (default: the case's rve seed and the next two)")
    p.add_argument("--upto", type=cli.positive, help="replay rows up to this s/B (default all)")
    p.add_argument("--at", type=cli.non_negative, nargs="+", default=[],
                   help="s/B at which the grains' and the RVEs' p and q/p are set side by side")
    p.add_argument("--volume", choices=("recorded", "free", "cells"), default="recorded",
                   help="the RVE's volume: the window's det F (recorded, the default), free, "
                   "following the grains' mean stress with the isochoric part of F imposed, or "
                   "cells, its grains' own volume (probes.csv's cells_volumetric)")
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    free = a.volume == "free"
    case = read_json(a.case)
    pb = problem(case, a.case, 1.0)
    rve, p0 = pb["rve"], pb["p0"]
    if not (os.path.isfile(a.mpm_lig) and os.access(a.mpm_lig, os.X_OK)):
        raise InputError(f"--mpm-lig {a.mpm_lig}: no such executable (build it: cmake --build "
                         "build --target mpm_lig)")
    probes = read_probes(a.run)
    names = a.probes or sorted(probes)
    for name in names:
        if name not in probes:
            raise InputError(f"--probes {name}: {a.run}/probes.csv has {', '.join(sorted(probes))}")
    seeds = a.seeds or [int(rve.get("seed", 1)) + k for k in range(3)]
    if len(set(seeds)) != len(seeds):
        raise InputError("--seeds: a seed given twice")
    rows_of = {name: path_rows(name, probes[name], a.upto, a.volume) for name in names}
    out = os.path.abspath(a.output)
    cli.writable_folder(out)
    if os.path.isdir(out) and os.listdir(out):
        raise InputError(f"{out}: not empty (choose a new folder)")
    for sub in ("paths", "cases", "runs"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    report = {"case": a.case, "run": a.run, "p0": p0, "seeds": seeds, "volume": a.volume,
              "probes": {}}
    histories = {}
    for name in names:
        table, rows = probes[name], rows_of[name]
        grains = {k: v[:rows] for k, v in table.items()}
        path_csv = os.path.join(out, "paths", f"{name}.csv")
        write_path(path_csv, table, rows, a.volume)
        histories[name] = {}
        for seed in seeds:
            case_path = os.path.join(out, "cases", f"{name}_s{seed}.json")
            with open(case_path, "w") as f:
                json.dump(element_case(rve, seed, os.path.join("..", "paths", f"{name}.csv"),
                                       f"probe {name} of {a.run} on an RVE of seed {seed}",
                                       free), f, indent=1)
            print(f"replaying probe {name} ({rows} rows, to s/B "
                  f"{grains['s_over_B'][-1]:.3f}) on the RVE of seed {seed}", flush=True)
            histories[name][seed] = replay(a.mpm_lig, case_path,
                                           os.path.join(out, "runs", f"{name}_s{seed}"))
        report["probes"][name] = compare(grains, histories[name], p0, a.at)
        report["probes"][name]["rows"] = rows
    print_table(report)
    with open(os.path.join(out, "replay.json"), "w") as f:
        json.dump(report, f, indent=1)
    picture(os.path.join(out, "replay.png"), probes, histories, names, report, p0, a.dpi, free)


def print_table(report):
    print("| probe | grains: peak q/p (s/B) | RVEs: peak q/p, mean ± std | mean abs. diff. "
          "of q/p | mean abs. diff. of p / p0 | final p / p0, grains / RVEs |")
    print("|---|---|---|---|---|---|")
    for name, r in report["probes"].items():
        seeds = r["seeds"].values()
        print(f"| {name} | {r['grains_peak_ratio']:.3f} ({r['grains_peak_at']:.3f}) | "
              f"{r['rve_peak_ratio_mean']:.3f} ± {r['rve_peak_ratio_std']:.3f} | "
              f"{np.mean([s['mean_abs_d_ratio'] for s in seeds]):.3f} | "
              f"{np.mean([s['mean_abs_dp_over_p0'] for s in seeds]):.3f} | "
              f"{r['grains_final_p_over_p0']:.2f} / "
              f"{np.mean([s['final_p_over_p0'] for s in seeds]):.2f} |")
    states = [(name, s) for name, r in report["probes"].items() for s in r["at"].values()]
    if states:
        print("\n| probe | s/B | p / p0, grains | p / p0, RVEs | q/p, grains | q/p, RVEs | "
              "ln det F, grains | ln of their cells | e_vol, RVEs |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, s in states:
            cells = s["grains_cells_volumetric"]
            print(f"| {name} | {s['s_over_B']:.3f} | {s['grains_p_over_p0']:.2f} | "
                  f"{s['rve_p_over_p0']:.2f} ± {s['rve_p_over_p0_std']:.2f} | "
                  f"{s['grains_ratio']:.3f} | {s['rve_ratio']:.3f} ± {s['rve_ratio_std']:.3f} | "
                  f"{s['grains_volumetric']:.4f} | "
                  f"{'–' if cells is None else format(cells, '.4f')} | "
                  f"{s['rve_volumetric']:.4f} ± {s['rve_volumetric_std']:.4f} |")


def picture(path, probes, histories, names, report, p0, dpi, free):
    """q/p above; below p/p0, or with a free volume (p held at the grains') the volumetric
    strain."""
    fig, axes = figures.subplots(2, len(names), figsize=(3.6 * len(names), 6.0),
                                 squeeze=False)
    for j, name in enumerate(names):
        rows = report["probes"][name]["rows"]
        g = {k: v[:rows] for k, v in probes[name].items()}
        s = g["s_over_B"]
        axes[0][j].plot(s, ratio(g["p"], g["q"]), "k-", lw=1.6, label="grains")
        axes[1][j].plot(s, volumetric(g) if free else g["p"] / p0, "k-", lw=1.6,
                        label="grains (ln det F)" if free else "grains")
        if free and "cells_volumetric" in g:
            axes[1][j].plot(s, g["cells_volumetric"], "k--", lw=1.2, label="grains (cells)")
        for seed, h in histories[name].items():
            n = min(rows, len(h["p"]))
            axes[0][j].plot(s[:n], ratio(h["p"][:n], h["q"][:n]), lw=0.9, label=f"RVE {seed}")
            axes[1][j].plot(s[:n], h["e_vol"][:n] if free else h["p"][:n] / p0, lw=0.9,
                            label=f"RVE {seed}")
        axes[0][j].set_title(name, fontsize=10)
        axes[1][j].set_xlabel("s / B")
    axes[0][0].set_ylabel("q / p")
    axes[1][0].set_ylabel("volumetric strain" if free else "p / p0")
    axes[0][0].legend(fontsize=7)
    if free:
        axes[1][0].legend(fontsize=7)
    figures.save(fig, path, dpi)


def entry():
    """The command: tools/replay_direct_dem.py in a checkout, mpm-lig-replay-direct-dem
    installed."""
    cli.run(main, failures=RuntimeError)


if __name__ == "__main__":
    entry()
