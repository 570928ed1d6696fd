"""The direct DEM's checkpoint (checkpoint.json beside the engine's restart): what it keeps, the
options a resume must keep, the digests that a resume checks before anything runs, and the
stop signals held back while it is committed."""
import hashlib
import json
import os
import shutil
import signal

from mpm_lig_post.errors import InputError
from mpm_lig_post.run_folder import check_digest, write_json_atomic
from mpm_lig_post.tables import read_json

FORMAT = 2             # checkpoint.json layout
# The options a run's results depend on: a resume keeps them (they are taken from the
# checkpoint when not given, refused when given otherwise). The end (--settlement), when to
# stop and which executable runs may change.
KEPT = {"scale": 1.0, "tiles": 1, "seed": 11, "speed_factor": 1.0, "np": 1, "fields_every": 0.05,
        "snapshots": [0.1, 0.5], "surcharge_every": 500, "checkpoint_steps": None,
        "void_ratio_tolerance": None, "probes": [], "probes_every": 0.005,
        "probe_window": None, "settle_damping": "kinetic", "footing_column": 0.0}
# Options added after runs were checkpointed without them: such a checkpoint ran with these
# values (a resume of it keeps them).
ADDED_KEPT = {"probes": [], "probes_every": 0.005, "probe_window": None, "settle_damping": "none",
              "footing_column": 0.0}
# Everything the run keeps in its checkpoint besides the engine's restart.
STATE = ("steps", "particle_steps", "grains", "solid", "lx", "ly", "load_steps", "next_field",
         "next_snap", "prepared", "settled", "prep_state", "servo_state", "settle_state",
         "next_checkpoint", "base_ids", "footing_ids", "top_fixes", "engine_cpu", "python_cpu",
         "wall")
# State added later, with its value in a checkpoint written before it.
ADDED_STATE = {"next_probe": 0, "extended_from": []}
# Default checkpoint interval: about ten minutes of one core's stepping (5e6 particle-steps/s).
CHECKPOINT_WORK = 3e9


class Stopped(Exception):
    """A signal or --stop-after-minutes: the run ends with its last checkpoint on disk."""


class blocked_signals:
    """The stop signals held back while a checkpoint is committed (delivered after it)."""
    SIGNALS = {signal.SIGTERM, signal.SIGHUP, signal.SIGINT}

    def __enter__(self):
        signal.pthread_sigmask(signal.SIG_BLOCK, self.SIGNALS)

    def __exit__(self, *exc):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, self.SIGNALS)


def stop_on_signals():
    def stop(number, frame):
        raise Stopped(signal.Signals(number).name)
    for s in blocked_signals.SIGNALS:
        signal.signal(s, stop)


def fill_options(a, pb, kept=None, source=None):
    """The options a run's results depend on: given, from `kept` (a checkpoint's), or the
    defaults. InputError naming an option given otherwise than `source` recorded."""
    for key, default in KEPT.items():
        given = getattr(a, key)
        if kept is not None and key in kept:
            if given is not None and given != kept[key]:
                raise InputError(f"--{key.replace('_', '-')} {given}: {source} was run with "
                                 f"{kept[key]}; a resume, or a --start-from of its settled "
                                 "block, keeps it")
            setattr(a, key, kept[key])
        elif given is None:
            setattr(a, key, default)
    if a.void_ratio_tolerance is None:
        a.void_ratio_tolerance = float(pb["prep"].get("void_ratio_tolerance", 0.005))
    if a.checkpoint_steps is None:
        a.checkpoint_steps = max(10_000, int(round(CHECKPOINT_WORK / pb["grains"], -3)))


def verify_checkpoint(out, a, case_digest, name="checkpoint.json"):
    """The checkpoint of `out`, checked before anything runs: its layout, the case and the
    options it was written with, and the digests of its files. InputError naming what
    differs."""
    path = os.path.join(out, name)
    if not os.path.isfile(path):
        raise InputError(f"{path}: no checkpoint to continue from")
    record = read_json(path)
    try:
        if record["format"] != FORMAT:
            raise InputError(f"{path}: a checkpoint of another layout (format "
                             f"{record['format']}, this tool writes {FORMAT})")
        stage, files, state = record["stage"], record["files"], record["state"]
        missing = [k for k in STATE if k not in state]
        missing += [k for k in ("settlement", "case", "digest") if k not in record]
        if missing or stage not in ("prepare", "settle", "settled", "load") or \
                "restart" not in files or not isinstance(record["options"], dict):
            raise KeyError(missing[0] if missing else "stage")
    except (KeyError, TypeError) as e:
        raise InputError(f"{path}: not a complete checkpoint (no {e}): damaged or edited") from None
    if record.get("digest") != record_digest(record):
        raise InputError(f"{path}: its content differs from its own digest: edited or damaged")
    if record["case"] != case_digest:
        raise InputError(f"{a.case}: differs from the case the checkpoint in {out} was written "
                         "with")
    check_digest(out, files["restart"]["name"], files["restart"])
    if stage in ("settled", "load"):
        check_digest(out, "reference.npz", files.get("reference", {"bytes": -1, "sha256": ""}))
    if stage == "load":
        check_digest(out, "history.csv", files.get("history", {"bytes": -1, "sha256": ""}),
                     prefix=True)
        if "fields" in files:
            check_digest(out, "checkpoint_results.h5", files["fields"])
        if "probes" in files:
            check_digest(out, "probes.csv", files["probes"], prefix=True)
    return record


def record_digest(record):
    """A checkpoint record's digest over everything but the digest itself."""
    body = {k: v for k, v in record.items() if k != "digest"}
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode()).hexdigest()


def case_digest(path):
    """A digest of the case's content (its JSON, key order and spacing aside)."""
    return hashlib.sha256(json.dumps(read_json(path), sort_keys=True).encode()).hexdigest()


OWN_FILES = ("history.csv", "summary.json", "results.h5", "results.xdmf", "checkpoint.json",
             "settled.json", "settled.restart", "reference.npz", "checkpoint_results.h5",
             "probes.csv")


def restore_outputs(out, record):
    """history.csv cut back to the checkpoint's rows (the rows after it are computed again)
    and results.h5 put back as it was then."""
    files = record["files"]
    with open(os.path.join(out, "history.csv"), "r+b") as f:
        f.truncate(files["history"]["bytes"])
    if "probes" in files:
        with open(os.path.join(out, "probes.csv"), "r+b") as f:
            f.truncate(files["probes"]["bytes"])
    if "fields" in files:
        shutil.copyfile(os.path.join(out, "checkpoint_results.h5"), os.path.join(out, "results.h5"))


def publish_settled(out, record):
    """settled.restart + settled.json: the settled block for --start-from."""
    name = record["files"]["restart"]["name"]
    shutil.copyfile(os.path.join(out, name), os.path.join(out, "settled.restart.tmp"))
    os.replace(os.path.join(out, "settled.restart.tmp"), os.path.join(out, "settled.restart"))
    record = json.loads(json.dumps(record))
    record["files"]["restart"]["name"] = "settled.restart"
    record["digest"] = record_digest(record)
    write_json_atomic(os.path.join(out, "settled.json"), record)
