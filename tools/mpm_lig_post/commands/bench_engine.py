"""Library API vs native executable on the same DEM work (≈400 dense grains under shear).

The box is orthogonal and sheared by pure shear (x stretched, y compressed at equal rates):
native LIGGGHTS 3.8 cannot run triclinic periodic boxes (atoms are lost; the library path
corrects that, see src/dem/liggghts_engine.cpp), so simple shear with a tilt would compare a
broken native run with a working library run.

usage: bench_engine.py [--build DIR] [--steps N] [--repeats R] [--engines liggghts,lammps]
                       [--json FILE]

For each engine: builds a jittered dense packing once with the native executable (written as
an engine restart file), then times, alternately and R times each:
  native         `liggghts`/`lmp` on the work input; time = the engine's own "Loop time"
  native-chunked the native executable with the same `run 100 pre yes post no` calls as
                 lib-chunked; time = wall time of that process minus the wall time of the
                 same input without runs (so it includes each run's setup, as lib-chunked)
  lib-1call      bench_engine (library API through mpm_lig_dem): one `run N` call
  lib-chunked    bench_engine: N steps as `run 100` calls (how RVEs are driven)
Library times are wall times around the run calls (they include each call's setup).
Prints a table of particle-steps/s (median of the repeats) and time ratios: lib-1call and
native-chunked against native, lib-chunked against native-chunked (the cost of our path for
the same engine work; the engine's own per-run setup is in both). Writes JSON.
"""
import json
import os
import random
import re
import shutil
import statistics
import subprocess
import tempfile
import time

from mpm_lig_post import checkout, cli
from mpm_lig_post.errors import InputError

NATIVE = {"liggghts": ["liggghts"], "lammps": ["lmp", "-nocite"]}
SPACING = 0.01
N_SIDE = (7, 7, 8)  # 392 grains


def packing(seed=1):
    rnd = random.Random(seed)
    grains = []
    for i in range(N_SIDE[0]):
        for j in range(N_SIDE[1]):
            for k in range(N_SIDE[2]):
                x = [(c + 0.5) * SPACING + rnd.uniform(-0.02, 0.02) * SPACING for c in (i, j, k)]
                grains.append((x, SPACING * rnd.uniform(1.0, 1.04)))
    return grains


def material_lines(engine):
    if engine == "liggghts":
        return """fix m1 all property/global youngsModulus peratomtype 7e8
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
"""
    return """comm_modify vel yes
pair_style granular
pair_coeff * * hertz/material 7e8 0.5 0.3 tangential mindlin NULL 1.0 0.5 damping tsuji
"""


def prep_input(engine, restart):
    lx, ly, lz = (n * SPACING for n in N_SIDE)
    head = ("units si\natom_style granular\natom_modify map array\nnewton off\n"
            "communicate single vel yes\n" if engine == "liggghts" else
            "units si\natom_style sphere\natom_modify map array\n")
    lines = [head, "boundary p p p\n",
             f"region box block 0 {lx} 0 {ly} 0 {lz} units box\ncreate_box 1 box\n",
             "neighbor 0.001 bin\nneigh_modify delay 0\n", material_lines(engine)]
    for n, (x, d) in enumerate(packing(), start=1):
        lines.append(f"create_atoms 1 single {x[0]} {x[1]} {x[2]} units box\n"
                     f"set atom {n} diameter {d} density 2650\n")
    lines.append("fix integrate all nve/sphere\ntimestep 2e-6\nrun 2000\n"
                 f"write_restart {restart}\n")
    return "".join(lines)


def work_input(engine, restart):
    return (f"read_restart {restart}\n" + ("newton off\ncommunicate single vel yes\n" if engine == "liggghts"
                                           else "") + material_lines(engine) +
            "neighbor 0.001 bin\nneigh_modify delay 0\nfix integrate all nve/sphere\n"
            "timestep 2e-6\ncompute p all pressure thermo_temp virial\n"
            "thermo_style custom step atoms c_p[1]\nthermo 1000\n"
            "fix shear all deform 1 x erate 5.0 y erate -5.0 remap x\n")


def run_native(engine, path, steps, workdir):
    log = os.path.join(workdir, f"{engine}.native.log")
    subprocess.run(NATIVE[engine] + ["-in", path, "-screen", "none", "-log", log],
                   check=True, cwd=workdir, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    text = open(log).read()
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps", text)
    seconds, done = loops[-1]
    assert int(done) == steps, f"native run did {done} steps"
    return float(seconds)


def run_native_wall(engine, path, workdir):
    start = time.perf_counter()
    subprocess.run(NATIVE[engine] + ["-in", path, "-screen", "none", "-log", "none"],
                   check=True, cwd=workdir, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def run_library(bench, engine, path, steps, chunk, workdir):
    out = subprocess.run([bench, engine, path, str(steps), str(chunk)], check=True, cwd=workdir,
                         capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])["seconds"]


def main():
    ap = cli.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=checkout.path("build"))
    ap.add_argument("--steps", type=cli.positive_int, default=4000)
    ap.add_argument("--chunk", type=cli.positive_int, default=100)
    ap.add_argument("--repeats", type=cli.positive_int, default=5)
    ap.add_argument("--engines", default="liggghts,lammps")
    ap.add_argument("--json", default="bench_engine.json")
    args = ap.parse_args()
    cli.writable_file(args.json, "--json file")
    engines = args.engines.split(",")
    unknown = [e for e in engines if e not in NATIVE]
    if unknown:
        raise InputError(f"--engines: unknown engine(s) {', '.join(unknown)} (known: "
                         f"{', '.join(NATIVE)})")
    bench = os.path.abspath(os.path.join(args.build, "bench_engine"))
    if not os.access(bench, os.X_OK) or os.path.isdir(bench):
        raise InputError(f"--build {args.build}: no bench_engine program in it (build the "
                         "project there, or give its build folder)")
    workdir = tempfile.mkdtemp(prefix="bench_engine_")
    grains = len(packing())
    results = []
    for engine in engines:
        if not shutil.which(NATIVE[engine][0]):
            print(f"skipping {engine}: no native executable")
            continue
        restart = os.path.join(workdir, f"{engine}.restart")
        prep = os.path.join(workdir, f"{engine}.prep.in")
        open(prep, "w").write(prep_input(engine, restart))
        subprocess.run(NATIVE[engine] + ["-in", prep, "-screen", "none", "-log", "none"],
                       check=True, cwd=workdir, stdout=subprocess.DEVNULL)
        work = os.path.join(workdir, f"{engine}.work.in")
        open(work, "w").write(work_input(engine, restart))
        native_in = os.path.join(workdir, f"{engine}.native.in")
        open(native_in, "w").write(work_input(engine, restart) + f"run {args.steps}\n")
        chunked_in = os.path.join(workdir, f"{engine}.native_chunked.in")
        runs = f"run {args.chunk} pre yes post no\n" * (args.steps // args.chunk)
        open(chunked_in, "w").write(work_input(engine, restart) + runs)
        times = {"native": [], "native-chunked": [], "lib-1call": [], "lib-chunked": []}
        for _ in range(args.repeats):  # alternate, so that load changes hit all alike
            times["native"].append(run_native(engine, native_in, args.steps, workdir))
            times["native-chunked"].append(run_native_wall(engine, chunked_in, workdir) -
                                           run_native_wall(engine, work, workdir))
            times["lib-1call"].append(
                run_library(bench, engine, work, args.steps, args.steps, workdir))
            times["lib-chunked"].append(
                run_library(bench, engine, work, args.steps, args.chunk, workdir))
        medians = {mode: statistics.median(ts) for mode, ts in times.items()}
        reference = {"native": "native", "native-chunked": "native", "lib-1call": "native",
                     "lib-chunked": "native-chunked"}
        for mode, ts in times.items():
            med = medians[mode]
            results.append({"engine": engine, "mode": mode, "grains": grains,
                            "steps": args.steps,
                            "chunk": args.chunk if mode.endswith("chunked") else args.steps,
                            "seconds": ts, "median_seconds": med,
                            "particle_steps_per_s": grains * args.steps / med,
                            "compared_with": reference[mode],
                            "ratio": med / medians[reference[mode]]})
    print(f"{'engine':9} {'mode':15} {'M particle-steps/s':>19} {'time ratio':>11}  (median of "
          f"{args.repeats}, {grains} grains, {args.steps} steps)")
    for r in results:
        print(f"{r['engine']:9} {r['mode']:15} {r['particle_steps_per_s'] / 1e6:19.3f} "
              f"{r['ratio']:11.3f}  vs {r['compared_with']}")
    json.dump(results, open(args.json, "w"), indent=1)
    print(f"wrote {args.json}; inputs in {workdir}")


def entry():
    """The command: tools/bench_engine.py in a checkout (it needs the checkout's files)."""
    cli.run(main, failures=subprocess.CalledProcessError)


if __name__ == "__main__":
    entry()
