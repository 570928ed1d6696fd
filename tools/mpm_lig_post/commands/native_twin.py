"""Native LIGGGHTS twin of an mpm_lig element test: the same test run by the `liggghts`
executable from a plain input script, and the two stress-strain curves compared.

usage: native_twin.py CASE.json --output DIR [--mpm-lig PATH] [--liggghts PATH]
                      [--chunk N] [--library-run RUN_DIR] [--dpi N]

CASE.json is an element test (isotropic_compression, drained_biaxial, drained_triaxial) whose
box is orthogonal. mpm_lig runs it into DIR/library (or --library-run names a finished run with
its prepared.restart); then DIR/native/in.twin is written and run with liggghts:
- the same packing: read_restart of the library run's prepared.restart (contact history kept);
- the same contact law, time step, integration and stress (the mpm_lig templates in
  lmp_inputs/liggghts rendered with the case's values);
- the same mean strain rate: the library run's final axial (isotropic: per-axis) log strain
  over its DEM time, applied as `fix deform ... erate` from start to end, with the grains
  given the affine (streaming) velocity of the box, as the library path does;
- the confining stress held by a servo on the lateral axes, updated every --chunk DEM steps
  (default 100): lateral strain rate = proportional + integral terms of the stress error
  over (K x chunk time), K the library run's measured servo_stiffness (SERVO_P, SERVO_I).
Output: DIR/native/history.csv (the element-test columns), DIR/twin.json and DIR/twin.png
(deviator and volumetric strain over axial strain, both paths), and a table: peak and 10-15 %
mobilised friction angles, largest dilatancy angle (differences in degrees) and the RMS
difference of the curves (relative to the library's largest deviator).
Exit 2 on bad input (not an element test, sheared box, missing file, a prepared.restart that
liggghts cannot read), 1 when a run fails (its error line and log named on stderr).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import checkout, cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.liggghts import (RunFailed, contact_values, render,  # noqa: E402
                                    require_templates, run_command)
from mpm_lig_post.quantities import PRESETS, Run, principal_series  # noqa: E402
from mpm_lig_post.tables import need, read_history, read_json, read_text  # noqa: E402
from mpm_lig_post.tradeoff import error  # noqa: E402

TESTS = ("isotropic_compression", "drained_biaxial", "drained_triaxial")
# Servo gains on the lateral strain rate, in units of (stress error) / (K x chunk time):
# proportional, and integral (the steady widening a dilating packing needs).
SERVO_P, SERVO_I = 0.5, 0.1


def check_case(case, path):
    rve, analysis = case.get("rve"), case.get("analysis", {})
    if analysis.get("type") != "element_test" or not isinstance(rve, dict):
        raise InputError(f"{path}: analysis.type: not an element test")
    if analysis.get("test") not in TESTS:
        raise InputError(f"{path}: analysis.test: '{analysis.get('test')}' has no native twin "
                         f"(supported: {', '.join(TESTS)})")
    if rve.get("engine", "liggghts") != "liggghts":
        raise InputError(f"{path}: rve.engine: the twin runs the liggghts executable")
    if rve.get("affine_motion", "streaming_velocity") != "streaming_velocity":
        raise InputError(f"{path}: rve.affine_motion: the twin streams velocities (remap v)")


def twin_input(case, library, chunk):
    """The native input script and the number of chunks it runs."""
    rve = case["rve"]
    summary = read_json(os.path.join(library, "summary.json"))
    table = read_history(os.path.join(library, "history.csv"))
    dim = rve.get("dimension", 3)
    radius = rve["radius"]
    mean_radius = 0.5 * (radius["min"] + radius["max"])
    thickness = rve.get("thickness", 2.0 * mean_radius) if dim == 2 else 1.0
    dt = need(summary, "time_step", os.path.join(library, "summary.json"), number=True)
    axes = "xyz"[:dim]
    test = case["analysis"]["test"]
    axial = axes[-1]
    strain = -table[f"e_{axial}{axial}"][-1]  # compression positive, log strain
    rate = strain / table["time"][-1]
    chunks = math.ceil(table["time"][-1] / dt / chunk)
    values, flags = contact_values(rve)
    script = [f"# Native twin of {case.get('title', 'an mpm_lig element test')}",
              render("restart.in", {"restart_file": '"' + os.path.abspath(
                  os.path.join(library, "prepared.restart")) + '"', "skin": repr(0.4 * mean_radius)},
                  flags),
              render("material.in", values, flags),
              render("dynamics.in", {"time_step": repr(dt)}, flags),
              "thermo_style custom step lx ly lz c_stress[1] c_stress[2] c_stress[3] c_stress[4]",
              "thermo_modify norm no lost ignore", "thermo 0", "run 0",
              # The executable lacks the library path's triclinic correction (docs/DESIGN.md
              # §3.2): an orthogonal box keeps its periodic images. change_box is refused
              # until a run has taken the restart's per-atom data, and that first run sees no
              # images: contacts across the cell lose their history there (0.2 % of the
              # initial pressure on a 400-disc packing).
              "change_box all ortho", "run 0"]
    servo = [] if test == "isotropic_compression" else list(axes[:-1])
    p0 = summary.get("confining_pressure", 0.0)
    stiffness = summary.get("servo_stiffness", 1.0)
    scale = thickness if dim == 2 else 1.0
    for a in axes:
        script.append(f"variable r_{a} equal {-rate if a not in servo else 0.0!r}")
        script.append(f"variable i_{a} equal 0.0")
    # Streaming velocity of the initial rates; later changes are added chunk by chunk.
    stream = " ".join(f"v_s_{a}" if a in axes else "NULL" for a in "xyz")
    for a in "xyz"[:dim]:
        script.append(f"variable s_{a} atom ${{r_{a}}}*({a}-${{c_{a}}})".replace(
            f"${{c_{a}}}", f"({a}lo+{a}hi)/2"))
    script += [f"velocity all set {stream} sum yes units box", "velocity all zero linear",
               "variable twin_step equal step", "variable twin_lx equal lx",
               "variable twin_ly equal ly", "variable twin_lz equal lz",
               "variable twin_sxx equal -c_stress[1]/" + repr(scale),
               "variable twin_syy equal -c_stress[2]/" + repr(scale),
               "variable twin_szz equal -c_stress[3]/" + repr(scale),
               "variable twin_sxy equal -c_stress[4]/" + repr(scale),
               'print "TWIN ${twin_step} ${twin_lx} ${twin_ly} ${twin_lz} ${twin_sxx} ${twin_syy} '
               '${twin_szz} ${twin_sxy}"',
               f"variable chunk loop {chunks}", "label twin_loop"]
    k = {"x": 1, "y": 2, "z": 3}
    for a in servo:
        # Lateral strain rate from the stress error (P / thickness above p0: widen), PI.
        gain = 1.0 / (stiffness * chunk * dt)
        script += [f"variable old_{a} equal ${{r_{a}}}",
                   f"variable e_{a} equal c_stress[{k[a]}]/{scale!r}-{p0!r}",
                   f"variable i_{a} equal ${{i_{a}}}+{SERVO_I * gain!r}*${{e_{a}}}",
                   f"variable new_{a} equal ${{i_{a}}}+{SERVO_P * gain!r}*${{e_{a}}}",
                   f"variable r_{a} equal ${{new_{a}}}",
                   f"variable s_{a} atom (${{r_{a}}}-${{old_{a}}})*({a}-({a}lo+{a}hi)/2)"]
    if servo:
        lateral = " ".join(f"v_s_{a}" if a in servo else "NULL" for a in "xyz")
        script += [f"velocity all set {lateral} sum yes units box", "velocity all zero linear"]
    deform = " ".join(f"{a} erate ${{r_{a}}}" for a in axes)
    script += [f"fix twin_deform all deform 1 {deform} remap v flip no", f"run {chunk}",
               "unfix twin_deform",
               'print "TWIN ${twin_step} ${twin_lx} ${twin_ly} ${twin_lz} ${twin_sxx} ${twin_syy} '
               '${twin_szz} ${twin_sxy}"',
               "next chunk", "jump SELF twin_loop"]
    return "\n".join(script) + "\n", chunks


def native_history(log_text, dim):
    """The TWIN lines of the native run as element-test history columns."""
    rows = np.array([[float(v) for v in line.split()[1:]] for line in log_text.splitlines()
                     if line.startswith("TWIN ")])
    if len(rows) < 2:
        raise RunFailed("the native run printed no states (see its log)")
    lengths = rows[:, 1:4]
    strain = np.log(lengths / lengths[0])
    if dim == 2:
        strain[:, 2] = 0.0
    table = {"increment": np.arange(len(rows)), "time": rows[:, 0]}
    for i, a in enumerate(("xx", "yy", "zz")):
        table[f"e_{a}"] = strain[:, i]
    for a in ("xy", "xz", "yz"):
        table[f"e_{a}"] = np.zeros(len(rows))
    for i, a in enumerate(("xx", "yy", "zz", "xy")):
        table[f"s_{a}"] = rows[:, 4 + i]
    table["s_xz"] = table["s_yz"] = np.zeros(len(rows))
    if dim == 2:
        table["s_zz"] = np.zeros(len(rows))
    table["e_vol"] = strain.sum(axis=1)
    return table


def write_history(table, path):
    names = list(table)
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for k in range(len(table[names[0]])):
            f.write(",".join("%.17g" % table[n][k] for n in names) + "\n")


def compare(case, library, native):
    measures = PRESETS["element"]()
    runs = {"library": Run(library, case), "native": Run(native, case)}
    values = {name: {q.name: q.value(run) for q in measures} for name, run in runs.items()}
    rows = []
    for q in measures:
        lib, nat = values["library"][q.name], values["native"][q.name]
        rows.append({"quantity": q.name, "unit": q.unit,
                     "library": lib if q.kind == "scalar" else None,
                     "native": nat if q.kind == "scalar" else None,
                     "difference": error(q.kind, nat, lib, q.absolute),
                     "difference_unit": q.unit if q.absolute else "relative"})
    return rows, values


def draw(values, volumetric, path, dpi, title):
    fig, (ax1, ax2) = figures.subplots(1, 2, figsize=(11, 4.3))
    for (name, v), style in zip(values.items(), ("-", "--")):
        e1, q = v["q curve"]
        ax1.plot(100 * e1, q / 1e3, style, label=name)
    ax1.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax1.set_ylabel(r"deviator $\sigma_1-\sigma_3$ [kPa]")
    ax1.legend(frameon=False)
    for (name, (e1, ev)), style in zip(volumetric.items(), ("-", "--")):
        ax2.plot(100 * e1, 100 * ev, style, label=name)
    ax2.set_xlabel(r"axial strain $\varepsilon_1$ [%]")
    ax2.set_ylabel(r"volumetric strain $\varepsilon_v$ [%] (dilation > 0)")
    fig.suptitle(title)
    fig.tight_layout()
    figures.save(fig, path, dpi)


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("case", metavar="CASE.json")
    p.add_argument("--output", required=True)
    p.add_argument("--mpm-lig", default=checkout.path("build", "mpm_lig"))
    p.add_argument("--liggghts", default=shutil.which("liggghts") or "liggghts")
    p.add_argument("--library-run", help="a finished run of CASE with its prepared.restart")
    p.add_argument("--chunk", type=cli.positive_int, default=100,
                   help="DEM steps between servo updates")
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    case = read_json(a.case)
    check_case(case, a.case)
    cli.writable_folder(a.output)
    if not shutil.which(a.liggghts):
        raise InputError(f"{a.liggghts}: no liggghts executable (give --liggghts PATH)")
    require_templates()
    library = a.library_run or os.path.join(a.output, "library")
    if a.library_run and not os.path.isdir(a.library_run):
        raise InputError(f"{a.library_run}: no such run folder (--library-run)")
    if not a.library_run:
        if not os.access(a.mpm_lig, os.X_OK):
            raise InputError(f"{a.mpm_lig}: no mpm_lig executable (give --mpm-lig)")
        os.makedirs(a.output, exist_ok=True)
        # The twin's own library run: a repeated twin replaces it (mpm_lig keeps earlier
        # results unless told).
        run_command([a.mpm_lig, os.path.abspath(a.case), "--output", os.path.abspath(library),
                     "--replace"],
                    a.output, os.path.join(a.output, "library.log"))
    for name in ("summary.json", "history.csv", "prepared.restart"):
        if not os.path.isfile(os.path.join(library, name)):
            raise InputError(f"{library}: missing {name} (the case must save its prepared packing)")
    restart = os.path.join(library, "prepared.restart")
    if os.path.getsize(restart) == 0:
        raise InputError(f"{restart}: empty file (a damaged or unfinished restart)")
    native = os.path.join(a.output, "native")
    os.makedirs(native, exist_ok=True)
    script, chunks = twin_input(case, library, a.chunk)
    with open(os.path.join(native, "in.twin"), "w") as f:
        f.write(script)
    run_command([a.liggghts, "-in", "in.twin", "-log", "log.twin", "-echo", "none"], native,
                os.path.join(native, "screen.txt"), restart=restart)
    dim = case["rve"].get("dimension", 3)
    table = native_history(read_text(os.path.join(native, "log.twin")), dim)
    write_history(table, os.path.join(native, "history.csv"))
    rows, values = compare(case, library, native)
    print(f"{'quantity':20s} {'library':>10s} {'native':>10s} {'difference':>10s}")
    for r, q in zip(rows, PRESETS["element"]()):
        lib, nat = (("curve" if q.kind != "scalar" else "-") if v is None else f"{v:.3f}"
                    for v in (r["library"], r["native"]))
        diff = q.error_text(r["difference"])
        print(f"{r['quantity']:20s} {lib:>10s} {nat:>10s} {diff:>10s}")
    with open(os.path.join(a.output, "twin.json"), "w") as f:
        json.dump({"case": a.case, "chunk": a.chunk, "chunks": chunks, "comparison": rows}, f,
                  indent=1)
    volumetric = {}
    for name, run in (("library", library), ("native", native)):
        _, _, e1, ev = principal_series(Run(run, case).history, dim)
        volumetric[name] = (e1, -ev)
    draw(values, volumetric, os.path.join(a.output, "twin.png"), a.dpi,
         f"library path against native LIGGGHTS: {os.path.basename(a.case)}")


def entry():
    """The command: tools/native_twin.py in a checkout, mpm-lig-native-twin installed."""
    cli.run(main, failures=RunFailed)


if __name__ == "__main__":
    entry()
