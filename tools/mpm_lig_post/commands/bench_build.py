#!/usr/bin/python3
"""Cold-build benchmark: configures the tree into a fresh temporary folder (no ccache), builds
the given targets and measures the CPU time (user + sys) of every compile and link step.

    tools/bench_build.py [--target mpm_lig] [--jobs 2] [--json out.json] [-- extra cmake args]

Prints the total CPU, the wall time, the longest chain of dependent steps (the critical path:
a static library's objects, its archive, the objects of what links it, ...) and the ten most
expensive translation units; writes the same as JSON. On a shared machine the wall time is
noisy; the CPU times are not, and the expected wall time on P cores is
max(total CPU / P, critical path).
"""
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

# The checkout: this module is tools/mpm_lig_post/commands/bench_build.py. It also runs as a
# plain script (the compiler launcher, --launch), so it needs nothing of the package at import.
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))


def launch(log, cmd):
    """Runs one compiler or linker command and appends its CPU and wall time to `log`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    rc = subprocess.call(cmd)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    out = cmd[cmd.index("-o") + 1] if "-o" in cmd else ""
    src = cmd[cmd.index("-c") + 1] if "-c" in cmd else ""
    kind = "compile" if src else "link"
    if not src and len(cmd) > 2 and os.path.basename(cmd[0]) in ("ar", "gcc-ar"):
        out = cmd[2]
    with open(log, "a") as f:
        f.write(json.dumps({"kind": kind, "source": src, "output": out, "cpu": round(cpu, 3),
                            "wall": round(wall, 3), "rc": rc, "end": time.time()}) + "\n")
    return rc


def relative(path):
    path = os.path.realpath(path) if path else path
    return os.path.relpath(path, ROOT) if path.startswith(ROOT) else path


def critical_path(steps, build):
    """Longest chain of dependent steps, in CPU seconds, from ninja's own graph: every input of
    a step (explicit, implicit, order-only, through phony targets) must be built before it."""
    cpu = {os.path.normpath(s["output"]): s["cpu"] for s in steps}
    memo = {}

    def inputs(node):
        query = subprocess.run(["ninja", "-C", build, "-t", "query", node], capture_output=True,
                               text=True).stdout
        found, section = [], None
        for line in query.splitlines()[1:]:
            text = line.strip()
            if text.startswith("input:"):
                section = "input"
            elif text.startswith("outputs:"):
                section = "outputs"
            elif section == "input":
                found.append(text.lstrip("|").strip())
        # Names relative to the build folder are its products (or phony); sources are absolute.
        return [n for n in found if not os.path.isabs(n)]

    def longest(node):
        if node not in memo:
            memo[node] = 0.0  # guards against cycles
            memo[node] = cpu.get(node, 0.0) + max((longest(n) for n in inputs(node)), default=0.0)
        return memo[node]

    return max((longest(n) for n in cpu), default=0.0)


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--launch":
        sys.exit(launch(sys.argv[2], sys.argv[3:]))
    from mpm_lig_post import cli
    from mpm_lig_post.errors import InputError

    parser = cli.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--target", action="append", help="target(s) to build; default: mpm_lig")
    parser.add_argument("--all", action="store_true", help="build the whole tree (tests too)")
    parser.add_argument("--jobs", type=cli.positive_int, default=2)
    parser.add_argument("--json", help="write the results here")
    parser.add_argument("--keep", help="build in this folder (kept) instead of a temporary one")
    parser.add_argument("--resume", action="store_true",
                        help="with --keep: build the targets in that folder as it stands (its "
                        "log goes on) and report every step it ever logged, e.g. the tests "
                        "after the program")
    parser.add_argument("--generator", default="Ninja",
                        help="CMake generator (the critical path is known for Ninja only)")
    parser.add_argument("--label", default="", help="a name for this configuration")
    parser.add_argument("cmake_args", nargs="*", help="extra arguments to cmake (after --)")
    args = parser.parse_args()
    targets = [] if args.all else (args.target or ["mpm_lig"])
    if args.resume and not args.keep:
        parser.error("--resume needs --keep")
    cli.writable_file(args.json, "--json file")
    if args.keep:
        cli.writable_folder(args.keep, "--keep folder")
        # --keep starts afresh by deleting the folder: only a bench build of its own.
        if (os.path.isdir(args.keep) and os.listdir(args.keep)
                and not os.path.isfile(os.path.join(args.keep, "steps.jsonl"))):
            raise InputError(f"--keep {args.keep}: not a bench_build folder (no steps.jsonl): "
                             "not deleted; give a new or empty folder")

    build = args.keep or tempfile.mkdtemp(prefix="mpm_lig_bench_build_")
    if args.keep and os.path.exists(build) and not args.resume:
        shutil.rmtree(build)
    os.makedirs(build, exist_ok=True)
    log = os.path.join(build, "steps.jsonl")
    launcher = f"{sys.executable};{os.path.abspath(__file__)};--launch;{log}"
    env = dict(os.environ, CCACHE_DISABLE="1")
    configure = ["cmake", "-S", ROOT, "-B", build, "-G", args.generator,
                 "-DCMAKE_BUILD_TYPE=Release",
                 f"-DCMAKE_CXX_COMPILER_LAUNCHER={launcher}",
                 f"-DCMAKE_C_COMPILER_LAUNCHER={launcher}",
                 f"-DCMAKE_CXX_LINKER_LAUNCHER={launcher}"] + args.cmake_args
    try:
        if not args.resume:
            subprocess.run(configure, check=True, stdout=subprocess.DEVNULL, env=env)
        start = time.monotonic()
        # The build's output (with any compiler warning) is kept in the folder's build.log.
        with open(os.path.join(build, "build.log"), "a") as out:
            subprocess.run(["cmake", "--build", build, "-j", str(args.jobs)] +
                           (["--target"] + targets if targets else []), check=True,
                           stdout=out, stderr=subprocess.STDOUT, env=env)
        wall = time.monotonic() - start
        with open(os.path.join(build, "build.log")) as f:
            warnings = sum("warning:" in line for line in f)
        with open(log) as f:
            # A step that failed and was run again (after a fix, with --resume) counts once.
            steps = [s for s in map(json.loads, f) if s.get("rc", 0) == 0]
        path = critical_path(steps, build) if args.generator == "Ninja" else float("nan")
    finally:
        if not args.keep:
            shutil.rmtree(build, ignore_errors=True)

    compiles = sorted((s for s in steps if s["kind"] == "compile"), key=lambda s: -s["cpu"])
    total = sum(s["cpu"] for s in steps)
    result = {
        "label": args.label, "targets": targets or ["all"], "jobs": args.jobs,
        "cmake_args": args.cmake_args, "translation_units": len(compiles),
        "cpu_total_s": round(total, 1),
        "cpu_compile_s": round(sum(s["cpu"] for s in compiles), 1),
        "cpu_link_s": round(sum(s["cpu"] for s in steps if s["kind"] == "link"), 1),
        "critical_path_s": round(path, 1), "wall_s": round(wall, 1), "warnings": warnings,
        "expected_wall_2_cores_s": round(max(total / 2, path if path == path else 0), 1),
        "units": [{"source": relative(s["source"]), "cpu_s": s["cpu"]} for s in compiles],
    }
    print(f"targets {' '.join(result['targets'])}  {args.label}")
    print(f"{'translation units':<34}{len(compiles):>10}")
    for key, name in (("cpu_total_s", "CPU total (user+sys) [s]"),
                      ("cpu_compile_s", "  of it compiling [s]"),
                      ("cpu_link_s", "  of it linking/archiving [s]"),
                      ("critical_path_s", "critical path (CPU) [s]"),
                      ("expected_wall_2_cores_s", "expected wall on 2 cores [s]"),
                      ("wall_s", f"measured wall, -j{args.jobs} [s]"),
                      ("warnings", "compiler warnings")):
        print(f"{name:<34}{result[key]:>10}")
    print("ten most expensive translation units (CPU s):")
    for unit in result["units"][:10]:
        print(f"  {unit['cpu_s']:8.1f}  {unit['source']}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=1)


def entry():
    from mpm_lig_post import cli

    cli.run(main, failures=subprocess.CalledProcessError)


if __name__ == "__main__":
    main()
