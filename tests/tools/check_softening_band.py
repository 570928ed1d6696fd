#!/usr/bin/python3
"""Checks of tools/softening_band.py: the internal length regularises a softening layer.

usage: check_softening_band.py WORK MPM_LIG

- bad input: exit 2, named, on one line, the output folder not created;
- the layer on h = L/2, L/4, L/8 (L = 0.1 m): without an internal length the band is one cell
  on every mesh (its width follows h); with the second gradient it is L wide within 20 % on
  h = L/4 and L/8 and the two agree within 20 % (the internal-length issue's target); and
  after the peak the layer with the length carries more than without (the band dissipates
  over L, not over one cell); history.csv has the gradient energy with the second gradient
  only, a part of the top's work. The table's numbers for all three meshes are in
  docs/methods.md §7;
- with one point per cell and the fit's residual energy (--residual-weights 1) the band is
  still L wide within 20 % on L/4 and L/8: the residual leaves a smooth band's width alone.
"""
import json
import os
import shutil
import sys

from checking import check, finish
from checking import tool as run_tool


def tool(args):
    return run_tool("softening_band.py", args)


def main():
    work, mpm_lig = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for args, named in ((["--length", "0.3"], "--length"),
                        (["--length", "0.07", "--refinements", "3"], "--refinements 3"),
                        (["--weights", "3"], "--weights"),
                        (["--mpm-lig", os.path.join(work, "none")], "mpm_lig executable")):
        out = os.path.join(work, "bad" + args[0])
        code, _, err = tool(["-o", out, "--mpm-lig", mpm_lig] + args
                            if "--mpm-lig" not in args else ["-o", out] + args)
        check(code == 2 and named in err and err.count("\n") == 1 and not os.path.exists(out),
              f"bad input {args}: exit 2 naming it ({code}: {err.strip()})")

    out = os.path.join(work, "layers")
    code, stdout, err = tool(["-o", out, "--mpm-lig", mpm_lig])
    check(code == 0, f"three meshes with and without the length: exit 0 ({code}: {err.strip()})")
    if code != 0:
        return
    print(stdout)
    report = json.load(open(os.path.join(out, "softening_band.json")))
    runs, length = report["runs"], report["length"]
    for n in (2, 4, 8):
        r = runs[f"local_h{n}"]
        check(abs(r["band_width"] / r["cell"] - 1.0) < 0.1,
              f"without the length the band is one cell at h = L/{n} "
              f"({r['band_width'] / r['cell']:.2f} cells)")
    widths = {}
    for n in (4, 8):
        r = runs[f"second_gradient_h{n}"]
        widths[n] = r["band_width"]
        check(abs(r["band_width"] / length - 1.0) < 0.2,
              f"with the length the band is L wide within 20 % at h = L/{n} "
              f"({r['band_width'] / length:.2f} L)")
        check(r["mean_stress_post_peak"] > runs[f"local_h{n}"]["mean_stress_post_peak"],
              f"h = L/{n}: more stress after the peak with the length "
              f"({r['mean_stress_post_peak'] / 1e3:.1f} against "
              f"{runs[f'local_h{n}']['mean_stress_post_peak'] / 1e3:.1f} kPa)")
    for key, r in runs.items():
        share = r["gradient_energy_share"]
        if r["variant"] == "second_gradient":
            check(share is not None and 0.0 < share < 1.0,
                  f"{key}: the gradient energy at the end is part of the top's work ({share})")
        else:
            check(share is None, f"{key}: no gradient energy without the second gradient")
    check(abs(widths[4] / widths[8] - 1.0) < 0.2,
          f"the band's width at h = L/4 and L/8 within 20 % ({widths[4]:.4f}, {widths[8]:.4f} m)")
    check(os.path.getsize(os.path.join(out, "softening_band.png")) > 10000, "picture written")

    out = os.path.join(work, "one_point")
    code, stdout, err = tool(["-o", out, "--mpm-lig", mpm_lig, "--refinements", "4", "8",
                              "--points-per-cell", "1", "--residual-weights", "1"])
    check(code == 0, f"one point per cell with the residual: exit 0 ({code}: {err.strip()})")
    if code != 0:
        return
    print(stdout)
    runs = json.load(open(os.path.join(out, "softening_band.json")))["runs"]
    for n in (4, 8):
        r = runs[f"residual_b1_h{n}"]
        check(abs(r["band_width"] / length - 1.0) < 0.2,
              f"one point per cell, with the residual, the band is L wide within 20 % at "
              f"h = L/{n} ({r['band_width'] / length:.2f} L)")
        check(r["gradient_energy_share"] is not None and 0.0 < r["gradient_energy_share"] < 1.0,
              f"h = L/{n}: the residual's run stores gradient energy")


if __name__ == "__main__":
    main()
    finish()
