"""Stepping efficiency and wall time of a dem_rve run projected to other rank counts, from the
run's cost record (<output>/packings/m<id>/cost_record.h5, docs/outputs.md).

For each rank count R (one rank per RVE) and each step of the record, the points' measured
work in particle-steps, (DEM steps + update_cost_steps) x grains, is laid out on R groups:
  round_robin  point i on group i mod R (the dealt start; what runs without the balancer)
  balancer     the run's balancer replayed: moves planned from the predicted costs before each
               step (src/coupling/rve_balance.cpp, same rule: a cost's excess over the sub-step
               floor kept at --persistence per update), their cost added to the step;
               equal rank speeds (a run with balance.rank_speed "measured" is not replayed)
  lpt          longest processing time first on the step's own measured costs (a reference)
  bound        max(costliest point, mean load): no assignment does better
Stepping efficiency = sum work / (R x sum_steps busiest group's work). Wall time per step =
busiest work / rate + gather(R, points), the rate (particle-steps/s per core, fixed cost
included) from the record's own measured seconds unless --rate is given, the gather from
bench_allgather's JSON (--gather; fitted as a log2(R) + b x bytes) or defaults stated in the
output.

usage: scaling_model.py RECORD_OR_OUTPUT [--ranks 2,4,...] [--tile K] [--gather FILE]
       [--rate R] [--threshold T --horizon H --move-cost C --persistence P] [--update-cost U]
       [--json FILE] [--plot FILE]
--tile K repeats every point K times in a row (neighbours of the same cost, as in a K times
finer numbering of the same field): a crude stand-in for a larger case.
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py")

import bisect  # noqa: E402
import glob  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402

DEFAULT_GATHER = {"latency": 5e-6, "per_byte": 1e-9, "source": "assumed (no --gather)"}
WIDTH_BYTES = 11 * 8  # doubles per point in the exchange


def read_record(path):
    if os.path.isdir(path):
        found = sorted(glob.glob(os.path.join(path, "packings", "m*", "cost_record.h5")))
        if not found:
            raise InputError(f"{path}: no packings/m*/cost_record.h5 in this folder")
        path = found[0]
    elif not os.path.isfile(path):
        raise InputError(f"{path}: no such cost record or output folder")
    try:
        with h5py.File(path, "r") as f:
            r = {k: np.asarray(f[k][()]) for k in
                 ("predicted_steps", "measured_steps", "seconds", "group", "groups")}
            r["grains"] = float(f.attrs["grains"])
            r["update_cost_steps"] = float(f.attrs["update_cost_steps"])
            # Records before the attribute: the fewest sub-steps any update took.
            r["floor_steps"] = (float(f.attrs["floor_steps"]) if "floor_steps" in f.attrs
                                else None)
    except (OSError, KeyError, ValueError, TypeError) as e:
        raise InputError(f"{path}: not a cost record: {e}") from None
    if r["measured_steps"].ndim != 2 or r["measured_steps"].shape[0] == 0:
        raise InputError(f"{path}: the cost record holds no rows")
    if r["predicted_steps"].shape != r["measured_steps"].shape:
        raise InputError(f"{path}: predicted_steps {r['predicted_steps'].shape} and "
                         f"measured_steps {r['measured_steps'].shape} differ in shape")
    if r["floor_steps"] is None:
        ran = r["measured_steps"][r["measured_steps"] > 0]
        r["floor_steps"] = float(ran.min()) if ran.size else 0.0
    r["file"] = path
    return r


def work_of(steps, ran, grains, update_cost):
    return np.where(ran, (steps + update_cost) * grains, 0.0)


def loads(cost, owner, groups):
    return np.bincount(owner, weights=cost, minlength=groups)


def busiest_migration(new, owner, groups):
    """Moves run in parallel: their time is that of the group with the most moves in or out."""
    moved = new != owner
    if not moved.any():
        return 0
    touched = np.bincount(owner[moved], minlength=groups) + np.bincount(new[moved], minlength=groups)
    return int(touched.max())


def horizon_costs(cost, floor, persistence, horizon):
    """The costs of the horizon's updates and their weights (rve_balance.cpp HorizonLoads):
    floor + rho^k (cost - floor) while the excess is above a thousandth, then the floor."""
    if floor is None or persistence >= 1 or not (floor < cost).any():
        return cost[None, :], np.array([float(horizon)])
    floor = np.minimum(floor, cost)
    exact = 1 if persistence <= 0 else int(math.ceil(math.log(1e-3) / math.log(persistence)))
    exact = min(exact, horizon)
    shares, factor = [], 1.0
    for _ in range(exact):
        shares.append(factor)
        factor *= persistence
    weights = [1.0] * exact
    if exact < horizon:
        shares.append(0.0)
        weights.append(float(horizon - exact))
    rows = [cost if k == 0 else floor + shares[k] * (cost - floor) for k in range(len(shares))]
    return np.stack(rows), np.array(weights)


def plan_moves(cost, owner, groups, threshold, horizon, move_cost, floor=None, persistence=1.0):
    """The balancer's rule (rve_balance.cpp plan_moves): returns the new owners."""
    load = loads(cost, owner, groups)
    total = load.sum()
    before = load.max()
    if groups < 2 or total <= 0 or before <= (1 + threshold) * total / groups:
        return owner
    future, weights = horizon_costs(cost, floor, persistence, horizon)
    future_load = np.stack([loads(row, owner, groups) for row in future])
    future_before = future_load.max(axis=1)
    members = [list(np.flatnonzero(owner == g)) for g in range(groups)]
    trial = owner.copy()
    touched = np.zeros(groups, dtype=np.int64)
    sequence, best_prefix, best_value = [], 0, 0.0
    for _ in range(2 * len(cost) + 2):
        src, dst = int(np.argmax(load)), int(np.argmin(load))
        diff = load[src] - load[dst]
        candidates = [i for i in members[src] if 0 < cost[i] < diff]
        if not candidates:
            break
        pick = min(candidates, key=lambda i: (abs(cost[i] - 0.5 * diff), i))
        for g, sign in ((trial[pick], -1), (dst, +1)):
            if g != owner[pick]:
                touched[owner[pick]] += sign
                touched[g] += sign
        trial[pick] = dst
        members[src].remove(pick)
        bisect.insort(members[dst], pick)
        load[src] -= cost[pick]
        load[dst] += cost[pick]
        future_load[:, src] -= future[:, pick]
        future_load[:, dst] += future[:, pick]
        sequence.append((pick, dst))
        gain = (weights * (future_before - future_load.max(axis=1))).sum()
        value = gain - move_cost * touched.max()
        if value > best_value:
            best_value, best_prefix = value, len(sequence)
    best = owner.copy()
    for pick, dst in sequence[:best_prefix]:
        best[pick] = dst
    return best


def lpt(cost, groups):
    order = np.argsort(-cost, kind="stable")
    load = np.zeros(groups)
    owner = np.zeros(len(cost), dtype=np.int64)
    for i in order:
        g = int(np.argmin(load))
        owner[i] = g
        load[g] += cost[i]
    return owner


def project(r, ranks, tile, threshold, horizon, move_cost_steps, persistence=1.0):
    grains, u = r["grains"], r["update_cost_steps"]
    measured = np.repeat(r["measured_steps"].astype(float), tile, axis=1)
    predicted = np.repeat(r["predicted_steps"].astype(float), tile, axis=1)
    ran = measured > 0
    work = work_of(measured, ran, grains, u)
    pred = work_of(predicted, ran | (predicted > 0), grains, u)
    points = work.shape[1]
    move_cost = move_cost_steps * grains
    floor = np.full_like(pred, (r["floor_steps"] + u) * grains)  # capped at each cost by the plan
    dealt = np.arange(points) % ranks
    total = work.sum()
    out = {"round_robin": 0.0, "balancer": 0.0, "lpt": 0.0, "bound": 0.0}
    owner = dealt.copy()
    migrations = 0
    for s in range(work.shape[0]):
        out["round_robin"] += loads(work[s], dealt, ranks).max()
        out["bound"] += max(work[s].max(), work[s].sum() / ranks)
        if ranks <= points:
            out["lpt"] += loads(work[s], lpt(work[s], ranks), ranks).max()
        else:
            out["lpt"] += work[s].max()
        previous = owner
        new = plan_moves(pred[s], owner, ranks, threshold, horizon, move_cost, floor[s],
                         persistence)
        moved = int(np.count_nonzero(new != owner))
        migrations += moved
        owner = new
        # The moves run in parallel; the step waits for the group with the most of them.
        out["balancer"] += loads(work[s], owner, ranks).max() + move_cost * busiest_migration(
            new, previous, ranks)
    eff = {k: (total / (ranks * v) if v > 0 else 1.0) for k, v in out.items()}
    return eff, out, migrations, points


def gather_model(path):
    if not path:
        return dict(DEFAULT_GATHER)
    try:
        with open(path) as f:
            rows = [row for row in json.load(f)["rows"] if row["ranks"] >= 2]
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise InputError(f"{path}: not bench_allgather JSON: {e}") from None
    if not rows:
        raise InputError(f"{path}: no rows with 2 or more ranks")
    a = np.array([[math.log2(row["ranks"]), row["points"] * WIDTH_BYTES * (row["ranks"] - 1)
                   / row["ranks"]] for row in rows])
    t = np.array([row["median_seconds"] for row in rows])
    coef, *_ = np.linalg.lstsq(a, t, rcond=None)
    coef = np.maximum(coef, [1e-7, 1e-12])
    return {"latency": float(coef[0]), "per_byte": float(coef[1]),
            "source": "fitted to %s (%d rows, ranks %d-%d)"
            % (path, len(rows), min(x["ranks"] for x in rows), max(x["ranks"] for x in rows))}


def gather_seconds(model, ranks, points):
    if ranks < 2:
        return 0.0
    return (model["latency"] * math.log2(ranks)
            + model["per_byte"] * points * WIDTH_BYTES * (ranks - 1) / ranks)


def rank_counts(text):
    """--ranks: a comma-separated list of rank counts."""
    return [cli.positive_int(x.strip()) for x in text.split(",")]


# As balance.persistence (src/coupling/rve_balance.cpp): above 0.95 a plan would need more
# than 135 rows of loads; 1 is a peak that stays.
persistence = cli.number(float, lambda x: 0 <= x <= 0.95 or x == 1, "in [0, 0.95] or 1")


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("record", metavar="RECORD_OR_OUTPUT",
                   help="a cost_record.h5, or a run's output folder (its first packings/m*)")
    p.add_argument("--ranks", type=rank_counts, default=[2 ** k for k in range(1, 13)],
                   help="rank counts, comma-separated (default 2,4,...,4096)")
    p.add_argument("--tile", type=cli.positive_int, default=1)
    p.add_argument("--gather", help="bench_allgather's JSON")
    p.add_argument("--rate", type=cli.positive, help="particle-steps/s per core")
    p.add_argument("--threshold", type=cli.non_negative, default=0.02)
    p.add_argument("--horizon", type=cli.positive_int, default=10)
    p.add_argument("--move-cost", type=cli.non_negative, default=60.0,
                   help="DEM steps of one RVE")
    p.add_argument("--persistence", type=persistence, default=0.6,
                   help="share of a cost above the sub-step floor left one update later")
    p.add_argument("--update-cost", type=cli.non_negative,
                   help="fixed cost per update in DEM steps (default: the record's)")
    p.add_argument("--json", help="write the result to this file")
    p.add_argument("--plot", help="draw the efficiencies into this picture")
    a = p.parse_args()
    cli.writable_file(a.json, "--json file")
    if a.plot:
        cli.picture_file(a.plot)
        require("matplotlib")
    ranks = a.ranks
    gm = gather_model(a.gather)
    r = read_record(a.record)
    if a.update_cost is not None:
        r["update_cost_steps"] = a.update_cost
    ran = r["measured_steps"] > 0
    measured_work = work_of(r["measured_steps"], ran, r["grains"], r["update_cost_steps"]).sum()
    seconds = float(r["seconds"].astype(float).sum())
    if a.rate is not None:
        rate, rate_source = a.rate, "given"
    elif seconds > 0:
        rate, rate_source = measured_work / seconds, "the record's measured seconds"
    else:
        raise InputError(f"{r['file']}: the record has no measured seconds: give --rate")
    steps = r["measured_steps"].shape[0]
    rows = []
    print("%s: %d steps, %d points x tile %d, rate %.4g particle-steps/s per core (%s)"
          % (r["file"], steps, r["measured_steps"].shape[1], a.tile, rate, rate_source))
    print("gather: %.3g s x log2(R) + %.3g s/byte (%s)" % (gm["latency"], gm["per_byte"],
                                                           gm["source"]))
    print("%6s %7s %9s %9s %9s %9s %12s %12s %10s" % (
        "ranks", "pts/rk", "rr", "balancer", "lpt", "bound", "wall rr [s]", "wall bal [s]",
        "moves"))
    for R in ranks:
        eff, makespan, migrations, points = project(r, R, a.tile, a.threshold, a.horizon,
                                                    a.move_cost, a.persistence)
        gather = gather_seconds(gm, R, points) * steps
        wall = {k: makespan[k] / rate + gather for k in makespan}
        rows.append({"ranks": R, "points_per_rank": points / R, "efficiency": eff,
                     "wall_seconds": wall, "gather_seconds": gather, "migrations": migrations})
        print("%6d %7.1f %9.3f %9.3f %9.3f %9.3f %12.4g %12.4g %10d" % (
            R, points / R, eff["round_robin"], eff["balancer"], eff["lpt"], eff["bound"],
            wall["round_robin"], wall["balancer"], migrations))
    takeover = next((row["ranks"] for row in rows if row["efficiency"]["bound"] < 0.95), None)
    note = ("the bound (the costliest point of each step alone) falls below 0.95 from %s ranks"
            % takeover if takeover else "the bound stays above 0.95 up to %d ranks" % ranks[-1])
    print(note)
    result = {"record": r["file"], "tile": a.tile, "rate": rate, "rate_source": rate_source,
              "gather": gm, "threshold": a.threshold, "horizon": a.horizon,
              "move_cost_steps": a.move_cost, "persistence": a.persistence,
              "floor_steps": r["floor_steps"], "rows": rows, "bound_takes_over_at": takeover}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(result, f, indent=1)
    if a.plot:
        fig, ax = figures.subplots(figsize=(6, 4))
        for key, label in (("round_robin", "round-robin"), ("balancer", "balancer"),
                           ("lpt", "LPT per step"), ("bound", "bound (costliest point)")):
            ax.plot(ranks, [row["efficiency"][key] for row in rows], marker="o", label=label)
        ax.set_xscale("log", base=2)
        ax.set_xlabel("MPI ranks (one per RVE group)")
        ax.set_ylabel("stepping efficiency")
        ax.set_ylim(0, 1.02)
        ax.grid(True, alpha=0.3)
        ax.legend()
        figures.finish(fig, a.plot, 120)


def entry():
    """The command: tools/scaling_model.py in a checkout, mpm-lig-scaling-model installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
