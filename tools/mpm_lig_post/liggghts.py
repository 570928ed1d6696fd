"""The native `liggghts` executable as the project's tools drive it: the mpm_lig engine
templates (lmp_inputs/liggghts) rendered with a case's contact law, batch runs of an input
script, and an interactive session fed command by command (tools/native_twin.py,
tools/direct_dem.py)."""
import math
import os
import shutil
import subprocess
import time

from mpm_lig_post.errors import InputError

TEMPLATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "lmp_inputs",
                         "liggghts")


def require_templates():
    """The engine templates are there, else an InputError saying where they should be: a copy
    of tools/ or an installed package without the checkout's lmp_inputs/ beside it has none."""
    if not os.path.isdir(TEMPLATES):
        raise InputError(f"{os.path.normpath(TEMPLATES)}: the engine's input templates are not "
                         "there (run the tool from an mpm_lig checkout, whose tools/ lies "
                         "beside lmp_inputs/)")


def render(name, values, flags):
    """An mpm_lig engine template: ${name} filled in, '#@if FLAG' blocks kept when FLAG is set."""
    out, keep = [], True
    for line in open(os.path.join(TEMPLATES, name)).read().splitlines():
        if line.startswith("#@if "):
            keep = line[5:].strip() in flags
        elif line.startswith("#@endif"):
            keep = True
        elif keep and line and not line.startswith("#"):
            for key, value in values.items():
                line = line.replace("${" + key + "}", value)
            out.append(line)
    return "\n".join(out) + "\n"


def contact_values(rve):
    """The case's contact law as the engine takes it (src/rve/spec.cpp)."""
    c = rve["contact"]
    if "poisson_ratio" in c:
        nu = c["poisson_ratio"]
    else:
        nu = (2.0 - 2.0 * c["stiffness_ratio"]) / (2.0 - c["stiffness_ratio"])
    if "restitution" in c:
        e = c["restitution"]
    else:
        z = c["damping_ratio"]
        e = math.exp(-math.pi * z / math.sqrt(1.0 - z * z))
    mu = c["friction"] if "friction" in c else math.tan(math.radians(c["friction_deg"]))
    values = {"youngs_modulus": repr(float(c["youngs_modulus"])), "poisson_ratio": repr(nu),
              "restitution": repr(e), "friction": repr(mu), "rolling_model": "",
              "cohesion_model": ""}
    flags = {"two_d"} if rve.get("dimension", 3) == 2 else set()
    if "rolling_friction" in c:
        values["rolling_friction"] = repr(float(c["rolling_friction"]))
        values["rolling_model"] = " rolling_friction epsd2"
        flags.add("rolling")
    if "cohesion_energy_density" in c:
        values["cohesion_energy_density"] = repr(float(c["cohesion_energy_density"]))
        values["cohesion_model"] = " cohesion sjkr"
        flags.add("cohesion")
    return values, flags


def rayleigh_time_step(rve):
    """The Rayleigh time step of the smallest grain (src/rve/spec.cpp)."""
    values, _ = contact_values(rve)
    nu = float(values["poisson_ratio"])
    shear = float(values["youngs_modulus"]) / (2.0 * (1.0 + nu))
    return math.pi * rve["radius"]["min"] * math.sqrt(rve["density"] / shear) / (0.1631 * nu + 0.8766)


def material_input(rve, friction=None, frictionless_types=0):
    """material.in for the case's contact law at `friction` (default: the case's), with
    `frictionless_types` more atom types (walls) whose contacts with everything have neither
    sliding nor rolling friction (their stiffness, Poisson ratio and restitution are the grains')."""
    values, flags = contact_values(rve)
    if friction is not None:
        values["friction"] = repr(float(friction))
    n = 1 + frictionless_types
    if n > 1:
        for key in ("youngs_modulus", "poisson_ratio"):
            values[key] = " ".join([values[key]] * n)
        pair = lambda v, rough: " ".join(v if (i == 0 and j == 0) or not rough else "0.0"
                                         for i in range(n) for j in range(n))
        values["restitution"] = pair(values["restitution"], False)
        values["friction"] = pair(values["friction"], True)
        if "rolling_friction" in values:
            values["rolling_friction"] = pair(values["rolling_friction"], True)
    text = render("material.in", values, flags)
    return text.replace("peratomtypepair 1 ", f"peratomtypepair {n} ")


class RunFailed(Exception):
    """mpm_lig or liggghts failed: exit code 1."""


def error_line(log):
    """The first line of an engine's or mpm_lig's log that says what went wrong, or ''. Read
    leniently: an engine echoes the bytes of a damaged file into its log."""
    try:
        with open(log, "rb") as f:
            lines = f.read().decode("utf-8", errors="replace").splitlines()
    except OSError:
        return ""
    return next((ln.strip() for ln in lines if ln.lstrip().startswith("ERROR")
                 or ": error:" in ln), "")


def run_command(command, cwd, log, restart=None):
    """Run `command` in `cwd` with its output in `log`. A failure is RunFailed with the log's
    error line; liggghts failing to read `restart` is the restart's fault (InputError)."""
    with open(log, "w") as f:
        code = subprocess.run(command, cwd=cwd, stdout=f, stderr=subprocess.STDOUT).returncode
    if code != 0:
        line = error_line(log)
        if restart and "restart" in line.lower():
            raise InputError(f"{restart}: {os.path.basename(command[0])} cannot read it "
                             f"({line}): a damaged or truncated restart file (log: {log})")
        raise RunFailed(f"{' '.join(command)} failed (exit {code})"
                        + (f": {line}" if line else "") + f"; see {log}")


def executable(name="liggghts"):
    return shutil.which(name) or name


class EngineFailed(RuntimeError):
    """The engine process stopped, reported an ERROR or did not answer in time."""


# Seconds a batch of commands may take beyond its DEM work before the engine counts as hung,
# and the slowest stepping rate (particle-steps per second) that still counts as working: a
# fiftieth of a core's rate here, so two runs sharing a core on a loaded machine stay inside.
ANSWER_SECONDS = 120.0
SLOWEST_RATE = 1e5
# Seconds the engine has to print its banner; the tests shorten it (an engine that hangs).
START_SECONDS = float(os.environ.get("MPM_LIG_TEST_ENGINE_START_SECONDS", 60.0))


def _die_with_parent():
    """In the engine's process: end it when the tool dies, even by SIGKILL (Linux prctl)."""
    try:
        import ctypes
        import signal
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


class Session:
    """An interactive liggghts process: commands go to its standard input, `send` returns
    the screen lines they printed (each batch ends with a marker the engine prints).
    Everything the engine prints is also kept in `log`. np > 1 runs it under mpirun. The
    engine runs in its own process group (a Ctrl-C in the terminal reaches the tool, which
    ends the engine itself) and dies with the tool."""

    MARK = "MPM_LIG_BATCH_DONE"

    def __init__(self, log, cwd, np=1, binary=None):
        import queue
        import threading

        binary = binary or executable()
        command = ["stdbuf", "-oL", binary, "-echo", "none", "-log", "none"]
        if np > 1:
            command = ["mpirun", "-np", str(np)] + command
        self.log = open(log, "a")
        self.lines = queue.Queue()
        self.proc = subprocess.Popen(command, cwd=cwd, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                     bufsize=1, start_new_session=True,
                                     preexec_fn=_die_with_parent)
        threading.Thread(target=self._read, daemon=True).start()
        banner = self.send("", seconds=START_SECONDS)
        if not any("LIGGGHTS" in line for line in banner):
            self.close()
            raise EngineFailed(f"{binary} answered without the LIGGGHTS banner: not the liggghts "
                               "executable")

    def _read(self):
        for line in self.proc.stdout:
            self.lines.put(line)
        self.lines.put(None)

    def send(self, commands, work=0.0, seconds=None):
        """Run the commands (a string of lines); the lines they printed. EngineFailed when the
        engine stops, reports an ERROR, or takes longer than ANSWER_SECONDS plus `work`
        particle-steps at SLOWEST_RATE (or `seconds`)."""
        import queue

        limit = seconds if seconds is not None else ANSWER_SECONDS + work / SLOWEST_RATE
        try:
            self.proc.stdin.write(commands.rstrip("\n") + f'\nprint "{self.MARK}"\n')
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            pass  # the engine has ended: what it printed is read below, then its exit code
        out = []
        deadline = time.monotonic() + limit
        while True:
            try:
                line = self.lines.get(timeout=max(deadline - time.monotonic(), 0.0))
            except queue.Empty:
                self.close(kill=True)
                raise EngineFailed(f"liggghts did not answer within {limit:.0f} s (hung, or "
                                   f"not the liggghts executable); last command: "
                                   f"{commands.strip()[-200:]}") from None
            if line is None:
                self.proc.wait()
                tail = "".join(out[-15:])
                raise EngineFailed(f"liggghts stopped (exit {self.proc.returncode}); its last "
                                   f"lines:\n{tail}")
            self.log.write(line)
            if line.strip() == self.MARK:
                return out
            if line.startswith("ERROR"):
                self.close(kill=True)
                raise EngineFailed(f"liggghts: {line.strip()} (after: {commands.strip()[-300:]})")
            out.append(line)

    def values(self, tag, expressions):
        """Evaluate LIGGGHTS immediate expressions ($(...)) now: a list of floats."""
        text = " ".join(f"$({e})" for e in expressions)
        for line in self.send(f'print "{tag} {text}"'):
            if line.startswith(tag + " "):
                return [float(v) for v in line.split()[1:]]
        raise EngineFailed(f"liggghts printed no {tag} line")

    def close(self, kill=False):
        """End the engine: `quit` and a wait, or at once with `kill`; its whole group."""
        import signal

        if self.proc.poll() is None:
            if not kill:
                try:
                    self.proc.stdin.write("quit\n")
                    self.proc.stdin.flush()
                    self.proc.wait(timeout=30)
                except (BrokenPipeError, OSError, subprocess.TimeoutExpired):
                    pass
            if self.proc.poll() is None:
                try:
                    os.killpg(self.proc.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                self.proc.wait()
        try:
            self.proc.stdin.close()
        except (BrokenPipeError, OSError):
            pass
        if not self.log.closed:
            self.log.close()
