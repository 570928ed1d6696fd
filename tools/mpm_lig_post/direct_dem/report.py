"""The direct DEM's summary.json, load picture and force-chain picture."""
import os
import resource
import time

import numpy as np

from mpm_lig_post import figures
from mpm_lig_post.direct_dem.probes import parse, window_side, windows
from mpm_lig_post.run_folder import write_json_atomic
from mpm_lig_post.tables import read_history


def probe_windows(run, pb, args):
    """{probe: its window's centre and side in footing widths} (tools/mpm_probes.py reads it)."""
    names = getattr(args, "probes", None) or []
    placed = windows(pb, parse(names), window_side(pb, args), run.lx, run.ly)
    return {name: {"x_over_B": float(c[0] / pb["B"]), "depth_over_B": float((run.ly - c[1]) / pb["B"]),
                   "side_over_B": float(side / pb["B"])} for name, (c, side) in placed.items()}


def summarise(run, pb, args, out, finished):
    table = read_history(os.path.join(out, "history.csv"))
    sB, q = table["s_over_B"], table["q_over_qs"]
    window = lambda a, b: float(np.mean(q[(sB >= a) & (sB <= b)])) if np.any((sB >= a) & (sB <= b)) \
        else None
    own = resource.getrusage(resource.RUSAGE_SELF)
    python_cpu = run.python_cpu + own.ru_utime + own.ru_stime
    cpu = run.engine_cpu
    summary = {
        "case": os.path.abspath(args.case), "finished": finished, "scale": args.scale,
        "tiles": args.tiles, "seed": args.seed, "grains": run.grains, "B": pb["B"],
        "B_over_d": pb["B"] / pb["d"], "block": [run.lx, run.ly], "thickness": pb["thickness"],
        "time_step": pb["dt"], "footing_speed": pb["speed"] * args.speed_factor,
        "speed_factor": args.speed_factor, "footing_column": args.footing_column,
        "inertial_number": pb["inertial"] * args.speed_factor,
        "q_s": pb["qs"], "preparation": run.prepared, "settled": run.settled,
        "dem_steps": run.steps, "loading_steps": run.load_steps,
        "extended_from": run.extended_from,
        "particle_steps": run.particle_steps, "ranks": args.np,
        "checkpoint_steps": args.checkpoint_steps,
        "wall_seconds": run.wall + time.time() - run.start, "engine_cpu_seconds": cpu,
        "python_cpu_seconds": python_cpu, "core_seconds": cpu + python_cpu,
        "s_over_B_reached": float(sB[-1]), "peak_q_over_qs": float(np.max(q)),
        "peak_at_s_over_B": float(sB[int(np.argmax(q))]),
        "plateau_0.1_0.3": window(0.1, 0.3), "plateau_0.1_0.4": window(0.1, 0.4),
        "mean_0.4_1.0": window(0.4, 1.0), "probes": probe_windows(run, pb, args)}
    write_json_atomic(os.path.join(out, "summary.json"), summary)
    fig, ax = figures.subplots(figsize=(6, 4))
    ax.plot(sB, q, "-", lw=1)
    ax.set_xlabel("settlement s/B")
    ax.set_ylabel(r"footing pressure $q/q_s$")
    ax.set_title(f"direct DEM, {run.grains} grains, B/d = {pb['B'] / pb['d']:.0f}")
    figures.save(fig, os.path.join(out, "load.png"))
    return summary


def chains_picture(out):
    from mpm_lig_post.commands import plot_force_chains as pfc

    sets = pfc.snapshot_sets(out)
    if not sets:
        return
    prefixes = sorted(next(iter(sets.values())).items())
    chosen = [prefixes[0], prefixes[-1]] if len(prefixes) > 1 else prefixes
    snaps = [pfc.Snapshot(p) for _, p in chosen]
    fmax = max([s.force.max() for s in snaps if len(s.force)], default=1.0)
    fig, axes = figures.subplots(len(snaps), 1, figsize=(8, 5 * len(snaps)), squeeze=False)
    for ax, (step, _), snap in zip(axes[:, 0], chosen, snaps):
        pfc.draw_panel(ax, snap, (0, 1), fmax, f"loading step {step}: {len(snap.force)} contacts, "
                       f"max |f| = {fmax:.3g} N")
    figures.save(fig, os.path.join(out, "force_chains.png"), 150)


