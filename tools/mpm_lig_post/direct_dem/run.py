"""The direct DEM's run: one liggghts session at a time, the run's state, and its checkpoints,
after each of which the engine continues from the restart it wrote (as a resume would)."""
import os
import shutil
import resource
import time

from mpm_lig_post.direct_dem.block import Block
from mpm_lig_post.direct_dem.checkpoint import (ADDED_STATE, FORMAT, KEPT, STATE, Stopped,
                                                blocked_signals, record_digest)
from mpm_lig_post.direct_dem.probes import Probes
from mpm_lig_post.direct_dem.preparation import Preparation
from mpm_lig_post.liggghts import EngineFailed, Session, material_input, render
from mpm_lig_post.run_folder import digest, write_json_atomic

class Run(Preparation, Block):
    def __init__(self, pb, args, out):
        self.pb, self.args, self.out = pb, args, out
        self.session = None
        self.steps = 0          # DEM steps so far (all stages)
        self.particle_steps = 0.0
        self.grains = 0
        self.solid = self.lx = self.ly = None
        self.load_steps = self.next_field = self.next_snap = self.next_probe = 0
        self.probes = Probes(self, args.probes) if args.probes else None
        self.prepared = self.settled = None
        self.prep_state = self.servo_state = self.settle_state = None
        self.next_checkpoint = args.checkpoint_steps
        self.base_ids = self.footing_ids = None
        self.engine_cpu = self.python_cpu = self.wall = 0.0  # of earlier sittings (--resume)
        self.start = time.time()
        self.sitting_steps = 0.0
        self.last_progress = 0.0
        self.top_fixes = []     # multiplicities m of the surcharge groups topM / fixes surM
        self.stage = "prepare"
        self.last_checkpoint = None  # (stage, steps, s/B) of the newest checkpoint on disk
        self.extended_from = []      # the ends (s/B) of the finished loadings --extend continued

    # engine plumbing
    def open(self):
        self.session = Session(os.path.join(self.out, "log.liggghts"), self.out, self.args.np,
                               self.args.liggghts)

    def close(self, kill=False):
        """End the engine; its CPU seconds (those of its whole process tree) are counted."""
        if self.session is not None:
            before = children_cpu()
            self.session.close(kill)
            self.engine_cpu += children_cpu() - before
            self.session = None

    def send(self, text, work=0.0):
        return self.session.send(text, work)

    def run(self, n):
        self.send(f"run {n}", n * self.grains)
        self.steps += n
        self.particle_steps += n * self.grains

    def materials(self, friction=None):
        self.send(material_input(self.pb["rve"], friction, frictionless_types=1))

    # stress, energy
    def observe(self):
        """lx, ly, sigma_xx, sigma_yy (compression negative, per thickness), kinetic energy,
        mean overlap strain of the soil."""
        t = self.pb["thickness"]
        lx, ly, pxx, pyy, ke, ov = self.session.values(
            "OBS", ["lx", "ly", "c_stress[1]", "c_stress[2]", "c_ke", "c_ov"])
        return {"lx": lx, "ly": ly, "sxx": -pxx / t, "syy": -pyy / t, "ke": ke, "ov": ov}

    def kinetic_ratio(self, o, area, p):
        elastic = 0.8 * max(p, 1e-12) * area * self.pb["thickness"] * max(o["ov"], 1e-12)
        return o["ke"] / elastic

    def observers(self):
        """The computes the preparation reads (also after a reload)."""
        self.send(render("dynamics.in", {"time_step": repr(self.pb["dt"])}, {"two_d"}))
        self.send("compute ke all ke\ncompute pl all pair/gran/local id force delta\n"
                  "compute ov all reduce ave c_pl[7]\n"
                  "thermo_style custom step atoms c_stress[1] c_stress[2] c_ke c_ov\n"
                  "thermo_modify norm no lost ignore\nthermo 0")

    # ------------------------------------------------------------------- checkpoints
    def safe_point(self, stage):
        """Between two chunks of DEM steps: a checkpoint when one is due (every
        --checkpoint-steps), after which the engine continues from the file it wrote; and the
        stop that --stop-after-minutes asks, at such a checkpoint. True when the engine was
        reloaded (the caller reads its state again)."""
        if self.steps < self.next_checkpoint:
            return False
        while self.next_checkpoint <= self.steps:
            self.next_checkpoint += self.args.checkpoint_steps
        self.checkpoint(stage)
        limit = self.args.stop_after_minutes
        if limit and time.time() - self.start > 60 * limit:
            raise Stopped(f"--stop-after-minutes {limit:g}")
        return True

    def checkpoint(self, stage, reload=True):
        """The engine's restart and checkpoint.json (the commit point, written last, with the
        digests of the files a resume needs); then the engine is started again from that
        restart, as a resume would start it, so that stopping here changes nothing."""
        restart = f"checkpoint_{self.steps:012d}.restart"
        path = os.path.join(self.out, restart)
        self.send(f'write_restart "{path}"', self.grains * 10)
        if not os.path.isfile(path) or os.path.getsize(path) < 1000:
            raise EngineFailed(f"{path}: write_restart left no usable file (disk full?)")
        self.close()
        with blocked_signals():
            files = {"restart": {"name": restart, **digest(path)}}
            history = os.path.join(self.out, "history.csv")
            if os.path.isfile(history):
                files["history"] = digest(history)
            probes = os.path.join(self.out, "probes.csv")
            if os.path.isfile(probes):
                files["probes"] = digest(probes)
            fields = os.path.join(self.out, "results.h5")
            if os.path.isfile(fields):
                shutil.copyfile(fields, os.path.join(self.out, "checkpoint_results.h5"))
                files["fields"] = digest(os.path.join(self.out, "checkpoint_results.h5"))
            reference = os.path.join(self.out, "reference.npz")
            if os.path.isfile(reference):
                files["reference"] = digest(reference)
            own = resource.getrusage(resource.RUSAGE_SELF)
            state = {k: getattr(self, k) for k in (*STATE, *ADDED_STATE)}
            state.update(python_cpu=self.python_cpu + own.ru_utime + own.ru_stime,
                         wall=self.wall + time.time() - self.start)
            record = {"format": FORMAT, "stage": stage, "case": self.args.case_digest,
                      "options": {k: getattr(self.args, k) for k in KEPT},
                      "settlement": self.args.settlement, "files": files, "state": state}
            record["digest"] = record_digest(record)
            write_json_atomic(os.path.join(self.out, "checkpoint.json"), record)
            for name in os.listdir(self.out):
                if name.startswith("checkpoint_") and name.endswith(".restart") and name != restart:
                    os.remove(os.path.join(self.out, name))
        self.last_checkpoint = (stage, self.steps, self.load_steps)
        self.progress(f"checkpoint at step {self.steps} ({stage})", force=True)
        if reload:
            self.restore(record, path, cpu_counted=True)
        return record

    def restore(self, record, restart, cpu_counted=False):
        """The engine started from `restart` and the run's state from `record` (a checkpoint's
        or a settled block's): the same commands whether the run goes on or resumes."""
        sitting = (self.python_cpu, self.wall)
        for k in STATE:
            setattr(self, k, record["state"][k])
        for k, before in ADDED_STATE.items():
            setattr(self, k, record["state"].get(k, before))
        if cpu_counted:  # the same sitting: its own seconds are counted at its end
            self.python_cpu, self.wall = sitting
        self.stage = record["stage"]
        self.open()
        self.send(render("restart.in", {"restart_file": f'"{restart}"',
                                        "skin": repr(0.4 * 0.5 * self.pb["d"])}, {"two_d"}))
        self.materials(self.prep_state["friction"] if self.stage == "prepare" else None)
        self.observers()
        if self.stage != "prepare":
            self.dynamics()
            # the surcharge groups came back with the restart, their forces did not
            self.send("\n".join(f"group top{m} delete" for m in self.top_fixes))
        self.top_fixes = []
        if self.stage == "load":
            self.push()
        self.send("run 0")


    # ------------------------------------------------------------------- bookkeeping

    # ------------------------------------------------------------------- bookkeeping
    def progress(self, text, force=False):
        now = time.time()
        if force or now - self.last_progress > 10:
            rate = (self.particle_steps - self.sitting_steps) / max(now - self.start, 1e-9)
            print(f"[{(now - self.start) / 60:6.1f} min] {text} ({rate / 1e6:.2f} M "
                  "particle-steps/s)", flush=True)
            self.last_progress = now


def children_cpu():
    """CPU seconds of this process's ended children (the engines and their MPI ranks)."""
    own = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime
