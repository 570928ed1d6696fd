#!/usr/bin/python3
"""Checks a finished run of cases/quickstart.json (plane-strain compression of a block of
dem_rve points under a confining traction p0 = 100 kPa).

usage: check_quickstart.py OUTPUT_DIR"""
import csv
import json
import sys

import h5py
import numpy as np

P0 = 1e5                    # confining traction = the packings' consolidation pressure [Pa]
WIDTH, HEIGHT = 0.1, 0.2    # block [m]
POINTS, STEPS, RANKS = 32, 300, 2
CFL = 0.5                   # the case's analysis.time_step.cfl


def main():
    out = sys.argv[1]
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    s = json.load(open(out + "/summary.json"))
    check(s["mpm_steps"] == STEPS, "mpm_steps %s" % s["mpm_steps"])
    check(s["rve_count"] == POINTS and s["material_points"] == POINTS, "rve_count %s" % s["rve_count"])
    check(s["ranks"] == RANKS, "ranks %s" % s["ranks"])
    # At least the minimum of 20 DEM sub-steps per RVE and MPM step.
    check(s["dem_particle_steps"] >= POINTS * 100 * 20 * STEPS,
          "dem_particle_steps %s" % s["dem_particle_steps"])
    split = s["time_split"]
    check(all(v >= 0 for v in split.values()), "negative time in %s" % split)
    check(split["dem"] > split["mpm"], "DEM should dominate: %s" % split)
    per_rank = s["dem_seconds_per_rank"]
    check(len(per_rank) == RANKS and min(per_rank) > 0, "dem_seconds_per_rank %s" % per_rank)
    check(abs(per_rank[0] - split["dem"]) < 1e-9 * split["dem"], "rank 0's DEM time %s" % per_rank)
    imbalance = max(per_rank) * len(per_rank) / sum(per_rank)
    check(abs(s["load_imbalance"] - imbalance) < 1e-12, "load_imbalance %s" % s["load_imbalance"])

    rows = list(csv.DictReader(open(out + "/history.csv")))
    check(len(rows) == STEPS + 1, "history rows %d" % len(rows))
    last = {k: float(v) for k, v in rows[-1].items()}
    # Left roller (bc1) carries the confining traction over the height: p0 H per metre.
    lateral = last["bc1_fx"] / (P0 * HEIGHT)
    check(abs(lateral - 1) < 0.05, "lateral reaction / p0 H = %.4f" % lateral)
    # The top platen (bc2) compresses: vertical stress above p0 and within the range a
    # granular packing with friction 26.6 deg can carry (K_p < 4).
    vertical = -last["bc2_fy"] / (P0 * WIDTH)
    check(1.2 < vertical < 4.0, "top reaction / p0 B = %.4f" % vertical)

    with h5py.File(out + "/results.h5") as f:
        steps = sorted(f.keys())
        check(steps[-1] == "step_%06d" % STEPS, "last field step %s" % steps[-1])
        first = f[steps[0]]["stress"][:]
        stress = f[steps[-1]]["stress"][:]
        check(np.all(np.isfinite(stress)), "non-finite stress")
        # Step 0: every point carries its packing's isotropic consolidation stress.
        check(np.allclose(first[:, :2], -P0, rtol=0.02), "initial stress %s" % first[:, :2])
        check(np.mean(stress[:, 1]) < -1.2 * P0, "mean sigma_yy %.4g" % np.mean(stress[:, 1]))
        # The step set at CFL 0.5 from the packings' moduli at p0 grows against their
        # stiffened waves as (p_max / p0)^(1/6) (Hertz: M ∝ p^(1/3)); the outputs' largest
        # in-plane mean stress bounds the run's from below.
        p_max = max(np.max(-0.5 * (f[k]["stress"][:, 0] + f[k]["stress"][:, 1])) for k in steps)
        lowest = CFL * (p_max / np.max(-0.5 * (first[:, 0] + first[:, 1]))) ** (1 / 6)
        stiffened = s["largest_stiffened_cfl"]
        check(lowest > 1.05 * CFL and 0.99 * lowest <= stiffened <= CFL * 4 ** (1 / 6),
              "largest_stiffened_cfl %.4f (from the outputs at least %.4f)" % (stiffened, lowest))
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print("quickstart ok: lateral %.4f, vertical %.4f (reactions / p0 area), %.3g particle-steps"
          % (lateral, vertical, s["dem_particle_steps"]))


if __name__ == "__main__":
    main()
