#!/usr/bin/python3
"""Checks of tools/direct_dem.py.

usage: check_direct_dem.py bad WORK      bad input: exit 2, the key named, nothing created;
                                         direct_dem_compare.py against a multiscale run
       check_direct_dem.py affine        coarse-grained strain of an affinely deformed packing
       check_direct_dem.py cells         the grains' own volume (Voronoi cells between the
                                         side planes) on lattices with closed-form areas
       check_direct_dem.py run WORK      a real run of tests/tools/direct_dem_tiny.json (100
                                         discs, to s/B = 0.12, two probes) and what it must
                                         reproduce
       check_direct_dem.py start_from_scale WORK
                                         --start-from a block of --scale 2 without --scale: the
                                         block's B and speed
       check_direct_dem.py settle_damping WORK REFERENCE
                                         the settling with kinetic damping (REFERENCE, run's
                                         block) against none, and --resettle
       check_direct_dem.py column WORK REFERENCE
                                         --footing-column on REFERENCE's settled block: the
                                         column's discs moved with the footing, its state
                                         through a SIGTERM and --resume bit for bit
       check_direct_dem.py resume WORK REFERENCE
                                         the same run stopped in its preparation (at a
                                         checkpoint) and in its loading (SIGTERM), resumed: the
                                         same history bit for bit as REFERENCE (run's); then
                                         damaged, edited or mismatched checkpoints refused
"""
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

import synthetic
from checking import tool as checkout_tool

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
TOOL = os.path.join(TOOLS, "direct_dem.py")
TINY = os.path.join(HERE, "direct_dem_tiny.json")

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


# The options of every real run here: checkpoints often enough to stop in each stage (the
# loading, 42 000 steps to s/B = 0.12, holds at least two of them wherever the preparation
# ended).
SETTLEMENT = 0.12
RUN = ["--settlement", str(SETTLEMENT), "--snapshots", "0.05", "--fields-every", "0.025",
       "--checkpoint-steps", "20000", "--probes", "wedge", "far=1.5:1.2:2.5", "--probe-window", "3"]


def run_tool(args, env=None, cwd=None):
    p = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True,
                       env=env, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def bad(work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    tiny = json.load(open(TINY))

    def variant(name, change):
        case = json.loads(json.dumps(tiny))
        change(case)
        path = os.path.join(work, name + ".json")
        json.dump(case, open(path, "w"))
        return path

    cases = [
        ("not a footing", os.path.join(HERE, "..", "..", "cases", "element_biaxial_2d_100kPa.json"),
         [], "analysis.type"),
        ("no rigid footing", variant("nofooting", lambda c: c.pop("rigid_bodies")), [],
         "rigid_bodies[0].type"),
        ("3D", variant("three_d", lambda c: c.update(dimension=3)), [], "dimension"),
        ("3D grains", variant("spheres", lambda c: c["materials"][0]["rve"].update(dimension=3)),
         [], "materials[0].rve.dimension"),
        ("no target void ratio", variant("noe", lambda c: c["materials"][0]["rve"]["preparation"]
                                         .pop("target_void_ratio")), [],
         "materials[0].rve.preparation.target_void_ratio"),
        ("off-centre footing", variant("offcentre", lambda c: c["rigid_bodies"][0].update(
            center=[0.05])), [], "rigid_bodies[0].center"),
        ("no roller on x+", variant("noroller", lambda c: c["boundary_conditions"].pop(1)), [],
         "face x+"),
        ("too many grains", TINY, ["--scale", "1000"], "--scale 1000"),
        ("negative speed factor", TINY, ["--speed-factor", "-1"], "--speed-factor"),
        ("negative seed", TINY, ["--seed", "-1"], "--seed"),
        ("friction not a number", variant("friction", lambda c: c["materials"][0]["rve"]
                                          ["contact"].update(friction_deg="x")),
         [], "materials[0].rve.contact.friction_deg"),
        ("grains smaller than the block allows", TINY, ["--scale", "1e-3"], "--scale 0.001"),
        ("tiles that do not divide the scale", TINY, ["--scale", "3", "--tiles", "2"],
         "--tiles 2"),
        ("no such engine", TINY, ["--liggghts", "/nonexistent/liggghts"], "--liggghts"),
        ("settlement past the base", TINY, ["--settlement", "10"], "--settlement"),
        ("resume of nothing", TINY, ["--resume"], "no such folder"),
        ("resettle without a block", TINY, ["--resettle"], "--resettle"),
        ("extend without a resume", TINY, ["--extend", "--settlement", "0.2"], "--extend"),
        ("no such settling", TINY, ["--settle-damping", "viscous"], "--settle-damping"),
        ("unknown option, one line", TINY, ["--sead", "3"], "unrecognized arguments"),
        ("no such probe place", TINY, ["--probes", "keel"], "--probes keel"),
        ("a probe's place not numbers", TINY, ["--probes", "a=x:1"], "--probes a=x:1"),
        ("a probe named twice", TINY, ["--probes", "far", "far=1:1"], "a name given twice"),
        ("a probe's own side zero", TINY, ["--probes", "far=1:1:0"], "--probes far=1:1:0"),
        ("a probe's own side wider than the block", TINY, ["--probes", "far=1:1:1000"],
         "--probes far"),
        ("a probe window wider than the block", TINY, ["--probes", "far"], "--probe-window"),
    ]
    for name, case, extra, key in cases:
        out = os.path.join(work, "out_" + name.replace(" ", "_"))
        code, stdout, stderr = run_tool([case, "--output", out] + extra)
        check(code == 2 and key in stderr and "Traceback" not in stderr,
              f"{name}: exit {code}, stderr names '{key}': {stderr.strip()[:160]}")
        check(not os.path.exists(out), f"{name}: no output folder created")
        check(len(stderr.strip().splitlines()) == 1, f"{name}: one line on stderr")
    # a copy of tools/ without the checkout's lmp_inputs/ beside it: named, nothing created
    copied = os.path.join(work, "copied", "tools")
    shutil.copytree(os.path.join(HERE, "..", "..", "tools"), copied,
                    ignore=shutil.ignore_patterns("__pycache__"))
    out = os.path.join(work, "out_copied_tools")
    p = subprocess.run([sys.executable, os.path.join(copied, "direct_dem.py"), TINY, "--output",
                        out], capture_output=True, text=True)
    check(p.returncode == 2 and "input templates are not there" in p.stderr and
          "Traceback" not in p.stderr and not os.path.exists(out),
          f"tools/ copied without lmp_inputs/: exit {p.returncode}: {p.stderr.strip()[:160]}")
    # an output that is a file, or inside a read-only folder
    afile = os.path.join(work, "a_file")
    open(afile, "w").close()
    code, _, stderr = run_tool([TINY, "--output", afile])
    check(code == 2 and "is a file" in stderr, f"--output naming a file: exit {code}: "
          f"{stderr.strip()[:120]}")
    if os.geteuid() != 0:  # root writes anywhere
        locked = os.path.join(work, "read_only")
        os.makedirs(locked)
        os.chmod(locked, 0o500)
        code, _, stderr = run_tool([TINY, "--output", os.path.join(locked, "x")])
        check(code == 2 and "writable" in stderr, f"--output in a read-only folder: exit {code}")
    # a symbolic link inside an output folder is refused, nothing written through it
    linked = os.path.join(work, "linked")
    os.makedirs(linked)
    elsewhere = os.path.join(work, "elsewhere.csv")
    open(elsewhere, "w").write("precious\n")
    os.symlink(elsewhere, os.path.join(linked, "history.csv"))
    code, _, stderr = run_tool([TINY, "--output", linked])
    check(code == 2 and "symbolic link" in stderr and open(elsewhere).read() == "precious\n",
          f"a history.csv link in the folder: exit {code}, target untouched: {stderr.strip()[:120]}")
    # an engine that hangs or only echoes: exit 3 within the start limit, no engine left
    for name, body in (("hangs", "sleep 1000"), ("echoes", "cat")):
        fake = os.path.join(work, f"liggghts_{name}")
        open(fake, "w").write(f"#!/bin/sh\n{body}\n")
        os.chmod(fake, 0o755)
        env = dict(os.environ, MPM_LIG_TEST_ENGINE_START_SECONDS="3")
        start = time.time()
        code, _, stderr = run_tool([TINY, "--output", os.path.join(work, "fake_" + name),
                                    "--liggghts", fake], env=env)
        check(code == 3 and "liggghts" in stderr and time.time() - start < 30,
              f"an engine that {name}: exit {code} in {time.time() - start:.0f} s: "
              f"{stderr.strip()[:120]}")
        left = subprocess.run(["pgrep", "-f", fake], capture_output=True, text=True).stdout
        check(not left.strip(), f"an engine that {name}: no process left")
    compare_checks(os.path.join(work, "compare"))


def affine():
    from mpm_lig_post.coarse_grain import deviatoric_strain, hencky, point_fields

    rng = np.random.default_rng(3)
    reference = rng.random((4000, 2)) * [0.6, 0.6]
    F = np.array([[1.08, 0.06], [-0.03, 0.91]])
    shift = np.array([0.01, -0.02])
    current = reference @ F.T + shift
    points = np.array([[x, y] for x in np.linspace(0.1, 0.5, 5) for y in np.linspace(0.1, 0.5, 5)])
    positions, fields = point_fields(reference, current, points, 0.025, 0.05 ** 2)
    strain = fields["strain"]
    C = F.T @ F
    w, v = np.linalg.eigh(C)
    exact = np.zeros((3, 3))
    exact[:2, :2] = v @ np.diag(0.5 * np.log(w)) @ v.T
    check(np.abs(strain - exact).max() < 1e-10,
          f"Hencky strain of an affine map recovered (max error {np.abs(strain - exact).max():.2e})")
    e = exact - np.trace(exact) / 3 * np.eye(3)
    eq = math.sqrt(2 / 3 * np.sum(e * e))
    check(np.abs(fields["deviatoric_strain"] - eq).max() < 1e-10,
          f"eps_q = {eq:.6f} at every point (the affine map's)")
    u = points @ F.T + shift - points
    check(np.abs(fields["displacement"][:, :2] - u).max() < 1e-12,
          "point displacement = F X + c - X")
    check(np.abs(positions - (points + u)).max() < 1e-12, "point positions follow the map")
    check(np.allclose(fields["volume"], 0.05 ** 2 * np.linalg.det(F)), "volume = h^2 det F")
    # a non-affine field fails the comparison (the check can fail)
    wobble = current + 0.002 * np.sin(40 * reference[:, :1])
    _, other = point_fields(reference, wobble, points, 0.025, 0.05 ** 2)
    check(np.abs(other["strain"] - exact).max() > 1e-3, "a wavy displacement is told apart")
    check(np.allclose(deviatoric_strain(hencky(np.tile(np.eye(2), (2, 1, 1)))), 0),
          "no strain without deformation")
    fabric_checks()
    size_checks()


def size_checks():
    """The size-effect fit gives back a known law, with and without a void-ratio term."""
    from mpm_lig_post import size_effect

    law = lambda bd, e: 22.0 - 40.0 / bd - 300.0 * (e - 0.187)
    rows = [{"B_over_d": bd, "void_ratio": e, "highest": law(bd, e)}
            for bd, e in ((20, 0.186), (20, 0.188), (40, 0.187), (80, 0.1855), (80, 0.1875))]
    f = size_effect.fit(rows, "highest", 0.187)
    check(abs(f["at_infinity"] - 22.0) < 1e-9 and abs(f["slope"] + 40) < 1e-8 and
          abs(f["void_ratio_slope"] + 300) < 1e-6,
          f"size fit: {f['at_infinity']:.3f} + {f['slope']:.2f} d/B + {f['void_ratio_slope']:.1f} de")
    g = {r["B_over_d"]: r for r in size_effect.summary(rows, "highest")}
    check(g[20]["n"] == 2 and abs(g[20]["mean"] - (law(20, 0.186) + law(20, 0.188)) / 2) < 1e-12
          and g[40]["std"] is None, "per-size mean, count and no std for one packing")
    check(size_effect.fit(rows[:2], "highest") is None, "no fit from two runs")


def compare_checks(work):
    """direct_dem_compare.py --multiscale-runs: a multiscale footing's peak and window means read
    from its own history over its case's B and q_s, and the grains' differences against them."""
    B, qs = 0.4, 2e5
    sB = (np.arange(1001) + 0.5) / 1000  # off the windows' ends, where rounding would decide
    # q/q_s: up to 20 at s/B 0.15, down to 12 by 0.3, then 12 + 4 (s/B - 0.3)
    shape = np.interp(sB, [0.0, 0.15, 0.3, 1.0], [2.0, 20.0, 12.0, 14.8])
    case = {"rigid_bodies": [{"width": [B], "center": [0, 0], "base": 0}],
            "boundary_conditions": [{"type": "traction", "traction": [0.0, -qs]}]}
    multi = os.path.join(work, "mpm_h8")
    synthetic.write_history(multi, ["step", "settlement", "q"],
                            [(k, s * B, v * qs) for k, (s, v) in enumerate(zip(sB, shape))])
    json.dump(case, open(os.path.join(multi, "case.json"), "w"))
    grains = os.path.join(work, "dem")
    synthetic.write_history(grains, ["s_over_B", "q_over_qs"], zip(sB, 0.9 * shape))
    json.dump({"grains": 100, "B_over_d": 20, "seed": 11, "speed_factor": 1,
               "particle_steps": 1e6, "loading_steps": 1000, "core_seconds": 36.0,
               "wall_seconds": 36.0}, open(os.path.join(grains, "summary.json"), "w"))
    prefix = os.path.join(work, "cmp")
    code, _, stderr = checkout_tool("direct_dem_compare.py", [grains, "--multiscale-runs", multi,
                                                              "--at", "2", "-o", prefix])
    check(code == 0, f"direct_dem_compare --multiscale-runs: exit {code} {stderr.strip()[-300:]}")
    if code != 0:
        return
    out = json.load(open(prefix + ".json"))
    m = out["multiscale"]["mpm_h8"]
    inside = (sB >= 0.4) & (sB <= 1.0)
    k = int(np.argmax(shape))
    check(abs(m["peak"] - shape[k]) < 1e-9 and abs(m["peak_at"] - sB[k]) < 1e-9 and
          abs(m["mean"] - shape[inside].mean()) < 1e-9,
          f"the multiscale run's peak {m['peak']:.4f} at s/B {m['peak_at']:.3f} and mean over "
          f"0.4-1.0 {m['mean']:.4f} from its history over its case's B and q_s")
    r = out["runs"][0]
    check(all(abs(r[f"{k} vs mpm_h8"] + 0.1) < 1e-9 for k in
              ("peak", "plateau_0.1_0.3", "plateau", "mean")),
          "the grains at 0.9 times the curve read -10 % in every window")
    check("vs DEM, h = B/4, flip 0.99" not in str(r), "no table rows read without --rows")
    os.remove(os.path.join(multi, "case.json"))
    code, _, stderr = checkout_tool("direct_dem_compare.py", [grains, "--multiscale-runs", multi,
                                                              "--at", "2", "-o", prefix + "2"])
    check(code == 2 and "--multiscale-case" in stderr and not os.path.exists(prefix + "2.json"),
          f"a multiscale folder without its case: exit {code}, {stderr.strip()!r}")


def fabric_checks():
    """Contact fabric of lattices whose fabric is known, across the periodic faces."""
    from mpm_lig_post.direct_dem.packing import fabric, tile

    r = 0.005
    # a hexagonal packing of touching discs, shifted off the origin: 6 contacts a grain
    nx, ny = 10, 6
    rows = [[(2 * r * (i + 0.5 * (j % 2)), r * math.sqrt(3) * j) for i in range(nx)]
            for j in range(ny)]
    xy = np.array(rows).reshape(-1, 2) + [0.3, -0.2]
    radii = np.full(len(xy), r * (1 + 1e-9))
    cell = (2 * r * nx, r * math.sqrt(3) * ny)
    f = fabric(xy, radii, cell, (0.3, -0.2))
    check(abs(f["coordination"] - 6) < 1e-9 and abs(f["anisotropy"]) < 1e-9,
          f"hexagonal packing: coordination {f['coordination']:.3f}, anisotropy "
          f"{f['anisotropy']:.2e}")
    # chains along x only: every normal along x, anisotropy 2, direction 0
    xy = np.array([(2 * r * i, 4 * r * j) for i in range(8) for j in range(4)], float)
    f = fabric(xy, np.full(len(xy), r * (1 + 1e-9)), (16 * r, 16 * r), (0, 0))
    check(abs(f["anisotropy"] - 2) < 1e-9 and abs(f["coordination"] - 2) < 1e-9 and
          min(f["direction_deg"], 180 - f["direction_deg"]) < 1e-6,
          f"chains along x: anisotropy {f['anisotropy']:.3f}, direction {f['direction_deg']:.1f}")
    # a cell repeated 3 x 3 keeps its fabric and its void ratio
    rng = np.random.default_rng(4)
    small = rng.random((60, 2)) * 0.1
    rr = rng.uniform(0.006, 0.012, 60)
    one = fabric(small, rr, (0.1, 0.1), (0, 0))
    big_xy, big_r, _, big_cell, n = tile(small, rr, np.zeros((60, 3)), (0.1, 0.1), 3)
    nine = fabric(big_xy, big_r, big_cell, (0, 0))
    check(n == 540 and nine["contacts"] == 9 * one["contacts"] and
          abs(nine["anisotropy"] - one["anisotropy"]) < 1e-12,
          f"tiles 3 x 3: {nine['contacts']} = 9 x {one['contacts']} contacts, the same anisotropy")


def real(work):
    shutil.rmtree(work, ignore_errors=True)
    # a relative --output, from another working folder, with the defaults (seed 11)
    os.makedirs(work)
    out = os.path.join(work, "tiny")
    code, stdout, stderr = run_tool([TINY, "--output", "tiny"] + RUN, cwd=work)
    check(code == 0, f"the tiny run ends with exit 0 (got {code}; {stderr.strip()[-300:]})")
    if code != 0:
        return
    case = json.load(open(TINY))
    rve = case["materials"][0]["rve"]
    s = json.load(open(os.path.join(out, "summary.json")))
    prep = s["preparation"]
    target = rve["preparation"]["target_void_ratio"]
    tolerance = rve["preparation"]["void_ratio_tolerance"]
    check(abs(prep["void_ratio"] - target) <= tolerance,
          f"void ratio {prep['void_ratio']:.4f} within {tolerance} of the case's {target}")
    p = -0.5 * (prep["sxx"] + prep["syy"])
    check(abs(p - 1e5) <= 0.005 * 1e5, f"prepared at p = {p:.0f} Pa (asked 1e5 within 0.5 %)")
    from mpm_lig_post.vtk_legacy import read_polydata
    import glob

    grains = read_polydata(glob.glob(os.path.join(out, "snapshots", "*_grains.vtk"))[0])
    r = grains.field("radius")
    lo, hi = rve["radius"]["min"], rve["radius"]["max"]
    check(len(r) == s["grains"] and r.min() >= lo and r.max() <= hi,
          f"{len(r)} radii within [{lo}, {hi}]")
    # uniform distribution: Kolmogorov-Smirnov distance below its 1 % critical value
    u = np.sort((r - lo) / (hi - lo))
    ks = np.max(np.abs(u - np.arange(1, len(u) + 1) / len(u)))
    check(ks < 1.63 / math.sqrt(len(u)), f"radii uniform on [min, max] (KS distance {ks:.3f})")
    block = np.prod(case["bodies"][0]["box"]["max"])
    e_count = block / np.sum(math.pi * r ** 2) - 1
    check(abs(e_count - target) <= 0.02,
          f"the grain count fills the case's block at e = {e_count:.4f} (target {target} +- 0.02)")
    # the surcharge on the free surface: what the base carries beyond the footing's load
    table = np.genfromtxt(os.path.join(out, "history.csv"), delimiter=",", names=True)
    first = table[0]
    t = s["thickness"]
    expected = 1e5 * t * (s["block"][0] - 0.5 * s["B"])
    check(abs(first["surcharge_force"] - expected) <= 1e-9 * expected,
          "the surcharge forces add up to q_s t (L - B/2)")
    carried = first["base_force"] - first["footing_force"]
    check(abs(carried / expected - 1) <= 0.05,
          f"settled: the base carries q_s beside the footing within 5 % "
          f"({carried / expected:.4f})")
    # the footing load is the sum of the contact forces on its grains
    ref = np.load(os.path.join(out, "reference.npz"))
    contacts = np.load(glob.glob(os.path.join(out, "snapshots", "*_contacts.npz"))[0])
    foot = set(ref["footing"].tolist())
    i_in = np.array([i in foot for i in contacts["id1"]])
    j_in = np.array([j in foot for j in contacts["id2"]])
    # pair/gran/local gives the force on the first grain of a pair
    total = contacts["fy"][i_in & ~j_in].sum() - contacts["fy"][j_in & ~i_in].sum()
    F = float(contacts["footing_force"])
    check(abs(total - F) <= 1e-3 * abs(F) and F > 0,
          f"footing load {F:.6g} N = sum of its contact forces {total:.6g} N")
    check(np.all(np.diff(table["s_over_B"]) > 0) and table["s_over_B"][-1] >= 0.05 - 1e-9,
          f"settlement rises to s/B = {table['s_over_B'][-1]:.4f}")
    for key in ("particle_steps", "core_seconds", "wall_seconds"):
        check(s.get(key, 0) > 0, f"summary.json has {key}")
    plot = subprocess.run([sys.executable, os.path.join(TOOLS, "plot_fields.py"), out, "-o",
                           os.path.join(work, "fields.png")], capture_output=True, text=True)
    check(plot.returncode == 0, f"plot_fields.py reads results.h5 ({plot.stdout.strip()[:100]})")
    check(os.path.isfile(os.path.join(out, "force_chains.png")), "force_chains.png drawn")
    probes_checked(out, s, prep)


def probes_checked(out, s, prep):
    """The grains' own stress (Love-Weber, what the probes write) against the engine's virial
    on the whole prepared cell, and the probe rows."""
    lw = prep["love_weber"]
    p = -0.5 * (prep["sxx"] + prep["syy"])
    worst = max(abs(lw["sxx"] - lw["engine_sxx"]), abs(lw["syy"] - lw["engine_syy"]))
    check(worst <= 1e-5 * p and abs(lw["sxy"]) < 0.05 * p,
          f"the prepared cell's Love-Weber stress equals the engine's virial within 1e-5 p "
          f"({worst / p:.2e} p; the dump's digits)")
    rows = np.genfromtxt(os.path.join(out, "probes.csv"), delimiter=",", names=True,
                         dtype=None, encoding=None)
    every = 0.005
    history = np.genfromtxt(os.path.join(out, "history.csv"), delimiter=",", names=True)
    row_step = float(np.max(np.diff(history["s_over_B"])))
    for name in ("wedge", "far"):
        r = rows[rows["probe"] == name]
        want = int(round(SETTLEMENT / every)) + 1
        due = every * np.arange(len(r))
        check(len(r) == want and np.all(r["s_over_B"] >= due - 1e-9) and
              np.all(r["s_over_B"] < due + row_step),
              f"probe {name}: {len(r)} rows (want {want}), each at the first history row from "
              f"k x {every} s/B")
        first = np.array([[r["F11"][0], r["F12"][0]], [r["F21"][0], r["F22"][0]]])
        check(np.abs(first - np.eye(2)).max() < 1e-12 and np.all(r["F11"] * r["F22"] -
                                                                 r["F12"] * r["F21"] > 0),
              f"probe {name}: F = I at the start of loading, det F > 0 after")
        check(np.all(r["p"] > 0) and np.all(r["grains"] > 3) and np.all(r["contacts"] > 0),
              f"probe {name}: compressed grains in its window ({r['grains'][0]} grains)")
        cells = r["cells_volumetric"]
        check(cells[0] == 0.0 and np.all(np.isfinite(cells)) and
              np.abs(cells).max() < 0.2,
              f"probe {name}: its grains' cells unchanged at the start of loading, finite after "
              f"(largest |ln| {np.abs(cells).max():.4f})")
    # each probe's own window: wedge --probe-window's 3 d, far its own 2.5 d
    summary = json.load(open(os.path.join(out, "summary.json")))
    d = summary["B"] / summary["B_over_d"]
    sides = {name: summary["probes"][name]["side_over_B"] * summary["B"] / d
             for name in ("wedge", "far")}
    check(abs(sides["wedge"] - 3.0) < 1e-9 and abs(sides["far"] - 2.5) < 1e-9,
          f"each probe's window side: wedge {sides['wedge']:.4g} d, far {sides['far']:.4g} d")
    # the footing pushes the wedge down: its vertical stretch falls below 1
    wedge = rows[rows["probe"] == "wedge"]
    check(wedge["F22"][-1] < 1.0, f"the wedge is compressed (F22 = {wedge['F22'][-1]:.4f})")


def stop_in_loading(args, out, what):
    """The tool on the tiny case with `args`, sent SIGTERM once `out` holds a checkpoint of the
    loading: exit 4 naming --resume (or the loading ended first: skipped)."""
    p = subprocess.Popen([sys.executable, TOOL, TINY] + args,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    while p.poll() is None:
        try:
            if json.load(open(os.path.join(out, "checkpoint.json")))["stage"] == "load":
                break
        except (OSError, ValueError, KeyError):
            pass
        time.sleep(0.1)
    p.send_signal(signal.SIGTERM)
    _, stderr = p.communicate()
    if p.returncode == 0:
        # A fast machine can finish the short loading before the signal lands: nothing was
        # stopped, and the resume continues a finished run (a no-op).
        print(f"skip {what}: the loading ended before the signal")
    else:
        check(p.returncode == 4 and "SIGTERM" in stderr and "--resume" in stderr,
              f"{what}: exit {p.returncode}: {stderr.strip()[-200:]}")


def resume(work, reference):
    """Stopped and resumed in each stage: the uninterrupted run's history bit for bit."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "tiny")
    code, _, stderr = run_tool([TINY, "--output", out] + RUN + ["--stop-after-minutes", "0.001"])
    record = json.load(open(os.path.join(out, "checkpoint.json")))
    check(code == 4 and "--resume" in stderr and record["stage"] == "prepare",
          f"--stop-after-minutes: exit {code} at a checkpoint of the preparation "
          f"({record['stage']}): {stderr.strip()[-160:]}")
    shutil.copytree(out, os.path.join(work, "stopped_in_preparation"))
    stop_in_loading(["--output", out, "--resume"], out, "SIGTERM in the loading")
    shutil.copytree(out, os.path.join(work, "stopped_in_loading"))
    code, _, stderr = run_tool([TINY, "--output", out, "--resume"])
    check(code == 0, f"the resumed run ends with exit 0 ({stderr.strip()[-200:]})")
    same = open(os.path.join(out, "history.csv"), "rb").read() == \
        open(os.path.join(reference, "tiny", "history.csv"), "rb").read()
    check(same, "stopped twice and resumed: history.csv bit-identical to the uninterrupted run's")
    same = open(os.path.join(out, "probes.csv"), "rb").read() == \
        open(os.path.join(reference, "tiny", "probes.csv"), "rb").read()
    check(same, "stopped twice and resumed: probes.csv bit-identical to the uninterrupted run's")
    mine, theirs = (json.load(open(os.path.join(d, "summary.json"))) for d in
                    (out, os.path.join(reference, "tiny")))
    check(mine["particle_steps"] == theirs["particle_steps"] and
          mine["preparation"] == theirs["preparation"],
          "the same preparation and particle-steps as the uninterrupted run")
    refused(work)
    # A finished run is not continued to a larger settlement: its last checkpoint is its end
    # state, off the loading's step grid, so a continued loading is not the longer run.
    finished = os.path.join(work, "finished")
    shutil.copytree(out, finished)
    before = {n: os.path.getmtime(os.path.join(finished, n)) for n in os.listdir(finished)
              if n != "direct_dem.lock"}
    code, _, stderr = run_tool([TINY, "--output", finished, "--resume", "--settlement",
                                str(2 * SETTLEMENT)])
    check(code == 2 and "finished" in stderr and "--start-from" in stderr and
          "--extend" in stderr,
          f"a finished run resumed to a larger settlement: exit {code}: {stderr.strip()[:160]}")
    code, _, stderr = run_tool([TINY, "--output", finished, "--resume", "--extend"])
    check(code == 2 and "--extend: only for a finished run resumed to a larger" in stderr,
          f"--extend without a larger settlement: exit {code}: {stderr.strip()[:160]}")
    after = {n: os.path.getmtime(os.path.join(finished, n)) for n in os.listdir(finished)
             if n != "direct_dem.lock"}
    check(after == before, "a finished run resumed: the folder unchanged")
    extended(finished)


def extended(finished):
    """--extend: the finished run continued from its end to twice its settlement, its rows
    kept as they were and new ones after them, the end it was continued from recorded."""
    rows_before = open(os.path.join(finished, "history.csv")).read().splitlines()
    steps_before = json.load(open(os.path.join(finished, "summary.json")))["particle_steps"]
    code, _, stderr = run_tool([TINY, "--output", finished, "--resume", "--extend",
                                "--settlement", str(2 * SETTLEMENT)])
    check(code == 0, f"--extend: exit {code}: {stderr.strip()[-200:]}")
    if code != 0:
        return
    rows = open(os.path.join(finished, "history.csv")).read().splitlines()
    check(rows[:len(rows_before)] == rows_before and len(rows) > len(rows_before),
          f"--extend: the finished rows kept ({len(rows_before)}), new ones after them "
          f"({len(rows) - len(rows_before)})")
    s = json.load(open(os.path.join(finished, "summary.json")))
    check(s["finished"] and s["extended_from"] == [SETTLEMENT] and
          abs(s["s_over_B_reached"] - 2 * SETTLEMENT) < 0.01 * SETTLEMENT and
          s["particle_steps"] > steps_before,
          f"--extend: summary finished at s/B {s['s_over_B_reached']}, extended from "
          f"{s['extended_from']}, particle-steps {s['particle_steps']:.3g} > {steps_before:.3g}")


def refused(work):
    """Checkpoints that are damaged, edited or do not fit the command: exit 2, named, before
    anything runs, the folder unchanged."""
    def tamper(stage, change):
        folder = os.path.join(work, f"tampered_{len(os.listdir(work))}")
        shutil.copytree(os.path.join(work, "stopped_in_" + stage), folder)
        change(folder)
        return folder

    def flip(folder, name):
        path = os.path.join(folder, name)
        data = bytearray(open(path, "rb").read())
        for k in range(16):
            data[len(data) // 2 + k] ^= 0xFF
        open(path, "wb").write(data)

    def restart(folder):
        return json.load(open(os.path.join(folder, "checkpoint.json")))["files"]["restart"]["name"]

    def edit(folder, change):
        path = os.path.join(folder, "checkpoint.json")
        record = json.load(open(path))
        change(record)
        json.dump(record, open(path, "w"))

    cases = [
        ("flipped restart bytes", "preparation", lambda f: flip(f, restart(f)), [], ".restart"),
        ("truncated restart", "preparation", lambda f: os.truncate(os.path.join(f, restart(f)), 100),
         [], ".restart"),
        ("another --scale", "preparation", lambda f: None, ["--scale", "1.5"], "--scale"),
        ("another --seed", "preparation", lambda f: None, ["--seed", "3"], "--seed"),
        ("another --speed-factor", "loading", lambda f: None, ["--speed-factor", "0.5"],
         "--speed-factor"),
        ("an edited stage", "preparation", lambda f: edit(f, lambda r: r.update(stage="load")),
         [], "checkpoint.json"),
        ("an empty checkpoint", "preparation",
         lambda f: open(os.path.join(f, "checkpoint.json"), "w").write("{}"), [], "checkpoint.json"),
        ("reference.npz missing", "loading", lambda f: os.remove(os.path.join(f, "reference.npz")),
         [], "reference.npz"),
        ("history.csv deleted", "loading", lambda f: os.remove(os.path.join(f, "history.csv")),
         [], "history.csv"),
        ("history.csv edited", "loading", lambda f: flip(f, "history.csv"), [], "history.csv"),
    ]
    for name, stage, change, extra, named in cases:
        folder = tamper(stage, change)
        # (the lock file aside: a run takes the lock before it reads the checkpoint)
        before = {n: os.path.getmtime(os.path.join(folder, n)) for n in os.listdir(folder)
                  if n != "direct_dem.lock"}
        start = time.time()
        code, _, stderr = run_tool([TINY, "--output", folder, "--resume"] + extra)
        check(code == 2 and named in stderr and "Traceback" not in stderr and
              time.time() - start < 20, f"resume with {name}: exit {code}, names '{named}': "
              f"{stderr.strip()[:160]}")
        after = {n: os.path.getmtime(os.path.join(folder, n)) for n in os.listdir(folder)
                 if n != "direct_dem.lock"}
        check(after == before, f"resume with {name}: the folder unchanged")
    # one run at a time: a second run into a folder being written is refused
    folder = tamper("preparation", lambda f: None)
    first = subprocess.Popen([sys.executable, TOOL, TINY, "--output", folder, "--resume"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lock = os.path.join(folder, "direct_dem.lock")
    while first.poll() is None and (not os.path.isfile(lock) or
                                    open(lock).read().strip() != str(first.pid)):
        time.sleep(0.1)
    code, _, stderr = run_tool([TINY, "--output", folder, "--resume"])
    check(code == 2 and "one run at a time" in stderr, f"a second run into a live folder: exit "
          f"{code}: {stderr.strip()[:120]}")
    code, _, stderr = run_tool([TINY, "--output", folder])
    check(code == 2, f"a new run into a live run's folder: exit {code}: {stderr.strip()[:120]}")
    first.send_signal(signal.SIGHUP)
    _, err = first.communicate()
    check(first.returncode == 4 and "SIGHUP" in err, f"SIGHUP: exit {first.returncode}")


def start_from_scale(work):
    """--start-from of a block prepared at --scale 2, without --scale: the new loading is the
    block's (its B, B/d and speed), not scale 1's; the loading starts where the block's did."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    block, again = os.path.join(work, "scale2"), os.path.join(work, "again")
    code, _, stderr = run_tool([TINY, "--output", block, "--scale", "2", "--tiles", "2",
                                "--settlement", "0.004", "--snapshots"])
    check(code == 0, f"the tiny block at scale 2 (tiled): exit {code} {stderr.strip()[-200:]}")
    if code != 0:
        return
    code, _, stderr = run_tool([TINY, "--output", again, "--start-from", block,
                                "--speed-factor", "0.5", "--settlement", "0.004", "--snapshots"])
    check(code == 0, f"--start-from it at half speed, no --scale: exit {code} "
          f"{stderr.strip()[-200:]}")
    if code != 0:
        return
    first, second = (json.load(open(os.path.join(d, "summary.json"))) for d in (block, again))
    check(second["B"] == first["B"] and second["B_over_d"] == first["B_over_d"] and
          second["scale"] == 2.0, f"the block's B {second['B']} (B/d {second['B_over_d']:g}), "
          f"not scale 1's")
    check(abs(second["footing_speed"] - 0.5 * first["footing_speed"]) < 1e-12,
          f"half the block's speed ({second['footing_speed']:.4g} against "
          f"{first['footing_speed']:.4g} m/s)")
    rows = [open(os.path.join(d, "history.csv")).read().splitlines()[1] for d in (block, again)]
    check(rows[0] == rows[1], "the loading starts from the block's own state (first rows equal)")


def settle_damping(work, reference):
    """The settling with the kinetic damping (REFERENCE, the run test's block, the default)
    against the contacts' damping alone (the same packing, --settle-damping none): at rest in
    fewer updates and closer to balance; and that free block settled again (--start-from
    --resettle): quenched, balanced, and its loading starts from the new state."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    free, again = os.path.join(work, "free"), os.path.join(work, "again")
    code, _, stderr = run_tool([TINY, "--output", free, "--settle-damping", "none",
                                "--settlement", "0.004", "--snapshots"])
    check(code == 0, f"the tiny block settled without damping: exit {code} {stderr.strip()[-200:]}")
    if code != 0:
        return
    damped = json.load(open(os.path.join(reference, "settled.json")))["state"]["settled"]
    undamped = json.load(open(os.path.join(free, "settled.json")))["state"]["settled"]
    check(damped["damping"] == "kinetic" and damped["quenches"] >= 1 and
          undamped["damping"] == "none" and undamped["quenches"] == 0,
          f"the default settling quenches ({damped['quenches']}), none does not")
    check(damped["updates"] < undamped["updates"] and
          abs(damped["balance"]) <= abs(undamped["balance"]),
          f"kinetic damping: at rest after {damped['updates']} updates (none: "
          f"{undamped['updates']}), base / applied - 1 = {damped['balance']:+.4f} (none: "
          f"{undamped['balance']:+.4f})")
    code, _, stderr = run_tool([TINY, "--output", again, "--start-from", free, "--resettle",
                                "--settlement", "0.004", "--snapshots"])
    check(code == 0, f"--start-from it --resettle: exit {code} {stderr.strip()[-200:]}")
    if code != 0:
        return
    resettled = json.load(open(os.path.join(again, "settled.json")))["state"]["settled"]
    check(resettled["damping"] == "kinetic" and abs(resettled["balance"]) <= 0.01,
          f"resettled with kinetic damping: {resettled['quenches']} quenches, base / applied "
          f"- 1 = {resettled['balance']:+.4f}")
    rows = [open(os.path.join(d, "history.csv")).read().splitlines()[1] for d in (free, again)]
    check(rows[0] != rows[1], "the resettled block's loading starts from its new state")


def column_discs(snapshot, radius, half_width):
    """Centres (n x 2) of the column's discs in a grains snapshot (VTK): radius `radius`,
    x < B/2."""
    from mpm_lig_post.vtk_legacy import read_polydata
    grains = read_polydata(snapshot)
    xy, r = grains.points[:, :2], grains.point_data["radius"]
    on = (np.abs(r - radius) < 1e-12) & (xy[:, 0] < half_width)
    return xy[on]


def column(work, reference):
    """--footing-column 1 on the run test's settled block (--start-from): the column's discs
    are frozen to the footing (every one moves down by the settlement, none sideways), the
    footing carries another load than the one-grain block's, and the run stopped by SIGTERM
    in its loading and resumed computes the same history bit for bit."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    whole, cut = os.path.join(work, "whole"), os.path.join(work, "cut")
    args = ["--start-from", reference, "--footing-column", "1", "--settlement", str(SETTLEMENT),
            "--snapshots", "0", str(SETTLEMENT), "--checkpoint-steps", "10000"]
    code, out, stderr = run_tool([TINY, "--output", whole] + args)
    check(code == 0, f"--footing-column 1 from the settled block: exit {code} "
          f"{stderr.strip()[-200:]}")
    if code != 0:
        return
    summary = json.load(open(os.path.join(whole, "summary.json")))
    settled = json.load(open(os.path.join(reference, "settled.json")))["state"]
    B, rmax = summary["B"], json.load(open(TINY))["materials"][0]["rve"]["radius"]["max"]
    per_row = math.ceil(0.5 * B / (2 * rmax) - 1e-9)
    radius = 0.5 * B / (2 * per_row)
    rows = math.floor(B / (2 * radius))  # at least this many fit in one B above the surface
    added = summary["grains"] - settled["grains"]
    check(summary["footing_column"] == 1.0 and added >= per_row * rows and added % per_row == 0,
          f"the column: {added} discs, {per_row} a row, at least {rows} rows")
    snaps = sorted(f for f in os.listdir(os.path.join(whole, "snapshots"))
                   if f.endswith("_grains.vtk"))
    start, end = (column_discs(os.path.join(whole, "snapshots", f), radius, 0.5 * B)
                  for f in (snaps[0], snaps[-1]))
    steps = [int(f.split("_")[1]) for f in (snaps[0], snaps[-1])]
    s = (steps[1] - steps[0]) * summary["footing_speed"] * summary["time_step"]
    order = lambda a: a[np.lexsort((a[:, 1], a[:, 0]))]
    moved = len(start) == added and len(end) == added and \
        np.allclose(order(end) - order(start), [0.0, -s], atol=1e-6 * B)  # VTK's 9 digits
    check(moved, f"every column disc ({len(start)}, {len(end)} found) moved down by the "
          f"footing's {s:.4g} m between the snapshots and not sideways")
    band = subprocess.run([sys.executable, os.path.join(TOOLS, "shear_band.py"), whole, "--to",
                           str(SETTLEMENT), "--widths", "2", "-o", os.path.join(work, "band.png")],
                          capture_output=True, text=True)
    check(band.returncode == 0, "shear_band.py from the start of loading, whose reference has no "
          f"column: exit {band.returncode} {band.stderr.strip()[-160:]}")
    mine, plain = (np.loadtxt(os.path.join(d, "history.csv"), delimiter=",", skiprows=1)
                   for d in (whole, reference))
    check(mine.shape == plain.shape and np.max(np.abs(mine[:, 6] - plain[:, 6])) > 1e-3,
          "the footing on its column carries another load than the one-grain block's "
          f"(largest difference {np.max(np.abs(mine[:, 6] - plain[:, 6])):.3g} q_s)")
    stop_in_loading(["--output", cut] + args, cut, "SIGTERM in the column's loading")
    fresh, again = os.path.join(work, "fresh"), os.path.join(work, "again")
    code, _, stderr = run_tool([TINY, "--output", fresh, "--footing-column", "1", "--settlement",
                                "0.004", "--snapshots"])
    settled = json.load(open(os.path.join(fresh, "settled.json"))) if code == 0 else {}
    check(code == 0 and settled["options"]["footing_column"] == 1.0 and
          len(settled["state"]["footing_ids"]) > added,
          f"a new run with the column: exit {code}, the settled block holds it "
          f"{stderr.strip()[-160:]}")
    code, _, stderr = run_tool([TINY, "--output", again, "--start-from", fresh,
                                "--footing-column", "0.5", "--settlement", "0.004"])
    check(code == 2 and "--footing-column 0.5" in stderr and not os.path.exists(again),
          f"--start-from a block with a column, another --footing-column: exit {code}, nothing "
          f"created {stderr.strip()[-160:]}")
    code, _, stderr = run_tool([TINY, "--output", cut, "--resume", "--footing-column", "0.5"])
    check(code == 2 and "--footing-column 0.5" in stderr,
          f"resumed with another --footing-column: exit {code} {stderr.strip()[-160:]}")
    code, _, stderr = run_tool([TINY, "--output", cut, "--resume"])
    check(code == 0, f"resumed: exit {code} {stderr.strip()[-200:]}")
    same = open(os.path.join(cut, "history.csv"), "rb").read() == \
        open(os.path.join(whole, "history.csv"), "rb").read()
    check(same, "the column's run stopped and resumed: history.csv bit-identical to the "
          "uninterrupted one's")


def cells():
    """Voronoi cells of a square lattice of grains between the side planes, where every cell is
    the lattice's square: beside a plane (mirrored), under a uniform stretch, and across a slip
    line that opens, where the least-squares F of the same grains misreads the volume."""
    from mpm_lig_post.direct_dem.cells import cells_volumetric, walled_areas
    from mpm_lig_post.direct_dem.probes import members, window_F

    a, columns, rows = 0.01, 12, 30  # spacing; the planes at x = 0 and columns * a
    width = columns * a
    grid = np.array([[(i + 0.5) * a, (j + 0.5) * a] for j in range(rows) for i in range(columns)])
    radii = np.full(len(grid), 0.45 * a)
    reach = 4.0 * radii.max()
    start = walled_areas(grid, width, reach)
    inner = (grid[:, 1] > a) & (grid[:, 1] < (rows - 1) * a)  # the top and bottom rows are open
    beside = inner & ((grid[:, 0] < a) | (grid[:, 0] > width - a))
    check(np.allclose(start[inner], a * a, rtol=1e-12, atol=0),
          f"every cell of the lattice is a^2, the columns beside the planes too (beside: "
          f"{np.nanmin(start[beside]) / a ** 2:.6f} to {np.nanmax(start[beside]) / a ** 2:.6f} a^2)")
    # a window touching the plane x = 0, stretched uniformly about the origin (the plane stays)
    window = members(grid, np.array([0.04, 0.15]), 0.08)
    stretch = 1.03
    now = walled_areas(grid * stretch, width * stretch, reach * stretch)
    got = cells_volumetric(start, now, radii, window)
    check(abs(got - 2.0 * math.log(stretch)) < 1e-12,
          f"a uniform stretch by {stretch}: ln of the cells {got:.12f} = 2 ln {stretch}")
    # a slip line through the window's middle that opens by delta: the grains above it move up
    delta = 0.2 * a
    centre, side = np.array([0.06, 0.15]), 0.1
    window = members(grid, centre, side)
    opened = grid + np.where(grid[:, 1:2] > centre[1], [0.0, delta], [0.0, 0.0])
    got = cells_volumetric(start, walled_areas(opened, width, reach), radii, window)
    exact = math.log(1.0 + delta / side)  # the window's area grows by its width times delta
    fitted = math.log(np.linalg.det(window_F(grid[window], opened[window])))
    check(abs(got - exact) < 1e-12,
          f"a slip line opening by {delta / a:g} a: ln of the cells {got:.6f} = ln(1 + delta / "
          f"side) {exact:.6f}")
    check(fitted > 1.3 * exact,
          f"the same grains' least-squares det F reads {fitted / exact:.2f} times the opening "
          f"(ln det F {fitted:.6f}): a jump is not an affine map")


def main():
    mode = sys.argv[1]
    if mode == "bad":
        bad(sys.argv[2])
    elif mode == "affine":
        affine()
    elif mode == "cells":
        cells()
    elif mode == "run":
        real(sys.argv[2])
    elif mode == "resume":
        resume(sys.argv[2], sys.argv[3])
    elif mode == "column":
        column(sys.argv[2], sys.argv[3])
    elif mode == "start_from_scale":
        start_from_scale(sys.argv[2])
    elif mode == "settle_damping":
        settle_damping(sys.argv[2], sys.argv[3])
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)


if __name__ == "__main__":
    main()
