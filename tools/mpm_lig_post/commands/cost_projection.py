"""Project the cost of an mpm_lig run with dem_rve materials from short measured runs.

    tools/cost_projection.py TARGET.json --run OUT_DIR [CASE.json] [--run ...] [--json FILE]
                             [--ranks N ...] [--efficiency E] [--substeps N]
                             [--rate R [AT_SUBSTEPS]] [--time-step DT]
                             [--fixed-steps F [F_TARGET]] [--setting SHIPPED_DIR SETTING_DIR]

Each measured run directory holds the `summary.json` that mpm_lig writes (wall_seconds,
dem_particle_steps, rve_count, ranks, mpm_steps, time_split). The case file of a measured run is
optional; with it the tool also reports the mean DEM sub-steps per RVE and MPM step, which the
projection needs unless --substeps gives them.

Projected core-seconds = RVEs x grains x sub-steps x MPM steps / (particle-steps/s per core),
where the rate per core counts the stepping phase only (wall time minus packing preparation and
output), so load imbalance between ranks is included. Preparation is reported separately.
With --ranks, the wall time of the stepping and the core-hours an allocation of N cores is
charged for it, at each N: a step lasts as long as the busiest rank, so the stepping efficiency
is at most the RVE granularity (RVEs / N) / ceil(RVEs / N) (equal RVEs, one rank each), times
--efficiency (default 1: the RVEs' cost spread perfectly; give a measured or modelled figure).

--fixed-steps F: what a DEM update costs besides its DEM steps, in DEM steps (the intercept over
the slope of `bench_rve_update --steps`), for the measured runs' updates, and F_TARGET for the
target's (default F; e.g. with `rve.setup_every` 20 against 1). The measured rate is then read
as (sub-steps + F x DEM updates) per core-second, and the target costs its sub-steps plus
F_TARGET per DEM update: a rate measured at few sub-steps per update no longer charges its fixed
share to every step of a target with many.
--setting SHIPPED_DIR SETTING_DIR: project the target at a work-saving setting measured on a
smaller case run both ways: its particle-steps and its DEM updates are the target's as shipped
times the ratios SETTING / SHIPPED of the two runs (quiet points and steady flow predict updates
without the DEM; `summary.json` counts them).
Exit code 2 on a missing file or key (named in the message).
"""
from mpm_lig_post.requirements import require

require("numpy")

import json  # noqa: E402
import math  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.tables import need, read_json  # noqa: E402


def listed(node, key, where):
    """node[key], a list of JSON objects."""
    items = need(node, key, where)
    if not isinstance(items, list) or not all(isinstance(m, dict) for m in items):
        raise InputError(f"{where}: {key}: expected a list of objects")
    return items


def dem_materials(case, where):
    mats = [m for m in listed(case, "materials", where) if m.get("type") == "dem_rve"]
    if not mats:
        raise InputError(f"{where}: no material of type dem_rve")
    return {m["id"]: m for m in mats}


def cell_size(case, where):
    mesh = need(case, "mesh", where)
    size, cells = need(mesh, "size", where + ": mesh"), need(mesh, "cells", where + ": mesh")
    for key, values in (("size", size), ("cells", cells)):
        if not isinstance(values, list) or not values or any(
                isinstance(v, bool) or not isinstance(v, (int, float)) or not v > 0
                for v in values):
            raise InputError(f"{where}: mesh.{key}: expected a list of numbers > 0")
    return [s / n for s, n in zip(size, cells)]


def case_rves(case, where):
    """Material points of dem_rve bodies and their grains: [(points, grains), ...]."""
    mats = dem_materials(case, where)
    h = cell_size(case, where)
    out = []
    for i, body in enumerate(listed(case, "bodies", where)):
        if body.get("material") not in mats:
            continue
        box = need(body, "box", f"{where}: bodies[{i}]")
        ppc = body.get("points_per_cell", 2)
        points = 1
        where_box = f"{where}: bodies[{i}].box"
        for lo, hi, hk in zip(need(box, "min", where_box), need(box, "max", where_box), h):
            points *= round((hi - lo) / hk) * ppc
        rve = need(mats[body["material"]], "rve", f"{where}: materials")
        out.append((points, need(rve, "grains", f"{where}: materials[].rve")))
    if not out:
        raise InputError(f"{where}: no body made of a dem_rve material")
    return out


def measure(run_dir, case_path):
    where = f"{run_dir}/summary.json"
    s = read_json(where)
    wall = need(s, "wall_seconds", where, True)
    ranks = need(s, "ranks", where, True)
    psteps = need(s, "dem_particle_steps", where, True)
    rves = need(s, "rve_count", where, True)
    steps = need(s, "mpm_steps", where, True) + s.get("gravity_stage_steps", 0)
    split = need(s, "time_split", where)
    prep = need(split, "preparation", where + ": time_split", True)
    stepping = wall - prep - split.get("output", 0.0)
    if ranks <= 0:
        raise InputError(f"{where}: ranks: expected a number > 0, got {ranks}")
    if stepping <= 0 or steps <= 0 or rves <= 0:
        raise InputError(f"{where}: no stepping measured (wall {wall} s, {steps} steps)")
    m = {
        "run": run_dir,
        "dem_updates_per_rve_step": dem_updates(s, where) / (rves * steps),
        "ranks": ranks,
        "rve_count": rves,
        "mpm_steps": steps,
        "wall_seconds": wall,
        "preparation_seconds": prep,
        "dem_share_of_stepping": split.get("dem", 0.0) / stepping,
        "particle_steps_per_s_per_core": psteps / (ranks * stepping),
        "core_seconds_per_mpm_step_per_rve": ranks * stepping / (steps * rves),
    }
    if case_path:
        case = read_json(case_path)
        grains = [g for _, g in case_rves(case, case_path)]
        if len(set(grains)) == 1:
            m["grains"] = grains[0]
            m["mean_substeps"] = psteps / (rves * grains[0] * steps)
        m["time_step"] = s.get("time_step")
        m["cell_size"] = min(cell_size(case, case_path))
    return m


def dem_updates(summary, where):
    """The RVE updates a run gave to the DEM: every point and step but those predicted."""
    quiet = summary.get("quiet_points")
    if quiet is not None:
        return need(quiet, "dem_updates", where + ": quiet_points", True)
    steps = need(summary, "mpm_steps", where, True) + summary.get("gravity_stage_steps", 0)
    every = need(summary, "rve_count", where, True) * steps
    return every - summary.get("steady_flow", {}).get("predicted_updates", 0.0)


def setting_ratios(shipped_dir, setting_dir):
    """Particle-steps and DEM updates of a setting against the shipped run of the same case."""
    ratios = []
    for key in ("dem_particle_steps", "dem_updates"):
        values = []
        for d in (shipped_dir, setting_dir):
            where = f"{d}/summary.json"
            s = read_json(where)
            values.append(dem_updates(s, where) if key == "dem_updates"
                          else need(s, key, where, True))
        if values[0] <= 0:
            raise InputError(f"{shipped_dir}/summary.json: {key} is {values[0]}: nothing to "
                             "compare the setting with")
        ratios.append(values[1] / values[0])
    return {"shipped": shipped_dir, "setting": setting_dir, "particle_steps_ratio": ratios[0],
            "dem_updates_ratio": ratios[1]}


def target_steps(case, path, runs, notes):
    end = need(need(case, "analysis", path), "end", path + ": analysis")
    gravity = case["analysis"].get("gravity_stage", {}).get("steps", 0)
    if "steps" in end:
        return end["steps"] + gravity
    t_end = need(end, "time", path + ": analysis.end")
    ref = next((r for r in runs if r.get("time_step") and r.get("cell_size")), None)
    if ref is None:
        raise InputError(f"{path}: analysis.end is a time; give --time-step or a measured run "
                         "with its case file (its CFL time step is scaled by the cell size)")
    dt = ref["time_step"] * min(cell_size(case, path)) / ref["cell_size"]
    notes.append(f"MPM time step {dt:.4g} s: CFL step {ref['time_step']:.4g} s of {ref['run']} "
                 f"scaled by the cell size (same material stiffness and density assumed)")
    return math.ceil(t_end / dt) + gravity


def project(runs, target_path, substeps=None, time_step=None, rate=None, fixed=(0.0, 0.0),
            setting=None, rate_substeps=None):
    case = read_json(target_path)
    notes = []
    rves = case_rves(case, target_path)
    if time_step:
        end = need(need(case, "analysis", target_path), "end", target_path + ": analysis")
        steps = end.get("steps") or math.ceil(end["time"] / time_step)
        notes.append(f"MPM time step {time_step:.4g} s (given)")
    else:
        steps = target_steps(case, target_path, runs, notes)
    if rate is None:
        source = min(runs, key=lambda r: r["particle_steps_per_s_per_core"])
        rate = source["particle_steps_per_s_per_core"]
        notes.append(f"rate {rate:.4g} particle-steps/s per core: the slowest measured run "
                     "(stepping phase, load imbalance included)")
    elif rate_substeps:
        source = {"run": "the given rate", "mean_substeps": rate_substeps,
                  "dem_updates_per_rve_step": 1.0}
        notes.append(f"rate {rate:.4g} particle-steps/s per core (given), measured at "
                     f"{rate_substeps:.4g} sub-steps per update")
    else:
        source = next((r for r in runs if "mean_substeps" in r), runs[0] if runs else {})
        notes.append(f"rate {rate:.4g} particle-steps/s per core (given)")
    measured_rate = rate
    if fixed[0] > 0.0:
        if "mean_substeps" not in source:
            raise InputError("--fixed-steps needs the sub-steps per update the rate was measured "
                             "at (they split it into steps and fixed costs): --rate R AT_SUBSTEPS,"
                             " or a --run with its case file")
        n, u = source["mean_substeps"], source["dem_updates_per_rve_step"]
        rate *= (n + fixed[0] * u) / n
        notes.append(f"{rate:.4g} step-equivalents/s per core: that rate with {fixed[0]:.3g} DEM "
                     f"steps of fixed cost on each of its {u:.3g} DEM updates per RVE and step "
                     f"at {n:.4g} sub-steps")
    if substeps is None:
        known = [r["mean_substeps"] for r in runs if "mean_substeps" in r]
        if not known:
            raise InputError("no measured run with its case file: give --substeps")
        substeps = max(known)
        notes.append(f"{substeps:.4g} DEM sub-steps per RVE and MPM step: the largest mean measured "
                     "(inertial-number control: it grows with the strain rate per step)")
    else:
        notes.append(f"{substeps:.4g} DEM sub-steps per RVE and MPM step (given)")
    steps_ratio, updates = 1.0, 1.0
    if setting:
        steps_ratio, updates = setting["particle_steps_ratio"], setting["dem_updates_ratio"]
        notes.append(f"the setting of {setting['setting']}: {steps_ratio:.4g} of the "
                     f"particle-steps and {updates:.4g} of the DEM updates of "
                     f"{setting['shipped']}")
    if fixed[1] > 0.0:
        notes.append(f"{fixed[1]:.3g} DEM steps of fixed cost per DEM update of the target")
    cost_per_rve_step = substeps * steps_ratio + fixed[1] * updates
    particle_steps_per_mpm_step = sum(p * g for p, g in rves) * cost_per_rve_step
    core_s_per_step = particle_steps_per_mpm_step / rate
    rve_count = sum(p for p, _ in rves)
    return {
        "target": target_path,
        "rve_count": rve_count,
        "grains": sorted({g for _, g in rves}),
        "mpm_steps": steps,
        "substeps": substeps,
        "fixed_steps": {"measured": fixed[0], "target": fixed[1]},
        "setting": setting,
        "dem_updates_per_rve_step": updates,
        "substeps_at_setting": substeps * steps_ratio,
        "particle_steps_per_s_per_core": measured_rate,
        "step_equivalents_per_s_per_core": rate,
        "core_seconds_per_mpm_step": core_s_per_step,
        "core_seconds_per_mpm_step_per_rve": core_s_per_step / rve_count,
        "core_hours": core_s_per_step * steps / 3600.0,
        "assumptions": notes,
    }


def at_ranks(projection, ranks, efficiency):
    """Wall hours and charged core-hours of the stepping on each rank count."""
    rves = projection["rve_count"]
    rows = []
    for n in ranks:
        granularity = (rves / n) / math.ceil(rves / n)
        stepping = granularity * efficiency
        wall_h = projection["core_hours"] / (n * stepping)
        rows.append({"ranks": n, "rves_per_rank": rves / n, "granularity": granularity,
                     "stepping_efficiency": stepping, "wall_hours": wall_h,
                     "charged_core_hours": n * wall_h})
    return rows


def main(argv=None):
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--run", nargs="+", action="append", default=[], metavar="DIR [CASE]",
                   help="a measured run's output directory, optionally followed by its case file "
                        "(none: --rate and --substeps give what it would)")
    p.add_argument("target", help="case file of the run to project")
    p.add_argument("--substeps", type=cli.positive, help="DEM sub-steps per RVE and MPM step")
    p.add_argument("--time-step", type=cli.positive, help="MPM time step of the target [s]")
    p.add_argument("--rate", type=cli.positive, nargs="+", metavar=("RATE", "AT_SUBSTEPS"),
                   help="particle-steps/s per core to assume [measured at AT_SUBSTEPS sub-steps "
                        "per update, one update per RVE and step]")
    p.add_argument("--json", help="write the result to this file")
    p.add_argument("--ranks", type=int, nargs="+", metavar="N",
                   help="rank counts to give the stepping's wall time and charged core-hours at")
    p.add_argument("--efficiency", type=float, default=1.0,
                   help="stepping efficiency besides the RVE granularity (default 1)")
    p.add_argument("--fixed-steps", type=cli.non_negative, nargs="+", metavar="F",
                   help="an update's fixed cost in DEM steps: measured runs' [target's]")
    p.add_argument("--setting", nargs=2, metavar=("SHIPPED_DIR", "SETTING_DIR"),
                   help="project the target at the setting SETTING_DIR was run with")
    a = p.parse_args(argv)
    fixed = (0.0, 0.0)
    if a.fixed_steps:
        if len(a.fixed_steps) > 2:
            raise InputError(f"--fixed-steps {a.fixed_steps}: one or two numbers")
        fixed = (a.fixed_steps[0], a.fixed_steps[-1])
    cli.writable_file(a.json, "--json file")
    if any(len(r) > 2 for r in a.run):
        raise InputError("--run takes a directory and at most one case file")
    rate, rate_substeps = (a.rate + [None])[:2] if a.rate else (None, None)
    if a.rate and len(a.rate) > 2:
        raise InputError(f"--rate {a.rate}: a rate and at most the sub-steps it was measured at")
    if not a.run and not (rate and a.substeps):
        raise InputError("no --run: give --rate and --substeps (and --time-step for an end time)")
    if a.ranks and min(a.ranks) < 1:
        raise InputError(f"--ranks {min(a.ranks)}: a rank count is at least 1")
    if not 0.0 < a.efficiency <= 1.0:
        raise InputError(f"--efficiency {a.efficiency}: a stepping efficiency is in (0, 1]")
    runs = [measure(r[0], r[1] if len(r) > 1 else None) for r in a.run]
    setting = setting_ratios(*a.setting) if a.setting else None
    result = {"measured": runs,
              "projection": project(runs, a.target, a.substeps, a.time_step, rate, fixed,
                                    setting, rate_substeps)}
    if a.ranks:
        result["ranks"] = at_ranks(result["projection"], a.ranks, a.efficiency)
    for r in runs:
        line = (f"{r['run']}: {r['rve_count']} RVEs, {r['mpm_steps']} steps, {r['ranks']} ranks, "
                f"{r['particle_steps_per_s_per_core']:.4g} particle-steps/s per core, "
                f"{r['core_seconds_per_mpm_step_per_rve']:.4g} core-s per MPM step per RVE, "
                f"DEM {100 * r['dem_share_of_stepping']:.0f} % of stepping")
        if "mean_substeps" in r:
            line += f", mean sub-steps {r['mean_substeps']:.4g}"
        print(line)
    pr = result["projection"]
    print(f"target {pr['target']}: {pr['rve_count']} RVEs x {pr['grains']} grains x "
          f"{pr['substeps_at_setting']:.4g} sub-steps x {pr['mpm_steps']} MPM steps")
    print(f"  {pr['core_seconds_per_mpm_step']:.4g} core-s per MPM step, "
          f"{pr['core_hours']:.4g} core-hours (packing preparation not included)")
    for n in pr["assumptions"]:
        print(f"  assumes {n}")
    for r in result.get("ranks", []):
        print(f"  {r['ranks']} ranks: {r['rves_per_rank']:.3g} RVEs per rank, stepping efficiency "
              f"{r['stepping_efficiency']:.3g} (granularity {r['granularity']:.3g}), "
              f"{r['wall_hours']:.3g} h wall, {r['charged_core_hours']:.4g} core-hours charged")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(result, f, indent=2)


def entry():
    """The command: tools/cost_projection.py in a checkout, mpm-lig-cost-projection installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
