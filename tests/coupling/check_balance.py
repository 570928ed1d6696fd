#!/usr/bin/python3
"""Checks the cost record and the stepping figures of runs of a dem_rve case against each
other: the record's measured steps add up to summary.json's particle-steps, its owners change
as often as summary.json counts migrations (from the dealt start, RVE i on group i mod groups),
and the stepping efficiencies recomputed from it are the summary's.

usage: check_balance.py DIR... [--expect-migrations] [--after UPDATE]
       check_balance.py --same-decisions REFERENCE OTHER
--expect-migrations: every run on more than one rank group moved RVEs (after UPDATE, if given).
--same-decisions: the two records hold the same predictions, steps and owners, row by row
(a resumed run made the balancer's decisions of the uninterrupted one)."""
import argparse
import glob
import json
import sys

import h5py
import numpy as np


def record(folder):
    files = glob.glob(folder + "/packings/m*/cost_record.h5")
    if len(files) != 1:
        sys.exit("%s: expected one packings/m*/cost_record.h5, found %s" % (folder, files))
    with h5py.File(files[0], "r") as f:
        r = {k: f[k][()] for k in f}
        r.update({k: float(v) for k, v in f.attrs.items()})
    return r


def efficiency(work, group, groups):
    total, makespan = 0.0, 0.0
    for row in range(work.shape[0]):
        loads = np.bincount(group[row], weights=work[row], minlength=groups)
        total += loads.sum()
        makespan += loads.max()
    return total / (groups * makespan) if makespan > 0 else 1.0


def check(folder, expect_migrations, after):
    failures = []
    s = json.load(open(folder + "/summary.json"))
    r = record(folder)
    rows, points = r["measured_steps"].shape
    if rows == 0 or list(r["update"]) != list(range(1, rows + 1)):
        failures.append("updates %s are not 1..%d" % (r["update"][:5], rows))
    grains = r["grains"]
    particle_steps = r["measured_steps"].sum(dtype=np.float64) * grains
    if particle_steps != s["dem_particle_steps"]:
        failures.append("record %.17g particle-steps, summary %.17g"
                        % (particle_steps, s["dem_particle_steps"]))
    groups = int(r["groups"][0])
    st = s["stepping"]
    if st["rank_groups"] != groups or groups != s["ranks"]:
        failures.append("groups %d, summary %s, ranks %s" % (groups, st["rank_groups"], s["ranks"]))
    dealt = np.arange(points) % groups
    owners = np.vstack([dealt, r["group"]])
    moves = (owners[1:] != owners[:-1]).sum(axis=1)
    if moves.sum() != st["migrations"]:
        failures.append("record %d owner changes, summary %s migrations"
                        % (moves.sum(), st["migrations"]))
    if expect_migrations and groups > 1 and moves[after:].sum() == 0:
        failures.append("no RVE moved after update %d on %d groups" % (after, groups))
    ran = r["measured_steps"] > 0
    for name, steps in (("efficiency", r["measured_steps"]),
                        ("efficiency_predicted", r["predicted_steps"])):
        work = np.where(ran | (steps > 0), (steps + r["update_cost_steps"]) * grains, 0.0)
        e = efficiency(work, r["group"], groups)
        if abs(e - st[name]) > 1e-9:
            failures.append("%s from the record %.12g, summary %.12g" % (name, e, st[name]))
    if not 0.0 < st["efficiency_bound"] <= 1.0 or st["efficiency"] > st["efficiency_bound"] + 1e-12:
        failures.append("efficiency %s above its bound %s" % (st["efficiency"], st["efficiency_bound"]))
    print("%s: %d groups, %d migrations, efficiency %.4f (predicted %.4f, bound %.4f)"
          % (folder, groups, st["migrations"], st["efficiency"], st["efficiency_predicted"],
             st["efficiency_bound"]))
    return ["%s: %s" % (folder, f) for f in failures]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dirs", nargs="+")
    p.add_argument("--expect-migrations", action="store_true")
    p.add_argument("--after", type=int, default=0)
    p.add_argument("--same-decisions", action="store_true")
    a = p.parse_args()
    failures = []
    if a.same_decisions:
        ref, other = (record(d) for d in a.dirs)
        for k in ("update", "groups", "predicted_steps", "measured_steps", "group"):
            if ref[k].shape != other[k].shape or not np.array_equal(ref[k], other[k]):
                failures.append("%s differs between %s and %s" % (k, a.dirs[0], a.dirs[1]))
    else:
        for d in a.dirs:
            failures += check(d, a.expect_migrations, a.after)
    if failures:
        sys.exit("\n".join(failures))
    print("cost records consistent")


if __name__ == "__main__":
    main()
