#!/usr/bin/python3
"""A drained biaxial test replayed with its volume left free gives back its own dilatancy.

usage: replay_free_volume.py MPM_LIG BIAXIAL_CASE WORK_DIR

The drained biaxial test (BIAXIAL_CASE, a small 2D packing, taken to 8 % axial strain in steps
of 0.1 %, over which its volume changes by several 1e-3) runs first. Its path is then
written as a recorded path with the volume taken out (F = diag(e^(e_xx - v/2), e^(e_yy - v/2)),
v = e_xx + e_yy: det F = 1 on every row) and the test's own mean stress as the column p, and
replayed on the same packing (its prepared.restart) twice:
- "volume": "free": the servo holds p at every row within 2 % (the tolerance 0.5 % plus the
  packing's noise) and the packing's volume follows the drained test's: the root mean square
  of their difference over the path below 0.6 times that of the drained test's volumetric
  strain itself, which is at least 2e-3 (the premise). A 100-disc packing's volume is noisy
  (the drained test's swings by 3e-3 within 1 % of axial strain), so the path, not one row,
  is compared;
- "volume": "recorded" (the same file, p ignored): the volumetric strain stays 0, whose
  difference is the drained test's own: the check above can fail.
"""
import json
import math
import os
import shutil
import sys

from element_runs import element_test


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values))


def numbers(rows):
    return [{k: float(v) for k, v in r.items()} for r in rows]


def main():
    mpm_lig, base_file, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    base = json.load(open(base_file))
    assert base["analysis"]["test"] == "drained_biaxial" and base["rve"]["dimension"] == 2
    base["analysis"].update({"axial_strain": 0.08, "strain_increment": 0.001})
    rows, _, drained_out = element_test(mpm_lig, base, work, "drained")
    drained = numbers(rows)

    table = os.path.join(work, "isochoric.csv")
    with open(table, "w") as f:
        f.write("# the drained test's path with its volume taken out, and its mean stress\n")
        f.write("time,F11,F12,F21,F22,p\n")
        for k, r in enumerate(drained):
            v = r["e_xx"] + r["e_yy"]
            f.write(f"{repr(float(k))},{repr(math.exp(r['e_xx'] - v / 2))},0,0,"
                    f"{repr(math.exp(r['e_yy'] - v / 2))},{repr(r['p'])}\n")
    rve = dict(base["rve"])
    rve.pop("preparation", None)
    rve["restart_file"] = os.path.join(drained_out, "prepared.restart")

    def replay(volume):
        case = {"title": f"the drained test replayed, volume {volume}", "rve": rve,
                "analysis": {"type": "element_test", "test": "recorded_path",
                             "path": {"csv": table, "volume": volume}, "save_restart": False}}
        return numbers(element_test(mpm_lig, case, work, volume)[0])

    free, recorded = replay("free"), replay("recorded")
    failures = []
    drained_vol = [r["e_vol"] for r in drained]
    scale = rms(drained_vol)
    if not scale >= 2e-3:
        failures.append(f"premise: the drained test's volumetric strain ({scale:.2e} rms) is "
                        "below 2e-3")
    if len(free) != len(drained):
        failures.append(f"{len(free)} rows replayed, {len(drained)} in the drained test")
    worst = max(abs(a["p"] - b["p"]) / b["p"] for a, b in zip(free, drained))
    if worst > 0.02:
        failures.append(f"free volume: p off the drained test's by {worst:.3%} somewhere")
    off_free = rms([a["e_vol"] - b for a, b in zip(free, drained_vol)])
    if not off_free <= 0.6 * scale:
        failures.append(f"free volume: e_vol off the drained test's by {off_free:.2e} rms, "
                        f"more than 0.6 x {scale:.2e}")
    off_fixed = rms([a["e_vol"] - b for a, b in zip(recorded, drained_vol)])
    if max(abs(r["e_vol"]) for r in recorded) > 1e-9 or off_fixed <= 0.6 * scale:
        failures.append(f"recorded volume: e_vol not 0, or within 0.6 x {scale:.2e} rms of the "
                        f"drained test's ({off_fixed:.2e})")
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print(f"{len(free)} rows: p within {worst:.2%} of the drained test's; e_vol off the drained "
          f"test's by {off_free:.2e} rms free, {off_fixed:.2e} recorded (its own {scale:.2e})")


main()
