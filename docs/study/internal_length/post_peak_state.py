#!/usr/bin/python3
"""Where the footing's post-peak load comes from, mesh against mesh: for each mpm_lig run of the
footing study (results.h5), the soil's state after the peak.

usage: post_peak_state.py MPM_RUN:LABEL ... [--json OUT] [--since 0.4] [--to 0.6]
       [--at 0.5 0.6 0.8] [--speed 0.5] [--width 0.2] [--surface 0.6]

- the slipping zone: the area (current volumes) where the strain gained from s/B = --since to
  --to (eps_q of the difference of the Hencky strains) exceeds 0.05 ... 0.3, and the
  volume-weighted sum of that strain;
- at each --at: the volume-weighted mean pressure p = -(s_xx + s_yy)/2, vertical stress and
  mobilised ratio t/p (t the in-plane Mohr radius) of the points under the footing (x < B/2,
  within 0.1 m below its base) and beside it (B/2 < x < 1.5 B, above 0.1 m below its base).
"""
import argparse
import json
import os

import h5py
import numpy as np

from fields_beside_grains import equivalent_strain, nearest_step

THRESHOLDS = (0.05, 0.1, 0.15, 0.2, 0.3)


def nearest(steps, s):
    return min(steps, key=lambda ks: abs(ks[1] - s))


def slipping_zone(f, steps, since, to):
    (ka, sa), (kb, sb) = nearest(steps, since), nearest(steps, to)
    gained = equivalent_strain(f[kb]["strain"][()] - f[ka]["strain"][()])
    volume = f[kb]["volume"][()].ravel()
    return {"from": sa, "to": sb,
            "area_above": {str(t): float(volume[gained > t].sum()) for t in THRESHOLDS},
            "volume_weighted_sum": float(np.sum(volume * gained))}


def regions(f, steps, s, width, surface):
    key, s_out = nearest(steps, s)
    g = f[key]
    x, stress, volume = g["positions"][:, :2], g["stress"][()], g["volume"][()].ravel()
    p = -(stress[:, 0] + stress[:, 1]) / 2
    t = np.sqrt(((stress[:, 0] - stress[:, 1]) / 2) ** 2 + stress[:, 3] ** 2)
    base = surface - s_out * width
    half = width / 2
    masks = {"under": (x[:, 0] < half) & (x[:, 1] > base - 0.1) & (x[:, 1] < base),
             "beside": (x[:, 0] > half) & (x[:, 0] < 3 * half) & (x[:, 1] > base - 0.1)}
    out = {"s_over_B": s_out}
    for name, m in masks.items():
        w = volume[m]
        out[name] = {"points": int(m.sum()),
                     "p_kPa": float(np.average(p[m], weights=w) / 1e3),
                     "vertical_stress_kPa": float(np.average(-stress[m, 1], weights=w) / 1e3),
                     "ratio_t_over_p": float(np.average(t[m] / np.maximum(p[m], 1.0), weights=w))}
    return out


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("runs", nargs="+", metavar="MPM_RUN:LABEL")
    a.add_argument("--json")
    a.add_argument("--since", type=float, default=0.4)
    a.add_argument("--to", type=float, default=0.6)
    a.add_argument("--at", type=float, nargs="+", default=[0.5, 0.6, 0.8])
    a.add_argument("--speed", type=float, default=0.5)
    a.add_argument("--width", type=float, default=0.2)
    a.add_argument("--surface", type=float, default=0.6)
    args = a.parse_args()
    report = {}
    for item in args.runs:
        run, _, label = item.partition(":")
        label = label or os.path.basename(run)
        path = os.path.join(run, "results.h5")
        steps = nearest_step(path, lambda attrs: args.speed * attrs["time"] / args.width)
        with h5py.File(path, "r") as f:
            zone = slipping_zone(f, steps, args.since, args.to)
            states = [regions(f, steps, s, args.width, args.surface) for s in args.at]
        report[label] = {"slipping_zone": zone, "regions": states}
        areas = " ".join(f"{v:.4f}" for v in zone["area_above"].values())
        print(f"{label}: strain gained s/B {zone['from']:.2f}-{zone['to']:.2f}, area above "
              f"{'/'.join(map(str, THRESHOLDS))}: {areas} m2, sum V eps_q "
              f"{zone['volume_weighted_sum']:.5f} m2")
        for st in states:
            print(f"  s/B {st['s_over_B']:.2f} " + "  ".join(
                f"{name}: n {r['points']} p {r['p_kPa']:.0f} kPa t/p {r['ratio_t_over_p']:.3f}"
                for name, r in ((n, st[n]) for n in ("under", "beside"))))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
