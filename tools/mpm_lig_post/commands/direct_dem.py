"""Direct DEM of a 2D mpm_lig footing case: the same grains, contact law and boundary value
problem run by the native `liggghts` executable, grain by grain.

usage: direct_dem.py CASE.json --output DIR [--scale S] [--seed N] [--settlement S_OVER_B]
                     [--speed-factor F] [--np N] [--snapshots S1 S2 ...] [--fields-every DS]
                     [--surcharge-every STEPS] [--checkpoint-minutes M] [--stop-after-minutes M]
                     [--resume | --start-from RUN_DIR]

CASE.json is a 2D footing case (analysis.type mpm, rigid_bodies[0] a footing at x = 0 on a
half model, one dem_rve material, rollers on x- and x+, fixed y-, a vertical traction: the
surcharge q_s). The direct DEM:
- grains: the rve's radius distribution and density, as many discs as fill the soil block
  (bodies[0].box, times --scale S with the grains unchanged, so B/d grows by S) at the rve's
  preparation.target_void_ratio; placed at random in a periodic cell at its
  initial_solid_fraction (src/rve/packing.cpp) and consolidated to its confining_pressure by
  the RVE procedure (src/rve/consolidation.cpp: per-axis isotropic servo, friction lowered in
  stages of x0.7 until the void ratio is reached, then the contact friction restored), with the
  contact law and time step of the rve (the lmp_inputs/liggghts templates);
- the problem: the periodic cell opened into the block: x- and x+ frictionless rigid planes
  (the rollers), the grains of the bottom 2 d_max frozen (the fixed rough base), the grains of
  the top d_max over 0 <= x < B/2 a rigid block (the rough footing) moved down at constant
  speed, the surcharge q_s as vertical forces on the top grain of each d_mean-wide column of the
  free surface beyond B/2, re-found every --surcharge-every steps (so it follows the heave);
  no gravity. Soil grains the opened planes cut are shrunk to fit and grown back under load;
- the speed: strain rate v/B at the rve's substeps.inertial_number, I = (v/B) d sqrt(rho/p),
  times --speed-factor.
Output in DIR: history.csv (settlement, footing load, q/q_s, base reaction, ...), results.h5 and
results.xdmf (the grains' motion coarse-grained onto the case's material points: displacement,
Hencky strain and eps_q, for tools/plot_fields.py and ParaView), snapshots/ (grains and
contacts as legacy VTK at --snapshots settlements, for tools/plot_force_chains.py),
force_chains.png, load.png, summary.json (grains, particle-steps, core-seconds, wall time,
peak and plateau), checkpoint.restart + checkpoint.json every --checkpoint-minutes (in the
preparation too; --resume continues from them) and settled.restart + settled.json (the block at
rest under q_s; --start-from loads it for another loading, e.g. at half the speed). Bad input: exit 2 naming the JSON key or option before
anything runs or is created; a failed engine run: exit 1; stopped with a checkpoint: exit 3.
"""
import argparse
import json
import math
import os
import resource
import shutil
import sys
import time

import numpy as np

from mpm_lig_post import cli, figures
from mpm_lig_post.coarse_grain import FieldOutput, mesh_points, point_fields
from mpm_lig_post.errors import InputError
from mpm_lig_post.footing import footing, surcharge
from mpm_lig_post.liggghts import Session, material_input, rayleigh_time_step, render
from mpm_lig_post.tables import read_history, read_json

CHUNK = 100            # servo steps per update (src/rve/consolidation.cpp kChunk)
AT_REST = 2e-3         # kinetic / elastic energy of a relaxed packing (kAtRest)
FRICTION_STEP = 0.7    # friction factor per compaction stage (kFrictionStep)
NEAR_TARGET = 0.05     # a compaction stage stops at its void ratio this close to p (kNearTarget)
STILL_CHUNKS = 20      # ... or on target with the void ratio within STILL_VOID_RATIO this long
STILL_VOID_RATIO = 2e-5
SETTLE_UPDATES = 400   # surcharge updates at most to settle the opened block
BALANCE = 0.01         # ... at rest once the base carries the applied load within 1 %
BYTES_PER_GRAIN = 4 * 1.1e6 / 400  # the engine's measured 2.75 kB per grain (src/rve/spec.cpp), x4
MAX_GRAINS = 2_000_000
HISTORY = ("step", "time", "settlement", "s_over_B", "footing_force", "q", "q_over_qs",
           "base_force", "surcharge_force", "wall_force", "kinetic_energy", "top_grains")


# ----------------------------------------------------------------------------- the case
def required(node, key, path):
    if not isinstance(node, dict) or key not in node:
        raise InputError(f"{path}.{key}: missing" if path else f"{key}: missing")
    return node[key]


def number(value, path, positive=True):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(f"{path}: must be a number, got {value!r}")
    if positive and value <= 0:
        raise InputError(f"{path}: must be > 0, got {value!r}")
    return float(value)


def problem(case, source, scale):
    """The footing problem of the case, checked: a dict of everything the run needs."""
    where = lambda key: f"{source}: {key}"
    def need(node, key, path):  # `required`, with the case file named
        try:
            return required(node, key, path)
        except InputError as e:
            raise InputError(where(str(e))) from None

    analysis = case.get("analysis")
    if not isinstance(analysis, dict) or analysis.get("type") != "mpm":
        raise InputError(where("analysis.type: not an mpm case (a footing is an mpm case)"))
    if case.get("dimension") != 2:
        raise InputError(where(f"dimension: {case.get('dimension')!r}; the direct DEM is 2D "
                               "(discs) only"))
    bodies = case.get("rigid_bodies")
    if not isinstance(bodies, list) or not bodies or not isinstance(bodies[0], dict) \
            or bodies[0].get("type") != "footing":
        raise InputError(where("rigid_bodies[0].type: not a footing case"))
    centre, width, base = footing(case, source)
    if len(width) != 1 or abs(centre[0]) > 1e-12:
        raise InputError(where("rigid_bodies[0].center: the direct DEM takes a 2D half model "
                               "with the footing centred on x = 0"))
    materials = [m for m in case.get("materials", []) if isinstance(m, dict)
                 and m.get("type") == "dem_rve"]
    if len(materials) != 1:
        raise InputError(where("materials: needs exactly one dem_rve material (the grains)"))
    rve = need(materials[0], "rve", "materials[0]")
    if rve.get("engine", "liggghts") != "liggghts":
        raise InputError(where("materials[0].rve.engine: the direct DEM runs liggghts"))
    if rve.get("dimension") != 2:
        raise InputError(where(f"materials[0].rve.dimension: {rve.get('dimension')!r}, "
                               "must be 2 (discs)"))
    radius = need(rve, "radius", "materials[0].rve")
    rmin = number(need(radius, "min", "materials[0].rve.radius"), where("materials[0].rve.radius.min"))
    rmax = number(need(radius, "max", "materials[0].rve.radius"), where("materials[0].rve.radius.max"))
    if rmax < rmin:
        raise InputError(where("materials[0].rve.radius: max < min"))
    number(need(rve, "density", "materials[0].rve"), where("materials[0].rve.density"))
    prep = need(rve, "preparation", "materials[0].rve")
    for key in ("confining_pressure", "target_void_ratio"):
        number(need(prep, key, "materials[0].rve.preparation"),
               where(f"materials[0].rve.preparation.{key}"))
    if "time_step" in rve:
        dt = number(rve["time_step"], where("materials[0].rve.time_step"))
    else:
        dt = number(need(rve, "time_step_fraction", "materials[0].rve"),
                    where("materials[0].rve.time_step_fraction")) * rayleigh_time_step(rve)
    inertial = number(need(need(rve, "substeps", "materials[0].rve"), "inertial_number",
                           "materials[0].rve.substeps"),
                      where("materials[0].rve.substeps.inertial_number"))
    body = need(case, "bodies", "")
    try:
        box_min = np.asarray(body[0]["box"]["min"], float)
        box_max = np.asarray(body[0]["box"]["max"], float)
    except (KeyError, IndexError, TypeError, ValueError):
        raise InputError(where("bodies[0].box: needs min and max")) from None
    if np.any(box_max <= box_min) or np.any(box_min != 0):
        raise InputError(where("bodies[0].box: must start at the origin with max > min"))
    faces = {}
    for bc in case.get("boundary_conditions", []):
        if isinstance(bc, dict) and isinstance(bc.get("nodes"), dict):
            faces[bc["nodes"].get("face")] = bc.get("type")
    for face, kind in (("x-", "roller"), ("x+", "roller"), ("y-", "fixed")):
        if faces.get(face) != kind:
            raise InputError(where(f"boundary_conditions: needs a {kind} on face {face} "
                                   f"(has {faces.get(face)!r}); the direct DEM models rollers on "
                                   "x-/x+ and a fixed base"))
    qs = surcharge(case, source)
    if qs is None:
        raise InputError(where("boundary_conditions: no vertical traction (the surcharge q_s)"))
    if abs(base - box_max[1]) > 1e-9:
        raise InputError(where("rigid_bodies[0].base: the footing must start on the soil surface "
                               "(bodies[0].box.max[1])"))
    mesh = need(case, "mesh", "")
    p0 = float(prep["confining_pressure"])
    e0 = float(prep["target_void_ratio"])
    mean_r2 = (rmin * rmin + rmin * rmax + rmax * rmax) / 3.0
    area = scale * scale * float(np.prod(box_max - box_min))
    grains = int(round(area / ((1.0 + e0) * math.pi * mean_r2)))
    d = rmin + rmax
    B = scale * float(width[0])
    speed = inertial * B / (d * math.sqrt(rve["density"] / p0))
    return {"rve": rve, "qs": qs, "p0": p0, "e0": e0, "B": B, "box": scale * box_max,
            "grains": grains, "dt": dt, "speed": speed, "d": d, "rmin": rmin, "rmax": rmax,
            "thickness": float(rve.get("thickness", d)), "inertial": inertial,
            "prep": prep, "mesh": {"origin": scale * np.asarray(mesh["origin"], float),
                                   "size": scale * np.asarray(mesh["size"], float),
                                   "cells": [int(c) for c in mesh["cells"]]},
            "scale": scale}


def check_memory(pb, scale):
    need_bytes = pb["grains"] * BYTES_PER_GRAIN
    available = None
    try:
        for line in open("/proc/meminfo"):
            if line.startswith("MemAvailable:"):
                available = float(line.split()[1]) * 1024
    except OSError:
        pass
    if pb["grains"] > MAX_GRAINS or (available and need_bytes > available):
        raise InputError(f"--scale {scale:g}: {pb['grains']} grains need about "
                         f"{need_bytes / 1e9:.3g} GB (limit {MAX_GRAINS} grains"
                         + (f", {available / 1e9:.3g} GB available)" if available else ")"))


# ----------------------------------------------------------------------------- grains
def draw_radii(radius, count, rng):
    """Radii as src/rve/packing.cpp draws them (uniform, or the tabulated cumulative)."""
    u = rng.random(count)
    if "radii" in radius:
        return np.interp(u, radius["cumulative"], radius["radii"])
    return radius["min"] + u * (radius["max"] - radius["min"])


def place(radii, lx, ly, rng):
    """Random non-overlapping centres in a periodic lx x ly cell, large grains first
    (src/rve/packing.cpp); InputError when a grain cannot be placed."""
    order = np.argsort(-radii)
    radii = radii[order]
    reach = 2.0 * radii[0]
    nx, ny = max(1, int(lx / reach)), max(1, int(ly / reach))
    buckets = {}
    centres = np.zeros((len(radii), 2))
    for k, r in enumerate(radii):
        for _ in range(100000):
            x = np.array([rng.random() * lx, rng.random() * ly])
            cx, cy = min(nx - 1, int(x[0] / lx * nx)), min(ny - 1, int(x[1] / ly * ny))
            clash = False
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for j in buckets.get(((cx + dx) % nx, (cy + dy) % ny), ()):
                        d = centres[j] - x
                        d[0] -= lx * round(d[0] / lx)
                        d[1] -= ly * round(d[1] / ly)
                        if d @ d < (radii[j] + r) ** 2:
                            clash = True
                            break
                    if clash:
                        break
                if clash:
                    break
            if not clash:
                centres[k] = x
                buckets.setdefault((cx, cy), []).append(k)
                break
        else:
            raise InputError(f"could not place grain {k + 1} of {len(radii)} without overlap: "
                             "lower preparation.initial_solid_fraction")
    return centres, radii


# ----------------------------------------------------------------------------- engine run
STATE = ("steps", "particle_steps", "grains", "load_steps", "next_field", "next_snap", "lx", "ly",
         "solid", "top_fixes", "prepared", "settled", "prep_state")


class Stopped(Exception):
    """--stop-after-minutes: the run checkpointed and stops (continue with --resume)."""


class Run:
    def __init__(self, pb, args, out):
        self.pb, self.args, self.out = pb, args, out
        self.session = None
        self.steps = 0          # DEM steps so far (all stages)
        self.particle_steps = 0.0
        self.start = time.time()
        self.wall_before = 0.0  # wall and engine CPU seconds of earlier sittings (--resume)
        self.cpu_before = 0.0
        self.grains = 0
        self.last_progress = 0.0
        self.load_steps = 0
        self.last_checkpoint = time.time()
        self.sitting_start = 0.0
        self.prepared = self.settled = self.prep_state = None
        self.top_fixes = []       # multiplicities m of the surcharge groups topM / fixes surM

    # engine plumbing
    def open(self):
        self.session = Session(os.path.join(self.out, "log.liggghts"), self.out, self.args.np,
                               self.args.liggghts)

    def send(self, text):
        return self.session.send(text)

    def run(self, n):
        self.send(f"run {n}")
        self.steps += n
        self.particle_steps += n * self.grains

    def cpu_seconds(self):
        try:
            fields = open(f"/proc/{self.session.proc.pid}/stat").read().rsplit(")", 1)[1].split()
            return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        except (OSError, IndexError, ValueError):
            return float("nan")

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

    # ------------------------------------------------------------------- preparation
    def prepare(self):
        pb, rve = self.pb, self.pb["rve"]
        prep = pb["prep"]
        rng = np.random.default_rng(self.args.seed)
        # as many grains as the drawn sample needs to fill the block at the target void ratio
        pool = draw_radii(rve["radius"], int(1.2 * pb["grains"]) + 50, rng)
        area = float(np.prod(pb["box"])) / (1.0 + pb["e0"])
        count = int(np.searchsorted(np.cumsum(math.pi * pool ** 2), area)) + 1
        radii = pool[:count]
        solid = float(np.sum(math.pi * radii ** 2))
        phi0 = float(prep.get("initial_solid_fraction", 0.6 * 0.8))
        aspect = pb["box"][0] / pb["box"][1]
        ly = math.sqrt(solid / phi0 / aspect)
        lx = aspect * ly
        centres, radii = place(radii, lx, ly, rng)
        self.radii, self.solid = radii, solid
        self.grains = len(radii)
        rmax = radii.max()
        setup = render("setup.in", {"dimension": "2", "lx": repr(lx), "ly": repr(ly),
                                    "zlo": repr(-rmax), "zhi": repr(rmax),
                                    "skin": repr(0.4 * 0.5 * pb["d"])}, {"two_d"})
        # The executable lacks the library path's triclinic correction (docs/DESIGN.md §3.2,
        # tools/native_twin.py): a prism cell loses its periodic images here, an orthogonal
        # block keeps them. Two atom types: the grains and the frictionless side planes.
        setup = setup.replace("create_box      1 cell", "create_box      2 cell")
        setup = setup.replace("region          cell prism", "region          cell block")
        setup = setup.replace(f" {rmax!r} 0 0 0 units box", f" {rmax!r} units box")
        self.send(setup)
        lines = []
        for i, (c, r) in enumerate(zip(centres, radii)):
            lines.append(f"create_atoms 1 single {c[0]!r} {c[1]!r} 0.0 units box")
            lines.append(f"set atom {i + 1} diameter {2 * r!r} density {float(rve['density'])!r}")
            if len(lines) >= 2000:
                self.send("\n".join(lines))
                lines = []
        if lines:
            self.send("\n".join(lines))
        mu = math.tan(math.radians(rve["contact"]["friction_deg"])) \
            if "friction" not in rve["contact"] else rve["contact"]["friction"]
        friction = math.tan(math.radians(prep["consolidation_friction_deg"])) \
            if "consolidation_friction_deg" in prep else mu
        self.materials(friction)
        self.send(render("dynamics.in", {"time_step": repr(pb["dt"])}, {"two_d"}))
        self.send("compute ke all ke\ncompute pl all pair/gran/local id force delta\n"
                  "compute ov all reduce ave c_pl[7]\n"
                  "thermo_style custom step atoms c_stress[1] c_stress[2] c_ke c_ov\n"
                  "thermo_modify norm no lost ignore\nthermo 0\nrun 0")
        self.prep_state = {"phase": "first", "friction": friction, "compacted": None}
        self.consolidate()

    def consolidate(self):
        """src/rve/consolidation.cpp consolidate(), resumable at each of its servo phases
        (self.prep_state: phase first / stage / final, the friction in use)."""
        pb, rve, prep = self.pb, self.pb["rve"], self.pb["prep"]
        mu = rve["contact"]["friction"] if "friction" in rve["contact"] \
            else math.tan(math.radians(rve["contact"]["friction_deg"]))
        self.budget = int(prep.get("max_steps", 5_000_000)) * max(1, int(round(self.grains / 400)))
        tol = float(prep.get("tolerance", 0.005))
        etol = float(prep.get("void_ratio_tolerance", 0.005))
        target = pb["e0"]
        stop = target + 0.25 * etol
        st = self.prep_state
        friction = st["friction"]
        if st["phase"] == "first":
            o = self.servo(tol)
            st["phase"] = "stage"
        else:
            # resumed: finish the servo phase that was interrupted
            o = self.servo(tol, stop if st["phase"] == "stage" and friction <= mu else 0.0)
        while st["phase"] == "stage" and self.void_ratio(o) > stop and friction > 0.0:
            previous = friction
            friction = FRICTION_STEP * friction if friction > 1e-3 else 0.0
            if previous > mu > friction:
                friction = mu
            st["friction"] = friction
            self.materials(friction)
            self.send("run 0")
            o = self.servo(tol, stop if friction <= mu else 0.0)
        if st["phase"] == "stage":
            st["compacted"] = self.void_ratio(o)
            st["phase"] = "final"
            if friction != mu:
                st["friction"] = mu
                self.materials(mu)
                self.send("run 0")
                o = self.servo(tol)
        e = self.void_ratio(o)
        self.prepared = {"void_ratio": e, "compacted_void_ratio": st["compacted"],
                         "friction_used": friction, "sxx": o["sxx"], "syy": o["syy"],
                         "steps": self.steps, "cell": [o["lx"], o["ly"]]}
        if abs(e - target) > etol:
            raise RuntimeError(f"preparation reached void ratio {e:.4f}, "
                               f"preparation.target_void_ratio asks {target} +- {etol}")
        self.progress(f"prepared: e = {e:.4f} (target {target}), sigma = "
                      f"{-o['sxx'] / 1e3:.1f} / {-o['syy'] / 1e3:.1f} kPa, {self.steps} steps",
                      force=True)

    def void_ratio(self, o):
        return o["lx"] * o["ly"] / self.solid - 1.0

    def servo(self, tol, stop_void_ratio=0.0):
        """src/rve/consolidation.cpp servo_isotropic on the periodic cell."""
        pb = self.pb
        p_t = pb["p0"]
        rate = 5e-3 / (pb["d"] * math.sqrt(pb["rve"]["density"] / p_t))
        max_step = float(pb["prep"].get("max_strain_rate", rate)) * CHUNK * pb["dt"]
        o = self.observe()
        settled = 0
        history = []
        while self.steps < self.budget:
            p = -0.5 * (o["sxx"] + o["syy"])
            strains = []
            for s in (o["sxx"], o["syy"]):
                strain = -max_step
                if p > 0.2 * p_t and o["ov"] > 0:
                    stiffness = 1.5 * p / o["ov"]
                    strain = min(max(-0.5 * (p_t + s) / stiffness, -max_step), max_step)
                strains.append(1.0 + strain)
            self.send(f"fix servo all deform 1 x scale {strains[0]!r} y scale {strains[1]!r} "
                      "remap x")
            self.run(CHUNK)
            self.send("unfix servo")
            o = self.observe()
            p_new = -0.5 * (o["sxx"] + o["syy"])
            e = self.void_ratio(o)
            self.progress(f"preparing: e = {e:.4f}, p = {p_new / 1e3:.1f} kPa, kinetic/elastic "
                          f"{self.kinetic_ratio(o, o['lx'] * o['ly'], p_new):.2g}")
            if stop_void_ratio > 0 and e <= stop_void_ratio and abs(p_new - p_t) <= NEAR_TARGET * p_t:
                return o
            on = abs(p_new - p_t) <= tol * p_t
            kr = self.kinetic_ratio(o, o["lx"] * o["ly"], p_new)
            # At rest as an RVE (kinetic energy below AT_REST of the elastic), or, as a block of
            # thousands of discs keeps a kinetic floor (rattlers: 0.5 % of its estimated
            # elastic energy for 3666 discs), on target with its void ratio still for
            # STILL_CHUNKS servo chunks.
            history.append(e)
            still = len(history) > STILL_CHUNKS and max(history[-STILL_CHUNKS:]) - \
                min(history[-STILL_CHUNKS:]) < STILL_VOID_RATIO
            settled = settled + 1 if on and (kr < AT_REST or still) else 0
            if settled >= 3:
                return o
            self.maybe_checkpoint("prepare")
        raise RuntimeError(f"the isotropic servo to {p_t} Pa did not settle within "
                           f"{self.budget} steps (preparation.max_steps per 400 grains)")

    # ------------------------------------------------------------------- the block
    def open_block(self):
        """Periodic cell -> half model: walls, base, footing, surcharge; cut grains regrown."""
        pb = self.pb
        lx, ly = self.prepared["cell"]
        self.lx, self.ly = lx, ly
        rmax = pb["rmax"]
        # The servo scaled the cell about its centre: move it back to the origin first.
        self.send(f"change_box all x final 0.0 {lx!r} y final 0.0 {ly!r} remap units box\n"
                  "change_box all boundary f m p")
        ids, xy, r = self.grains_now()
        base = ids[xy[:, 1] < 2 * 2 * rmax]
        foot = ids[(xy[:, 0] < 0.5 * pb["B"]) & (xy[:, 1] > ly - 2 * rmax)]
        self.send("group base id " + " ".join(map(str, base)) + "\n"
                  "group footing id " + " ".join(map(str, foot)) + "\n"
                  "group frozen union base footing\ngroup soil subtract all frozen\n"
                  "velocity frozen set 0 0 0")
        self.base_ids, self.footing_ids = base, foot
        soil = np.isin(ids, np.concatenate([base, foot]), invert=True)
        cut = soil & ((xy[:, 0] - r < 0) | (xy[:, 0] + r > lx))
        self.cut = {int(i): float(rr) for i, rr in zip(ids[cut], r[cut])}
        # A cut grain shrinks to fit between its centre and the plane, but to no less than half
        # its radius: then its centre moves in to that half radius (no new overlap: the move
        # is at most what the radius lost).
        gap, moves = {}, []
        for i, x, rr in zip(ids[cut], xy[cut, 0], r[cut]):
            room = min(x, lx - x)
            gap[int(i)] = max(0.98 * room, 0.49 * rr)
            if 0.98 * room < 0.49 * rr:
                target = 0.5 * rr if x < 0.5 * lx else lx - 0.5 * rr
                moves.append(f"set atom {int(i)} x {target!r}")
        rho = float(pb["rve"]["density"])
        self.send("\n".join([f"set atom {i} diameter {2 * g!r} density {rho!r}"
                             for i, g in gap.items()] + moves))
        self.dynamics()
        self.regrow(gap, 0.0)
        self.progress(f"opened the block: {len(base)} base, {len(foot)} footing, "
                      f"{len(self.cut)} cut grains regrown", force=True)

    def dynamics(self):
        """Integration of the soil, walls, exclusions, force sums (also after --resume)."""
        lx = self.lx
        self.send("unfix integrate\nunfix plane\nfix integrate soil nve/sphere\n"
                  "fix plane soil enforce2d\n"
                  f"fix wall_l soil wall/gran model hertz tangential history primitive type 2 "
                  f"xplane 0.0\nfix wall_r soil wall/gran model hertz tangential history primitive "
                  f"type 2 xplane {lx!r}\n"
                  "neigh_modify exclude group frozen frozen\n"
                  "compute f_foot footing reduce sum fy\ncompute f_base base reduce sum fy\n"
                  "compute f_soil_x soil reduce sum fx\ncompute ke_soil soil ke\n"
                  "thermo_style custom step atoms c_stress[1] c_stress[2] c_ke c_ov c_f_foot "
                  "c_f_base c_ke_soil c_f_soil_x\nthermo_modify norm no lost ignore\nthermo 0")

    def regrow(self, gap, settle_steps):
        """Cut grains from their fitted radius back to their own in 50 increments of 100 steps
        (an overlap growth of 1 % of the radius per increment), the surcharge re-found every 5."""
        rho = float(self.pb["rve"]["density"])
        for k in range(51):
            f = k / 50.0
            cmds = [f"set atom {i} diameter {2 * ((1 - f) * gap[i] + f * r)!r} density {rho!r}"
                    for i, r in self.cut.items()]
            if cmds:
                self.send("\n".join(cmds))
            if k % 5 == 0:
                self.surcharge_update()
            self.run(100)

    def grains_now(self, group="all"):
        """(ids, centres n x 2, radii) from a dump of the engine now."""
        path = os.path.join(self.out, "grains.tmp")
        self.send(f'write_dump {group} custom "{path}" id x y radius modify sort id')
        data = np.loadtxt(path, skiprows=9, ndmin=2)
        os.remove(path)
        return data[:, 0].astype(int), data[:, 1:3], data[:, 3]

    def surcharge_update(self):
        """Forces q_s t w on the top soil grain of each w-wide column over [B/2, lx]."""
        pb = self.pb
        ids, xy, r = self.grains_now("soil")
        x0, x1 = 0.5 * pb["B"], self.lx
        columns = max(1, int(round((x1 - x0) / (0.5 * pb["d"]))))
        w = (x1 - x0) / columns
        top = {}
        reach = xy[:, 1] + r
        for c in range(columns):
            a, b = x0 + c * w, x0 + (c + 1) * w
            inside = np.flatnonzero((xy[:, 0] + r > a) & (xy[:, 0] - r < b))
            if len(inside):
                k = inside[np.argmax(reach[inside])]
                top[int(ids[k])] = top.get(int(ids[k]), 0) + 1
        force = pb["qs"] * pb["thickness"] * w
        cmds = []
        for m in self.top_fixes:
            cmds += [f"unfix sur{m}", f"group top{m} delete"]
        self.top_fixes = sorted(set(top.values()))
        for m in self.top_fixes:
            members = [i for i, n in top.items() if n == m]
            cmds += [f"group top{m} id " + " ".join(map(str, members)),
                     f"fix sur{m} top{m} addforce 0.0 {-m * force!r} 0.0"]
        self.send("\n".join(cmds))
        self.top_count = len(top)
        self.top_force = force * columns
        self.top_y = float(np.mean([xy[ids == i, 1][0] for i in top])) if top else float("nan")

    # ------------------------------------------------------------------- loading
    def settle(self):
        """Under the surcharge, the footing held, until the soil is at rest."""
        # At rest: kinetic energy below AT_REST of the elastic, or (the kinetic floor of a large
        # block) the base carrying the surcharge and the footing's load within BALANCE; three
        # updates in a row, at most SETTLE_UPDATES (the 3709-disc block at e0 = 0.187 ran all
        # 200 under the kinetic criterion alone and started loading 5 % out of balance).
        settled = 0
        for k in range(SETTLE_UPDATES):
            self.surcharge_update()
            self.run(self.args.surcharge_every)
            o = self.observe()
            kr = self.kinetic_ratio(o, self.lx * self.ly, self.pb["p0"])
            row = self.history_row(0.0)
            balance = row["base_force"] / (row["surcharge_force"] + row["footing_force"]) - 1.0
            settled = settled + 1 if kr < AT_REST or abs(balance) < BALANCE else 0
            if settled >= 3 and k >= 5:
                break
        row = self.history_row(0.0)
        self.settled = {"steps": self.steps, "base_force_over_qs_L": row["base_force"] /
                        (self.pb["qs"] * self.pb["thickness"] * self.lx),
                        "balance": balance, "updates": k + 1,
                        "q_over_qs": row["q_over_qs"], "top_grains": self.top_count}
        self.progress(f"settled under q_s after {k + 1} updates: base / applied - 1 = "
                      f"{balance:+.4f}, footing q/q_s = "
                      f"{row['q_over_qs']:.3f}", force=True)

    def history_row(self, s):
        pb = self.pb
        ff, fb, ke, fx = self.session.values("H", ["c_f_foot", "c_f_base", "c_ke_soil",
                                                   "c_f_soil_x"])
        q = ff / (pb["thickness"] * 0.5 * pb["B"])
        return {"step": self.steps, "time": self.load_steps * pb["dt"] * 1.0,
                "settlement": s, "s_over_B": s / pb["B"], "footing_force": ff, "q": q,
                "q_over_qs": q / pb["qs"], "base_force": -fb, "surcharge_force": self.top_force,
                "wall_force": fx, "kinetic_energy": ke, "top_grains": self.top_count}

    def load(self, state):
        pb, a = self.pb, self.args
        v = pb["speed"] * a.speed_factor
        dt = pb["dt"]
        ds = v * dt
        end = a.settlement * pb["B"]
        total = int(math.ceil(end / ds))
        self.send(f"fix push footing move linear 0.0 {-v!r} 0.0")
        hist = os.path.join(self.out, "history.csv")
        self.surcharge_update()
        self.send("run 0")  # the force sums current before the first history row
        if not state:
            with open(hist, "w") as f:
                f.write(",".join(HISTORY) + "\n")
            self.load_steps = 0
            self.write_row(hist, self.history_row(0.0))
            self.next_field = 0
            self.next_snap = 0
        outs = [k * a.fields_every for k in range(int(a.settlement / a.fields_every + 1e-9) + 1)]
        snaps = sorted(a.snapshots)
        started, first_step = time.time(), self.load_steps  # the ETA from this sitting's rate
        while self.load_steps < total:
            n = min(a.surcharge_every, total - self.load_steps)
            self.surcharge_update()
            self.run(n)
            self.load_steps += n
            s = self.load_steps * ds
            row = self.history_row(s)
            self.write_row(hist, row)
            sB = s / pb["B"]
            while self.next_field < len(outs) and sB >= outs[self.next_field] - 1e-9:
                self.fields(s)
                self.next_field += 1
            while self.next_snap < len(snaps) and sB >= snaps[self.next_snap] - 1e-9:
                self.snapshot()
                self.next_snap += 1
            done = self.load_steps - first_step
            left = (total - self.load_steps) / max(done, 1) * (time.time() - started)
            self.progress(f"s/B = {sB:.3f}, q/q_s = {row['q_over_qs']:.2f}, "
                          f"{self.load_steps}/{total} steps, ETA {left / 60:.1f} min")
            self.maybe_checkpoint("load")
        return True

    def write_row(self, path, row):
        with open(path, "a") as f:
            f.write(",".join("%.10g" % row[k] for k in HISTORY) + "\n")

    def fields(self, s):
        pb = self.pb
        ids, xy, _ = self.grains_now()
        keep = np.isin(ids, self.ref_ids)
        cur = xy[keep][np.argsort(ids[keep])]
        mesh = pb["mesh"]
        sx, sy = self.lx / pb["box"][0], self.ly / pb["box"][1]
        pts, h = mesh_points(mesh["origin"], mesh["size"], mesh["cells"], [0, 0], pb["box"])
        pts = pts * [sx, sy]
        h = h * [sx, sy]
        pos, data = point_fields(self.ref_xy, cur, pts, 0.5 * float(np.mean(h)), float(np.prod(h)))
        step = int(round(s / pb["B"] * 1000))
        self.field_out.add(step, self.load_steps * pb["dt"], pos, data)

    def snapshot(self):
        """Grains and contacts as legacy VTK (the layout of src/rve/snapshot.cpp)."""
        folder = os.path.join(self.out, "snapshots")
        os.makedirs(folder, exist_ok=True)
        prefix = os.path.join(folder, f"grains_{self.load_steps:09d}")
        self.send("run 0")  # forces and the contact list of one state
        ids, xy, r = self.grains_now()
        path = prefix + ".tmp"
        self.send(f'write_dump all local "{path}" c_pl[1] c_pl[2] c_pl[4] c_pl[5]')
        loc = np.loadtxt(path, skiprows=9, ndmin=2)
        os.remove(path)
        where = {int(i): k for k, i in enumerate(ids)}
        first = xy[[where[int(i)] for i in loc[:, 0]]]
        second = xy[[where[int(i)] for i in loc[:, 1]]]
        np.savez(prefix + "_contacts.npz", id1=loc[:, 0].astype(int), id2=loc[:, 1].astype(int),
                 fx=loc[:, 2], fy=loc[:, 3], footing_force=self.history_row(0.0)["footing_force"])
        loc = np.column_stack([first, second, loc[:, 2:4]])
        with open(prefix + "_grains.vtk", "w") as f:
            f.write("# vtk DataFile Version 3.0\ngrains\nASCII\nDATASET POLYDATA\n"
                    f"POINTS {len(xy)} double\n")
            np.savetxt(f, np.column_stack([xy, np.zeros(len(xy))]), fmt="%.9g")
            f.write(f"POINT_DATA {len(xy)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
            np.savetxt(f, r, fmt="%.9g")
        with open(prefix + "_contacts.vtk", "w") as f:
            n = len(loc)
            f.write("# vtk DataFile Version 3.0\ncontacts\nASCII\nDATASET POLYDATA\n"
                    f"POINTS {2 * n} double\n")
            pts = np.zeros((2 * n, 3))
            pts[0::2, :2], pts[1::2, :2] = loc[:, 0:2], loc[:, 2:4]
            np.savetxt(f, pts, fmt="%.9g")
            f.write(f"LINES {n} {3 * n}\n")
            np.savetxt(f, np.column_stack([np.full(n, 2), 2 * np.arange(n), 2 * np.arange(n) + 1]),
                       fmt="%d")
            f.write(f"CELL_DATA {n}\nSCALARS force double 1\nLOOKUP_TABLE default\n")
            np.savetxt(f, np.hypot(loc[:, 4], loc[:, 5]), fmt="%.9g")

    # ------------------------------------------------------------------- bookkeeping
    def progress(self, text, force=False):
        now = time.time()
        if force or now - self.last_progress > 10:
            rate = (self.particle_steps - self.sitting_start) / max(now - self.start, 1e-9)
            print(f"[{(now - self.start) / 60:6.1f} min] {text} ({rate / 1e6:.2f} M "
                  "particle-steps/s)", flush=True)
            self.last_progress = now

    def maybe_checkpoint(self, stage):
        """A checkpoint every --checkpoint-minutes; with --stop-after-minutes, one and a stop."""
        a = self.args
        if time.time() - self.last_checkpoint > 60 * a.checkpoint_minutes:
            self.checkpoint(stage)
        if a.stop_after_minutes and time.time() - self.start > 60 * a.stop_after_minutes:
            self.checkpoint(stage)
            raise Stopped()

    def checkpoint(self, stage, name="checkpoint"):
        path = os.path.join(self.out, name + ".restart")
        self.send(f'write_restart "{path}.tmp"')
        if not os.path.isfile(path + ".tmp") or os.path.getsize(path + ".tmp") < 1000:
            raise RuntimeError(f"{path}.tmp: write_restart left no usable file (disk full?)")
        os.replace(path + ".tmp", path)
        state = {k: getattr(self, k, None) for k in STATE}
        state.update(stage=stage, scale=self.args.scale, seed=self.args.seed, wall_seconds=self.wall_before + time.time() - self.start,
                     cpu_seconds=self.cpu_before + self.cpu_seconds())
        with open(os.path.join(self.out, name + ".json.tmp"), "w") as f:
            json.dump(state, f, indent=1)
        os.replace(os.path.join(self.out, name + ".json.tmp"), os.path.join(self.out, name + ".json"))
        self.last_checkpoint = time.time()
        self.progress(f"{name} written ({stage})", force=True)

    def resume(self, state, restart):
        for k in STATE:
            setattr(self, k, state[k])
        self.wall_before, self.cpu_before = state["wall_seconds"], state["cpu_seconds"]
        self.sitting_start = self.particle_steps  # the rate in the progress lines: this sitting's
        self.send(render("restart.in", {"restart_file": f'"{restart}"',
                                        "skin": repr(0.4 * 0.5 * self.pb["d"])}, {"two_d"}))
        friction = self.prep_state["friction"] if state["stage"] == "prepare" else None
        self.materials(friction)
        self.send(render("dynamics.in", {"time_step": repr(self.pb["dt"])}, {"two_d"}))
        self.send("compute ke all ke\ncompute pl all pair/gran/local id force delta\n"
                  "compute ov all reduce ave c_pl[7]\n"
                  "thermo_style custom step atoms c_stress[1] c_stress[2] c_ke c_ov\n"
                  "thermo_modify norm no lost ignore\nthermo 0")
        if state["stage"] != "prepare":
            self.dynamics()
            self.send("\n".join(f"group top{m} delete" for m in state["top_fixes"]))
            self.top_fixes = []
        self.send("run 0")


def summarise(run, pb, args, out, finished):
    table = read_history(os.path.join(out, "history.csv"))
    sB, q = table["s_over_B"], table["q_over_qs"]
    window = lambda a, b: float(np.mean(q[(sB >= a) & (sB <= b)])) if np.any((sB >= a) & (sB <= b)) \
        else None
    wall = run.wall_before + time.time() - run.start
    own = resource.getrusage(resource.RUSAGE_SELF)
    python_cpu = own.ru_utime + own.ru_stime
    cpu = run.cpu_before + run.final_cpu
    summary = {
        "case": os.path.abspath(args.case), "finished": finished, "scale": args.scale,
        "seed": args.seed, "grains": run.grains, "B": pb["B"], "B_over_d": pb["B"] / pb["d"],
        "block": [run.lx, run.ly], "thickness": pb["thickness"], "time_step": pb["dt"],
        "footing_speed": pb["speed"] * args.speed_factor, "speed_factor": args.speed_factor,
        "inertial_number": pb["inertial"] * args.speed_factor, "q_s": pb["qs"],
        "preparation": run.prepared, "settled": run.settled,
        "dem_steps": run.steps, "loading_steps": run.load_steps,
        "particle_steps": run.particle_steps, "ranks": args.np,
        "wall_seconds": wall, "engine_cpu_seconds": cpu,
        "python_cpu_seconds": python_cpu, "core_seconds": cpu * args.np + python_cpu,
        "s_over_B_reached": float(sB[-1]), "peak_q_over_qs": float(np.max(q)),
        "peak_at_s_over_B": float(sB[int(np.argmax(q))]),
        "plateau_0.1_0.4": window(0.1, 0.4), "mean_0.4_1.0": window(0.4, 1.0)}
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
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


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("case", metavar="CASE.json")
    p.add_argument("--output", required=True)
    p.add_argument("--scale", type=float, default=1.0, help="soil block and footing x S, grains unchanged")
    p.add_argument("--seed", type=int, default=11, help="packing seed")
    p.add_argument("--settlement", type=float, default=1.0, help="final s/B (default 1)")
    p.add_argument("--speed-factor", type=float, default=1.0,
                   help="footing speed over the one of the rve's inertial number")
    p.add_argument("--np", type=int, default=1, help="MPI ranks (default 1: serial)")
    p.add_argument("--liggghts", default=None)
    p.add_argument("--fields-every", type=float, default=0.05, help="s/B between field outputs")
    p.add_argument("--snapshots", type=float, nargs="*", default=[0.1, 0.5],
                   help="s/B of the grain and contact snapshots")
    p.add_argument("--surcharge-every", type=int, default=500,
                   help="DEM steps between surcharge updates and history rows")
    p.add_argument("--checkpoint-minutes", type=float, default=10.0)
    p.add_argument("--stop-after-minutes", type=float, default=0.0,
                   help="checkpoint and stop after this long (continue with --resume)")
    p.add_argument("--resume", action="store_true", help="continue DIR from its checkpoint")
    p.add_argument("--start-from", metavar="RUN_DIR",
                   help="load the settled block of an earlier run (e.g. at another speed)")
    a = p.parse_args()
    for name in ("scale", "settlement", "speed_factor", "fields_every"):
        v = getattr(a, name)
        if not math.isfinite(v) or v <= 0:
            raise InputError(f"--{name.replace('_', '-')}: must be > 0, got {v}")
    if a.resume and a.start_from:
        raise InputError("--resume and --start-from exclude each other")
    if a.np < 1 or a.surcharge_every < 1:
        raise InputError("--np and --surcharge-every must be >= 1")
    case = read_json(a.case)
    pb = problem(case, a.case, a.scale)
    check_memory(pb, a.scale)
    state = restart = None
    if a.resume:
        state = read_json(os.path.join(a.output, "checkpoint.json"))
        restart = os.path.join(a.output, "checkpoint.restart")
    elif os.path.exists(os.path.join(a.output, "history.csv")) or \
            os.path.exists(os.path.join(a.output, "checkpoint.json")):
        raise InputError(f"{a.output}: holds a run already (continue it with --resume)")
    if a.start_from:
        # a settled block of an earlier run (another speed): its packing, a fresh loading
        state = read_json(os.path.join(a.start_from, "settled.json"))
        restart = os.path.join(a.start_from, "settled.restart")
        for k, v in (("scale", a.scale), ("seed", a.seed)):
            if state.get(k) not in (None, v):
                raise InputError(f"--start-from {a.start_from}: its --{k} is {state.get(k)}, "
                                 f"not {v}")
    os.makedirs(a.output, exist_ok=True)
    run = Run(pb, a, a.output)
    run.open()
    finished = False
    try:
        if state:
            run.resume(state, restart)
        else:
            print(f"direct DEM of {a.case}: about {pb['grains']} grains, B/d = "
                  f"{pb['B'] / pb['d']:.1f}, footing {pb['speed'] * a.speed_factor:.4g} m/s, "
                  f"dt {pb['dt']:.4g} s", flush=True)
            run.prepare()
        stage = state["stage"] if state else "prepare"
        if stage == "prepare":
            if state:
                run.consolidate()
            run.open_block()
            run.settle()
            ids, xy, _ = run.grains_now()
            order = np.argsort(ids)
            np.savez(os.path.join(a.output, "reference.npz"), ids=ids[order], xy=xy[order],
                     base=run.base_ids, footing=run.footing_ids)
            run.checkpoint("settled", "settled")
        elif stage == "settled" and a.start_from:
            shutil.copy(os.path.join(a.start_from, "reference.npz"), a.output)
        reference = np.load(os.path.join(a.output, "reference.npz"))
        run.ref_ids, run.ref_xy = reference["ids"], reference["xy"]
        loading = stage == "load"
        if not loading:
            run.load_steps = 0
        run.field_out = FieldOutput(a.output, resume=loading)
        finished = run.load(loading)
        run.checkpoint("load")
    except Stopped:
        pass
    finally:
        run.final_cpu = run.cpu_seconds()
        run.session.close()
    if not os.path.isfile(os.path.join(a.output, "history.csv")):
        print(f"stopped during the preparation: continue with --resume {a.output}")
        sys.exit(3)
    summary = summarise(run, pb, a, a.output, finished)
    chains_picture(a.output)
    print(f"{'finished' if finished else 'stopped (continue with --resume)'}: peak q/q_s "
          f"{summary['peak_q_over_qs']:.2f} at s/B {summary['peak_at_s_over_B']:.2f}, "
          f"{summary['particle_steps']:.3g} particle-steps, {summary['wall_seconds'] / 60:.1f} min")
    if not finished:
        sys.exit(3)


def entry():
    """The command: tools/direct_dem.py in a checkout, mpm-lig-direct-dem installed."""
    cli.run(main, failures=RuntimeError)


if __name__ == "__main__":
    entry()
