#!/usr/bin/python3
"""Checks of tools/direct_dem.py.

usage: check_direct_dem.py bad WORK      bad input: exit 2, the key named, nothing created
       check_direct_dem.py affine        coarse-grained strain of an affinely deformed packing
       check_direct_dem.py run WORK      a real run of tests/tools/direct_dem_tiny.json (100
                                         discs, to s/B = 0.05) and what it must reproduce
"""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
TOOL = os.path.join(TOOLS, "direct_dem.py")
TINY = os.path.join(HERE, "direct_dem_tiny.json")

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def run_tool(args):
    p = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
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
    ]
    for name, case, extra, key in cases:
        out = os.path.join(work, "out_" + name.replace(" ", "_"))
        code, stdout, stderr = run_tool([case, "--output", out] + extra)
        check(code == 2 and key in stderr and "Traceback" not in stderr,
              f"{name}: exit {code}, stderr names '{key}': {stderr.strip()[:160]}")
        check(not os.path.exists(out), f"{name}: no output folder created")


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


def real(work):
    shutil.rmtree(work, ignore_errors=True)
    out = os.path.join(work, "tiny")
    code, stdout, stderr = run_tool([TINY, "--output", out, "--settlement", "0.05", "--seed", "12",
                                     "--snapshots", "0.05", "--fields-every", "0.025"])
    check(code == 0, f"the tiny run ends with exit 0 (got {code}; {stderr.strip()[-300:]})")
    if code != 0:
        return
    case = json.load(open(TINY))
    rve = case["materials"][0]["rve"]
    s = json.load(open(os.path.join(out, "summary.json")))
    prep = s["preparation"]
    target = rve["preparation"]["target_void_ratio"]
    check(abs(prep["void_ratio"] - target) <= 0.005,
          f"void ratio {prep['void_ratio']:.4f} within 0.005 of the case's {target}")
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


def main():
    mode = sys.argv[1]
    if mode == "bad":
        bad(sys.argv[2])
    elif mode == "affine":
        affine()
    elif mode == "run":
        real(sys.argv[2])
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)


if __name__ == "__main__":
    main()
