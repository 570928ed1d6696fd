"""Direct DEM of a 2D mpm_lig footing case: the same grains, contact law and boundary value
problem run by the native `liggghts` executable, grain by grain.

usage: direct_dem.py CASE.json --output DIR [--scale S] [--tiles T] [--seed N]
                     [--settlement S_OVER_B] [--speed-factor F] [--np N] [--snapshots S1 S2 ...]
                     [--fields-every DS] [--surcharge-every STEPS] [--checkpoint-steps STEPS]
                     [--void-ratio-tolerance DE] [--settle-damping kinetic|none]
                     [--footing-column H]
                     [--stop-after-minutes M] [--liggghts PATH]
                     [--resume | --start-from RUN_DIR [--resettle]]

CASE.json is a 2D footing case (analysis.type mpm, rigid_bodies[0] a footing at x = 0 on a
half model, one dem_rve material, rollers on x- and x+, fixed y-, a vertical traction: the
surcharge q_s). The direct DEM:
- grains: the rve's radius distribution and density, as many discs as fill the soil block
  (bodies[0].box, times --scale S with the grains unchanged, so B/d grows by S) at the rve's
  preparation.target_void_ratio; placed at random in a periodic cell at its
  initial_solid_fraction (src/rve/packing.cpp) and consolidated to its confining_pressure by
  the RVE procedure (src/rve/consolidation.cpp: per-axis isotropic servo, friction lowered in
  stages of x0.7 until the void ratio is reached, then the contact friction restored), with the
  contact law and time step of the rve (the lmp_inputs/liggghts templates). With --tiles T
  (S a multiple of T) that procedure prepares a periodic cell of 1/T of the block's width and
  height, which is repeated T x T times and settled again at the contact friction;
- the problem: the periodic cell opened into the block: x- and x+ frictionless rigid planes
  (the rollers), the grains of the bottom 2 d_max frozen (the fixed rough base), the grains of
  the top d_max over 0 <= x < B/2 a rigid block (the rough footing) moved down at constant
  speed, the surcharge q_s as vertical forces on the top grain of each d_mean-wide column of the
  free surface beyond B/2, re-found every --surcharge-every steps (so it follows the heave);
  no gravity. Soil grains the opened planes cut are shrunk to fit and grown back under load;
  with --footing-column H the footing block is extended up by a column of frozen discs H
  footing widths above the surface (soil that heaves beside the sinking footing then stays
  beside it, as the multiscale footing keeps its whole column clear; without it the soil
  flows onto the one-grain block); the block then settles under q_s, the footing held, until
  at rest (with --settle-damping
  kinetic, the default, the soil's velocities are zeroed at each maximum of its kinetic
  energy: the opened block rings in its lowest vertical mode, which the contacts hardly damp);
- the speed: strain rate v/B at the rve's substeps.inertial_number, I = (v/B) d sqrt(rho/p),
  times --speed-factor.
Output in DIR: history.csv (settlement, footing load, q/q_s, base reaction, ...), results.h5 and
results.xdmf (the grains' motion coarse-grained onto the case's material points: displacement,
Hencky strain and eps_q, for tools/plot_fields.py and ParaView), snapshots/ (grains and
contacts as legacy VTK at --snapshots settlements, for tools/plot_force_chains.py),
force_chains.png, load.png, summary.json (grains, particle-steps, core-seconds, wall time,
peak and plateau), checkpoint.json with its restart every --checkpoint-steps DEM steps and at
the settled block (settled.json + settled.restart: --start-from loads it for another loading,
e.g. at half the speed; --resettle settles it again first, e.g. a block settled without
damping). The engine is reloaded from every checkpoint it writes, so a run that
stops and resumes (--resume) computes bit for bit what an uninterrupted one does; the checkpoint
carries digests of its files and the options a resume must keep, and --resume refuses (exit 2,
naming what differs) before running anything. One run at a time writes DIR.
Exit codes (mpm_lig's): 0 done; 1 the run failed (e.g. the preparation missed its void
ratio); 2 bad input, named, before anything runs (nothing created for a new run); 3 the engine
failed (stopped, reported an ERROR, or did not answer); 4 stopped (SIGTERM, SIGHUP, Ctrl-C, or
--stop-after-minutes at the first checkpoint after that time): the last line says which
checkpoint --resume continues from.
"""
import os
import shutil
import sys

import numpy as np

from mpm_lig_post import cli
from mpm_lig_post.coarse_grain import FieldOutput
from mpm_lig_post.direct_dem.block import loading_steps
from mpm_lig_post.direct_dem.case import check_memory, problem
from mpm_lig_post.direct_dem.checkpoint import (ADDED_KEPT, KEPT, OWN_FILES, Stopped,
                                                case_digest, fill_options, publish_settled,
                                                restore_outputs, stop_on_signals,
                                                verify_checkpoint)
from mpm_lig_post.direct_dem.probes import check_probes
from mpm_lig_post.direct_dem.report import chains_picture, summarise
from mpm_lig_post.direct_dem.run import Run
from mpm_lig_post.errors import InputError
from mpm_lig_post.liggghts import EngineFailed, require_templates
from mpm_lig_post.run_folder import FolderLock, refuse_links, refuse_links_below
from mpm_lig_post.tables import read_json

LOCK = "direct_dem.lock"
EXIT_ENGINE, EXIT_STOPPED = 3, 4

# ----------------------------------------------------------------------------- command line
def arguments():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("case", metavar="CASE.json")
    p.add_argument("--output", required=True)
    p.add_argument("--scale", type=cli.positive, help="soil block and footing x S, grains "
                   "unchanged (default 1)")
    p.add_argument("--tiles", type=cli.positive_int, help="prepare a periodic cell of 1/T of the "
                   "block and repeat it T x T times (default 1: the whole block)")
    p.add_argument("--seed", type=cli.non_negative_int, help="packing seed (default 11)")
    p.add_argument("--settlement", type=cli.positive,
                   help="final s/B (default 1; on --resume the checkpoint's, or a larger one "
                   "while the run has not finished)")
    p.add_argument("--speed-factor", type=cli.positive,
                   help="footing speed over the one of the rve's inertial number (default 1)")
    p.add_argument("--np", type=cli.positive_int, help="MPI ranks (default 1: serial)")
    p.add_argument("--liggghts", default=None, help="the liggghts executable (default: on PATH)")
    p.add_argument("--fields-every", type=cli.positive, help="s/B between field outputs "
                   "(default 0.05)")
    p.add_argument("--snapshots", type=cli.non_negative, nargs="*",
                   help="s/B of the grain and contact snapshots (default 0.1 0.5)")
    p.add_argument("--surcharge-every", type=cli.positive_int,
                   help="DEM steps between surcharge updates and history rows (default 500)")
    p.add_argument("--checkpoint-steps", type=cli.positive_int,
                   help="DEM steps between checkpoints (default: about 3e9 particle-steps)")
    p.add_argument("--void-ratio-tolerance", type=cli.positive, help="the prepared void ratio's "
                   "tolerance (default: the case's preparation.void_ratio_tolerance, or 0.005)")
    p.add_argument("--probes", nargs="+", metavar="NAME[=X:DEPTH[:SIDE]]",
                   help="windows that follow their grains, with their F and the grains' own "
                   "stress in probes.csv (named: wedge band passive far; or NAME=X:DEPTH, the "
                   "centre in footing widths from the axis and below the surface, :SIDE its "
                   "own window side in grain diameters), for tools/replay_direct_dem.py")
    p.add_argument("--probes-every", type=cli.positive,
                   help="s/B between probe rows (default 0.005)")
    p.add_argument("--probe-window", type=cli.positive, metavar="D",
                   help="the window side in grain diameters of the probes without their own "
                   "SIDE (default: the side of the case's RVE)")
    p.add_argument("--settle-damping", choices=("kinetic", "none"),
                   help="the settling under q_s: kinetic (default: the soil's velocities zeroed "
                   "at each maximum of its kinetic energy) or none (the contacts' damping only, "
                   "as runs before this option)")
    p.add_argument("--footing-column", type=cli.non_negative, metavar="H",
                   help="the footing block extended up by a column of frozen discs H footing "
                   "widths above the surface (default 0: the one-grain block; with "
                   "--start-from a block settled without one, the column is added before "
                   "the loading)")
    p.add_argument("--resettle", action="store_true",
                   help="with --start-from: settle the loaded block again (with "
                   "--settle-damping) before its loading")
    p.add_argument("--stop-after-minutes", type=cli.positive,
                   help="stop at the first checkpoint after this long (continue with --resume)")
    p.add_argument("--extend", action="store_true",
                   help="with --resume and a larger --settlement: continue a finished run "
                   "from its end state (not bit for bit one longer run: the loading's "
                   "500-step grid restarts at the old end)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--resume", action="store_true", help="continue DIR from its checkpoint")
    g.add_argument("--start-from", metavar="RUN_DIR",
                   help="load the settled block of an earlier run (e.g. at another speed)")
    return p.parse_args()


def main():
    a = arguments()
    stop_on_signals()
    case = read_json(a.case)
    out = a.output = os.path.abspath(a.output)
    if a.liggghts is not None:
        if not shutil.which(a.liggghts):
            raise InputError(f"--liggghts {a.liggghts}: no such executable")
        a.liggghts = os.path.abspath(shutil.which(a.liggghts))  # the engine runs in the folder
    if a.liggghts is None and not shutil.which("liggghts"):
        raise InputError("liggghts: not on PATH (apt-get install liggghts, or give --liggghts)")
    require_templates()
    a.case_digest = case_digest(a.case)
    cli.writable_folder(out)
    record = None
    if a.resume:
        if not os.path.isdir(out):
            raise InputError(f"{out}: no such folder to resume")
        lock = FolderLock(out, LOCK)
        refuse_links_below(out)
        record = verify_checkpoint(out, a, a.case_digest)
        pb = problem(case, a.case, record["options"]["scale"])
        fill_options(a, pb, {**ADDED_KEPT, **record["options"]}, out)
        if a.settlement is None:
            a.settlement = record["settlement"]
        finished = record["stage"] == "load" and record["state"]["load_steps"] >= \
            loading_steps(pb, a.speed_factor, record["settlement"])
        longer = a.settlement > record["settlement"]
        if a.extend and not (finished and longer):
            raise InputError(f"--extend: only for a finished run resumed to a larger "
                             f"--settlement ({out}: " + ("finished at" if finished else
                                                         "not finished, its end") +
                             f" s/B {record['settlement']:g})")
        if finished and longer and not a.extend:
            # Its last checkpoint is the end state, a shorter chunk off the loading's 500-step
            # grid: a loading continued from there is not bit for bit the longer run.
            raise InputError(f"{out}: this run finished (s/B {record['settlement']:g}); for a "
                             "longer loading start a new run from its settled block with "
                             "--start-from, or continue this one from its end with --extend "
                             "(not bit for bit one longer run)")
    else:
        if a.extend:
            raise InputError("--extend: only with --resume (it continues a finished run)")
        if a.resettle and not a.start_from:
            raise InputError("--resettle: only with --start-from (a new run settles anyway)")
        if a.start_from:
            start = os.path.abspath(a.start_from)
            refuse_links(start, ["settled.json", "settled.restart", "reference.npz"])
            record = verify_checkpoint(start, a, a.case_digest, "settled.json")
            options = {k: v for k, v in record["options"].items()
                       if k in ("scale", "tiles", "seed", "void_ratio_tolerance")
                       or (k == "footing_column" and v > 0)}
            # The problem at the settled block's scale: its footing width, speed and the
            # probes' places are those of that block, whatever --scale says (or omits).
            pb = problem(case, a.case, options["scale"])
            fill_options(a, pb, options, start)
        else:
            pb = problem(case, a.case, a.scale or KEPT["scale"])
            fill_options(a, pb)
        a.settlement = a.settlement or 1.0
        if os.path.isdir(out):
            refuse_links_below(out)
        if os.path.isdir(out) and any(os.path.lexists(os.path.join(out, f)) for f in OWN_FILES):
            raise InputError(f"{out}: holds a run already (continue it with --resume, or choose "
                             "another folder)")
    if a.tiles > 1 and abs(a.scale / a.tiles - round(a.scale / a.tiles)) > 1e-9:
        raise InputError(f"--tiles {a.tiles}: --scale {a.scale:g} must be a multiple of it (each "
                         "tile is a block of the case's own size or a multiple)")
    check_memory(pb, a.scale)
    check_probes(pb, a)
    deepest = pb["box"][1] - 8 * pb["rmax"]  # above the frozen base (2 d_max) and a d_max more
    if a.settlement * pb["B"] > deepest:
        raise InputError(f"--settlement {a.settlement:g}: the footing would pass s/B = "
                         f"{deepest / pb['B']:.2f}, where the block's frozen base begins")
    if not a.resume:
        os.makedirs(out, exist_ok=True)
        lock = FolderLock(out, LOCK)
        refuse_links_below(out)
    run = Run(pb, a, out)
    try:
        return go(run, a, out, record)
    except Stopped as e:
        run.close(kill=True)
        where = run.last_checkpoint or (record and (record["stage"], record["state"]["steps"],
                                                    record["state"]["load_steps"]))
        if where and os.path.isfile(os.path.join(out, "checkpoint.json")):
            stage, steps, load = where
            print(f"direct_dem: stopped ({e}) at step {run.steps}: the checkpoint of step "
                  f"{steps} ({stage}" + (f", s/B {load * pb['speed'] * a.speed_factor * pb['dt'] / pb['B']:.3f}"
                                        if stage == "load" else "")
                  + f") is on disk: continue with --resume --output {out}", file=sys.stderr)
        else:
            print(f"direct_dem: stopped ({e}) at step {run.steps} before the first checkpoint: "
                  "nothing to resume, start again", file=sys.stderr)
        return EXIT_STOPPED
    except EngineFailed as e:
        run.close(kill=True)
        print(f"direct_dem: the engine failed: {e}", file=sys.stderr)
        return EXIT_ENGINE
    finally:
        run.close(kill=True)
        lock.release()


def go(run, a, out, record):
    """The run from its start, a checkpoint or a settled block to the end."""
    if record is None:
        print(f"direct DEM of {a.case}: about {run.pb['grains']} grains, B/d = "
              f"{run.pb['B'] / run.pb['d']:.1f}, footing {run.pb['speed'] * a.speed_factor:.4g} "
              f"m/s, dt {run.pb['dt']:.4g} s", flush=True)
        run.prepare()
    else:
        folder = out if a.resume else os.path.abspath(a.start_from)
        if not a.resume:
            shutil.copyfile(os.path.join(folder, "reference.npz"), os.path.join(out, "reference.npz"))
        elif record["stage"] == "load":
            restore_outputs(out, record)
        restart = os.path.join(folder, record["files"]["restart"]["name"])
        run.restore(record, restart)
        run.sitting_steps = run.particle_steps
        if a.extend:
            run.extended_from = run.extended_from + [record["settlement"]]
        if not a.resume:  # a new loading of the settled block: its own checkpoints from here
            run.next_checkpoint = run.steps + a.checkpoint_steps
            if a.resettle:
                run.stage, run.settle_state = "settle", None
            if a.footing_column > 0 and not record["options"].get("footing_column"):
                run.add_footing_column(a.footing_column)  # a block settled without one
    if run.stage == "prepare":
        run.consolidate()
        run.open_block()
        if a.footing_column > 0:
            run.add_footing_column(a.footing_column)
        run.stage = "settle"
    if run.stage == "settle":
        run.settle()
        ids, xy, _ = run.grains_now()
        order = np.argsort(ids)
        np.savez(os.path.join(out, "reference.npz"), ids=ids[order], xy=xy[order],
                 base=run.base_ids, footing=run.footing_ids)
        settled = run.checkpoint("settled")
        publish_settled(out, settled)
    reference = np.load(os.path.join(out, "reference.npz"))
    run.ref_ids, run.ref_xy = reference["ids"], reference["xy"]
    run.field_out = FieldOutput(out, resume=run.stage == "load")
    finished = run.load()
    run.checkpoint("load", reload=False)
    summary = summarise(run, run.pb, a, out, finished)
    chains_picture(out)
    print(f"finished: peak q/q_s {summary['peak_q_over_qs']:.2f} at s/B "
          f"{summary['peak_at_s_over_B']:.2f}, {summary['particle_steps']:.3g} particle-steps, "
          f"{summary['wall_seconds'] / 60:.1f} min")
    return 0


def entry():
    """The command: tools/direct_dem.py in a checkout, mpm-lig-direct-dem installed."""
    cli.run(main, failures=RuntimeError)


if __name__ == "__main__":
    entry()

