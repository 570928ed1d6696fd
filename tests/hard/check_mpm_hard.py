#!/usr/bin/python3
"""Checks of the MPM hard cases from their outputs (history.csv, results.h5, summary.json).
Prints one table row: case | criterion | measured margin; exits 1 on a failed criterion.

usage: check_mpm_hard.py extension OUTPUT_DIR
       check_mpm_hard.py large_shear OUTPUT_DIR
       check_mpm_hard.py velocity_step OUTPUT_DIR
       check_mpm_hard.py footing_deep OUTPUT_DIR
       check_mpm_hard.py free_surface OUTPUT_DIR
       check_mpm_hard.py rotation STILL_TWIN_OUTPUT_DIR OUTPUT_DIR"""
import csv
import math
import sys

import h5py
import numpy as np


def history(out):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(out + "/history.csv"))]


def last_step(out):
    with h5py.File(out + "/results.h5") as f:
        name = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
        g = f[name]
        return {k: g[k][()] for k in g.keys()}


def finite_everywhere(out):
    with h5py.File(out + "/results.h5") as f:
        for name in f:
            if name.startswith("step_"):
                for k, d in f[name].items():
                    if np.issubdtype(d.dtype, np.floating) and not np.all(np.isfinite(d[()])):
                        return False
    return True


def extension(out, failures):
    """Pulled to det F = 1.5: stress -> 0 (below 1 % of the initial p') without NaN."""
    s = last_step(out)
    with h5py.File(out + "/results.h5") as f:
        first = f[sorted(k for k in f.keys() if k.startswith("step_"))[0]]
        p0 = -np.mean(first["stress"][:, :2].sum(axis=1) / 2)
        det = s["volume"] / first["volume"][()]
    stress = np.abs(s["stress"]).max()
    if not finite_everywhere(out):
        failures.append("non-finite output")
    if det.min() < 1.5 - 1e-3:
        failures.append("det F reached only %.4f" % det.min())
    if stress > 1e-2 * p0:
        failures.append("stress %.3g Pa left at det F = 1.5 (p0' %.3g Pa)" % (stress, p0))
    return ("extension to det F = 1.5 | |sigma| < 1e-2 p0', no NaN, no lost grains | "
            "det F %.4f, max |sigma| %.2e p0'" % (det.min(), stress / p0))


def large_shear(out, failures):
    """Monotonic simple shear to gamma = 5 at constant volume. A jump at a cell-basis reduction
    would be a one-step spike: the step's stress change (max of |d tau|, |d p'|) against the
    median change of the 50 steps around it. The largest spike after gamma = 0.45 (where the
    reductions begin) must stay within twice the largest one before (the RVE's own
    fluctuation, 0.05 < gamma < 0.45)."""
    rows = history(out)
    gamma = np.array([r["shear_strain"] for r in rows])
    tau = np.array([r["shear_stress"] for r in rows])
    p = np.array([r["mean_stress"] for r in rows])
    if not (np.all(np.isfinite(tau)) and np.all(np.isfinite(p))):
        failures.append("non-finite stress")
    jump = np.maximum(np.abs(np.diff(tau)), np.abs(np.diff(p)))
    spike = np.array([jump[i] / np.median(jump[max(0, i - 25):i + 26]) for i in range(len(jump))])
    g = gamma[1:]
    early = spike[(g > 0.05) & (g < 0.45)].max()
    late = spike[g >= 0.45].max()
    if gamma[-1] < 5.0 - 1e-6:
        failures.append("gamma reached only %.3f" % gamma[-1])
    if late > 2.0 * early:
        failures.append("spike %.2f after gamma 0.45 > 2 x %.2f before" % (late, early))
    return ("simple shear to gamma = 500 %% | largest one-step spike after the first reduction "
            "<= 2 x before | gamma %.2f, spikes %.2f after vs %.2f before (ratio %.2f of 2)"
            % (gamma[-1], late, early, late / early))


def rotation(out, still):
    """Turned rigidly by 360 degrees, against its twin held still (`still`, the same packings
    over the same updates: a packing at rest drifts by itself, about 1 % of p0' here): at every
    output (every 45 degrees) each point's stress is the twin's turned by the angle so far,
    within 1 % of p0' in every component and in p', q; the volume stays (no spurious stretch)."""
    failures = []
    with h5py.File(out + "/results.h5") as f, h5py.File(still + "/results.h5") as g:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        v0 = f[steps[0]]["volume"][()]
        s0 = g[steps[0]]["stress"][()]
        p0 = -np.mean(s0[:, :2].sum(axis=1) / 2)
        total = __import__("json").load(open(out + "/summary.json"))["mpm_steps"]
        worst_tensor = worst_invariant = worst_volume = drift = 0.0
        for name in steps[1:]:
            angle = 2 * math.pi * int(name[5:]) / total
            c, s = math.cos(angle), math.sin(angle)
            r = np.array([[c, -s], [s, c]])
            for k in range(len(s0)):
                at_rest = tensor2(g[name]["stress"][k])
                turned = tensor2(f[name]["stress"][k])
                worst_tensor = max(worst_tensor, np.abs(turned - r @ at_rest @ r.T).max() / p0)
                a, b = invariants(turned), invariants(at_rest)
                worst_invariant = max(worst_invariant, abs(a[0] - b[0]) / p0,
                                      abs(a[1] - b[1]) / p0)
                drift = max(drift, np.abs(at_rest - tensor2(s0[k])).max() / p0)
            worst_volume = max(worst_volume, np.abs(f[name]["volume"][()] / v0 - 1).max())
        turned_degrees = 360 * int(steps[-1][5:]) / total
    if not (finite_everywhere(out) and finite_everywhere(still)):
        failures.append("non-finite output")
    if turned_degrees < 360 - 1e-9:
        failures.append("turned only %.1f degrees" % turned_degrees)
    if worst_tensor > 1e-2 or worst_invariant > 1e-2:
        failures.append("stress off its twin's turned value by %.3g p0' (invariants %.3g p0')"
                        % (worst_tensor, worst_invariant))
    if worst_volume > 1e-9:
        failures.append("volume changed by %.3g" % worst_volume)
    row = ("rigid rotation by 360 degrees | sigma = R sigma_still R^T and p', q within 1e-2 p0' "
           "every 45 degrees, volume kept | turned %.0f degrees, max |sigma - R sigma_still R^T| "
           "%.1e p0', invariants %.1e p0', volume %.1e (the twin at rest drifts %.1e p0')"
           % (turned_degrees, worst_tensor, worst_invariant, worst_volume, drift))
    return row, failures


def velocity_step(out, failures):
    """Pressed from rest, then the top velocity reversed twice in one step each: no NaN, no
    overshoot (after the first reversal no stress component exceeds 1.05 x the largest before
    it: the body unloads), and the sub-steps follow the rate: above the RVE's min (10) at the
    steps' rate, and not at the max (400)."""
    with h5py.File(out + "/results.h5") as f:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        number = [int(n[5:]) for n in steps]
        stress = np.array([np.abs(f[n]["stress"][()]).max() for n in steps])
        substeps = max(f[n]["dem_substeps_m1"][()].max() for n in steps)
    reversal = number.index(50)  # t = T/4 of the 0.04 s square wave, 2e-4 s steps
    before, after = stress[:reversal + 1].max(), stress[reversal + 1:].max()
    if not finite_everywhere(out):
        failures.append("non-finite output")
    if after > 1.05 * before:
        failures.append("stress overshoots after the reversal: %.4g > 1.05 x %.4g" % (after, before))
    if not 10 < substeps < 400:
        failures.append("largest sub-step count %d: not following the rate between min 10 and "
                        "max 400" % substeps)
    return ("velocity steps (0 to 10 cm/s, reversals of 20 cm/s) | no NaN, max |sigma| after the "
            "first reversal <= 1.05 x before, largest sub-step count between min 10 and max 400 | "
            "after/before %.3f, sub-steps <= %d" % (after / before, substeps))


def footing_deep(out, failures):
    """A tiny DEM footing to d/B = 1.5: reached, no NaN, every point kept and inside the mesh
    (0.3 x 0.45 m), the bearing pressure positive and finite throughout."""
    rows = history(out)
    depth = rows[-1]["settlement"] / 0.1
    q = np.array([r["q"] for r in rows[1:]])
    with h5py.File(out + "/results.h5") as f:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        counts = {len(f[n]["positions"]) for n in steps}
        x = np.concatenate([f[n]["positions"][()] for n in steps])
    inside = (x[:, 0] >= 0).all() and (x[:, 0] <= 0.3).all() and (x[:, 1] >= 0).all() and \
        (x[:, 1] <= 0.45).all()
    if not finite_everywhere(out) or not np.all(np.isfinite(q)):
        failures.append("non-finite output")
    if depth < 1.5 - 1e-9:
        failures.append("d/B reached only %.3f" % depth)
    if len(counts) != 1 or not inside:
        failures.append("points lost or outside the mesh: counts %s" % sorted(counts))
    if q.min() <= 0:
        failures.append("bearing pressure %.3g <= 0" % q.min())
    return ("tiny DEM footing to d/B = 1.5 | reached, no NaN, no point lost or outside, q > 0 | "
            "d/B %.3f, %d points throughout, q %.0f-%.0f kPa"
            % (depth, counts.pop(), q.min() / 1e3, q.max() / 1e3))


def free_surface(out, failures):
    """A column prepared at p0' with a free top, under gravity: from the second half of the run
    on, no stress component above 5 % of p0' (its own weight is 1-2 %); no NaN; the kinetic
    energy at the end below 1 % of its peak (at rest again)."""
    with h5py.File(out + "/results.h5") as f:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        s0 = f[steps[0]]["stress"][()]
        p0 = -np.mean(s0[:, :2].sum(axis=1) / 2)
        late = [n for n in steps if int(n[5:]) >= int(steps[-1][5:]) // 2]
        stress = max(np.abs(f[n]["stress"][()]).max() for n in late) / p0
    energy = np.array([r["kinetic_energy"] for r in history(out)])
    if not finite_everywhere(out):
        failures.append("non-finite output")
    if stress > 0.05:
        failures.append("stress %.3g p0' left after the unloading" % stress)
    if energy[-1] > 0.01 * energy.max():
        failures.append("still moving: kinetic energy %.3g of its peak" % (energy[-1] / energy.max()))
    return ("free surface unloaded to zero stress | |sigma| <= 5e-2 p0' in the second half, no "
            "NaN, kinetic energy at the end < 1 %% of its peak | max |sigma| %.1e p0', kinetic "
            "energy %.1e of its peak" % (stress, energy[-1] / energy.max()))


def tensor2(voigt_or_matrix):
    """The in-plane 2 x 2 block of a stored stress (3 x 3, or Voigt xx yy zz xy ...)."""
    a = np.asarray(voigt_or_matrix)
    if a.shape == (3, 3):
        return a[:2, :2]
    return np.array([[a[0], a[3]], [a[3], a[1]]])


def invariants(sig):
    """Mean pressure p' and deviatoric magnitude q of a 2D stress (as the history's columns)."""
    p = -np.trace(sig) / 2
    dev = sig + p * np.eye(2)
    return p, math.sqrt(0.5 * np.sum(dev * dev))


def main():
    kind, out = sys.argv[1], sys.argv[2]
    failures = []
    if kind == "rotation":
        row, failures = rotation(sys.argv[3], out)  # rotation STILL_DIR OUTPUT_DIR
    else:
        row = {"extension": extension, "large_shear": large_shear,
               "velocity_step": velocity_step, "footing_deep": footing_deep,
               "free_surface": free_surface}[kind](out, failures)
    print(row)
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


main()
