"""The multiscale footing beside the grains, place by place: an MPM footing run's points
averaged over the windows of a direct DEM's probes (tools/direct_dem.py --probes), their
stress and strain against the grains' at equal s/B.

usage: mpm_probes.py MPM_RUN CASE.json DEM_RUN -o OUT_DIR [--probes NAME ...] [--window W]
                     [--ratio-gap G] [--pressure-gap P] [--dpi N]

CASE.json is the MPM run's case (its footing gives B, its base the surface). The DEM run's
probes.csv gives each window's rows (F and the grains' Love-Weber stress by s/B), its
summary.json p0 = q_s and "probes", each window's centre and side in footing widths (for a
run from before they were recorded: the named places of direct_dem and --window). In the MPM
run the window has the same place and size in footing widths; at every output step its
points (those whose reference position, position minus displacement, lies in the window)
give the volume-weighted mean stress and logarithmic strain, and s/B is the footing's
settlement at that step over B. Both are set side by side at the grains' rows (the MPM's interpolated in s/B): p / p0, the stress ratio
q/p (q the radius of Mohr's circle in the plane, as the element tests write it) and the
volumetric and deviatoric strain (Hencky: the grains' from their window's F; where probes.csv
has it, also the grains' own volume change, the ln of their summed Voronoi cells,
grains_cells_volumetric in mpm_probes.csv). The two
"part" at the first s/B where |q/p| differs by more than --ratio-gap (default 0.1) or p by
more than --pressure-gap p0 (default 0.5). Prints a table; writes OUT_DIR/mpm_probes.json,
OUT_DIR/mpm_probes.png and OUT_DIR/mpm_probes.csv (the side-by-side rows).
Exit 0 done, 2 bad input (before anything is written).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib", "h5py")

import json  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.direct_dem.probes import PLACES, read_probes  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402


def footing_geometry(case, path):
    """(B, surface y) of an MPM footing case: the first rigid body's width and base."""
    bodies = case.get("rigid_bodies") or []
    if not bodies or bodies[0].get("type") != "footing":
        raise InputError(f"{path}: no footing (rigid_bodies[0] of type footing)")
    width, base = bodies[0].get("width"), bodies[0].get("base")
    if not (isinstance(width, list) and width and isinstance(base, (int, float))):
        raise InputError(f"{path}: rigid_bodies[0]: width and base expected")
    return float(width[0]), float(base)


def hencky(F):
    """(volumetric, deviatoric) logarithmic strain of plane 2 x 2 gradients (n, 2, 2): ln det F
    and the radius of the in-plane Hencky strain's Mohr circle times 2 (an engineering shear)."""
    values = np.array([np.linalg.eigvalsh(f @ f.T) for f in F])
    e = 0.5 * np.log(values)
    return e.sum(axis=1), np.abs(e[:, 1] - e[:, 0])


def mpm_windows(run, B, surface, centres):
    """{probe: {s_over_B, p, q, volumetric, deviatoric}} of an MPM run: each output step's
    points in each window (centres: {probe: (x/B, depth/B, side/B)}; reference positions),
    volume-weighted."""
    history = read_history(os.path.join(run, "history.csv"))
    require_columns(history, ("step", "settlement"), run)
    settlement = dict(zip(history["step"].astype(int), history["settlement"]))
    fields = FieldFile(os.path.join(run, "results.h5"))
    out = {name: {k: [] for k in ("s_over_B", "p", "q", "volumetric", "deviatoric", "points")}
           for name in centres}
    try:
        for step in fields.steps:
            if step not in settlement:
                continue
            at = fields.step(step)
            x = at["positions"][:, :2] - at["displacement"][:, :2]
            stress, strain, volume = at["stress"], at["strain"], at["volume"].ravel()
            for name, (cx, depth, side) in centres.items():
                centre = np.array([cx * B, surface - depth * B])
                inside = np.all(np.abs(x - centre) <= 0.5 * side * B, axis=1)
                if not inside.any():
                    continue
                w = volume[inside] / volume[inside].sum()
                s = (stress[inside] * w[:, None]).sum(axis=0)  # Voigt xx yy zz xy xz yz
                e = (strain[inside] * w[:, None]).sum(axis=0)
                p = -0.5 * (s[0] + s[1])
                q = np.sqrt(0.25 * (s[0] - s[1]) ** 2 + s[3] ** 2)
                row = out[name]
                row["s_over_B"].append(settlement[step] / B)
                row["p"].append(p)
                row["q"].append(q)
                row["volumetric"].append(e[0] + e[1])
                row["deviatoric"].append(2.0 * np.sqrt(0.25 * (e[0] - e[1]) ** 2 + e[3] ** 2))
                row["points"].append(int(inside.sum()))
    finally:
        fields.close()
    return {name: {k: np.array(v) for k, v in row.items()} for name, row in out.items()}


def compare(grains, mpm, p0, ratio_gap, pressure_gap):
    """The two at the grains' rows (the MPM's interpolated in s/B, within its range)."""
    s = grains["s_over_B"]
    keep = (s >= mpm["s_over_B"][0]) & (s <= mpm["s_over_B"][-1])
    s = s[keep]
    g_p, g_q = grains["p"][keep], grains["q"][keep]
    F = np.stack([np.stack([grains["F11"][keep], grains["F12"][keep]], axis=-1),
                  np.stack([grains["F21"][keep], grains["F22"][keep]], axis=-1)], axis=-2)
    g_vol, g_dev = hencky(F)
    m = {k: np.interp(s, mpm["s_over_B"], mpm[k]) for k in ("p", "q", "volumetric",
                                                              "deviatoric")}
    g_ratio, m_ratio = g_q / np.maximum(g_p, 1e-300), m["q"] / np.maximum(m["p"], 1e-300)
    parted = (np.abs(g_ratio - m_ratio) > ratio_gap) | (np.abs(g_p - m["p"]) > pressure_gap * p0)
    first = float(s[np.argmax(parted)]) if parted.any() else None
    rows = {"s_over_B": s, "grains_p_over_p0": g_p / p0, "mpm_p_over_p0": m["p"] / p0,
            "grains_ratio": g_ratio, "mpm_ratio": m_ratio, "grains_volumetric": g_vol,
            "mpm_volumetric": m["volumetric"], "grains_deviatoric": g_dev,
            "mpm_deviatoric": m["deviatoric"]}
    if "cells_volumetric" in grains:
        rows["grains_cells_volumetric"] = grains["cells_volumetric"][keep]
    summary = {"rows": int(len(s)), "parted_at_s_over_B": first,
               "grains_peak_ratio": float(g_ratio.max()) if len(s) else None,
               "mpm_peak_ratio": float(m_ratio.max()) if len(s) else None,
               "mean_abs_d_ratio": float(np.mean(np.abs(g_ratio - m_ratio))) if len(s) else None,
               "mean_abs_dp_over_p0": float(np.mean(np.abs(g_p - m["p"])) / p0) if len(s)
               else None,
               "mpm_points_in_window": int(np.median(mpm["points"])) if len(mpm["points"])
               else 0}
    return rows, summary


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mpm_run", metavar="MPM_RUN", help="an mpm_lig footing run's output folder")
    p.add_argument("case", metavar="CASE.json", help="that run's case")
    p.add_argument("dem_run", metavar="DEM_RUN", help="a direct-DEM run with probes.csv")
    p.add_argument("-o", "--output", required=True, metavar="OUT_DIR")
    p.add_argument("--probes", nargs="+", help="which probes (default: all in probes.csv)")
    p.add_argument("--window", type=cli.positive, metavar="W",
                   help="the windows' side in footing widths (default: the DEM run's, from its "
                   "summary.json)")
    p.add_argument("--ratio-gap", type=cli.positive, default=0.1,
                   help="q/p difference at which the two part (default 0.1)")
    p.add_argument("--pressure-gap", type=cli.positive, default=0.5,
                   help="p difference, in p0, at which the two part (default 0.5)")
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    case = read_json(a.case)
    B, surface = footing_geometry(case, a.case)
    summary = read_json(os.path.join(a.dem_run, "summary.json"))
    p0 = float(summary.get("q_s") or 0.0)
    if not p0 > 0.0:
        raise InputError(f"{a.dem_run}/summary.json: no q_s")
    probes = read_probes(a.dem_run)
    names = a.probes or sorted(probes)
    recorded = summary.get("probes") or {}
    centres = {}
    for name in names:
        if name not in probes:
            raise InputError(f"--probes {name}: {a.dem_run}/probes.csv has "
                             f"{', '.join(sorted(probes))}")
        if name in recorded:
            x, depth = recorded[name]["x_over_B"], recorded[name]["depth_over_B"]
        elif name in PLACES:
            x, depth = PLACES[name]
        else:
            raise InputError(f"probe {name}: its centre is neither recorded in "
                             f"{a.dem_run}/summary.json nor a named place")
        side = a.window or recorded.get(name, {}).get("side_over_B")
        if not side:
            raise InputError(f"{a.dem_run}/summary.json records no window for probe {name} (a "
                             "run before windows were recorded): give --window (footing widths)")
        centres[name] = (x, depth, side)
    out = os.path.abspath(a.output)
    cli.writable_folder(out)
    if os.path.isdir(out) and os.listdir(out):
        raise InputError(f"{out}: not empty (choose a new folder)")
    mpm = mpm_windows(a.mpm_run, B, surface, centres)
    report = {"mpm_run": a.mpm_run, "dem_run": a.dem_run, "B_mpm": B,
              "windows_over_B": {name: centres[name][2] for name in names}, "p0": p0, "ratio_gap": a.ratio_gap, "pressure_gap": a.pressure_gap, "probes": {}}
    tables = {}
    for name in names:
        if not len(mpm[name]["s_over_B"]):
            raise InputError(f"probe {name}: no MPM point in its window (centre "
                             f"{centres[name][:2]} B, side {centres[name][2]:.3g} B)")
        tables[name], report["probes"][name] = compare(probes[name], mpm[name], p0,
                                                       a.ratio_gap, a.pressure_gap)
    os.makedirs(out, exist_ok=True)
    print_table(report)
    with open(os.path.join(out, "mpm_probes.json"), "w") as f:
        json.dump(report, f, indent=1)
    write_rows(os.path.join(out, "mpm_probes.csv"), tables)
    picture(os.path.join(out, "mpm_probes.png"), tables, a.dpi)


def print_table(report):
    print("| probe | grains: largest q/p | MPM: largest q/p | mean abs. diff. of q/p | "
          "mean abs. diff. of p / p0 | parted at s/B | MPM points in the window |")
    print("|---|---|---|---|---|---|---|")
    for name, r in report["probes"].items():
        parted = "-" if r["parted_at_s_over_B"] is None else f"{r['parted_at_s_over_B']:.3f}"
        print(f"| {name} | {r['grains_peak_ratio']:.3f} | {r['mpm_peak_ratio']:.3f} | "
              f"{r['mean_abs_d_ratio']:.3f} | {r['mean_abs_dp_over_p0']:.3f} | {parted} | "
              f"{r['mpm_points_in_window']} |")


def write_rows(path, tables):
    columns = ["s_over_B", "grains_p_over_p0", "mpm_p_over_p0", "grains_ratio", "mpm_ratio",
               "grains_volumetric", "mpm_volumetric", "grains_deviatoric", "mpm_deviatoric"]
    if all("grains_cells_volumetric" in t for t in tables.values()):
        columns.append("grains_cells_volumetric")
    with open(path, "w") as f:
        f.write("probe," + ",".join(columns) + "\n")
        for name, t in tables.items():
            for k in range(len(t["s_over_B"])):
                f.write(name + "," + ",".join("%.6g" % t[c][k] for c in columns) + "\n")


def picture(path, tables, dpi):
    names = list(tables)
    fig, axes = figures.subplots(3, len(names), figsize=(3.6 * len(names), 8.0), squeeze=False)
    for j, name in enumerate(names):
        t = tables[name]
        s = t["s_over_B"]
        for i, (key, label) in enumerate((("ratio", "q / p"), ("p_over_p0", "p / p0"),
                                          ("deviatoric", "deviatoric strain"))):
            axes[i][j].plot(s, t["grains_" + key], "k-", lw=1.4, label="grains")
            axes[i][j].plot(s, t["mpm_" + key], "r-", lw=1.0, label="multiscale")
            axes[i][0].set_ylabel(label)
        axes[0][j].set_title(name, fontsize=10)
        axes[2][j].set_xlabel("s / B")
    axes[0][0].legend(fontsize=7)
    figures.save(fig, path, dpi)


def entry():
    """The command: tools/mpm_probes.py in a checkout, mpm-lig-mpm-probes installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
