"""The footing problem a direct DEM runs (tools/direct_dem.py): the case checked and turned into
what the run needs."""
import math

import numpy as np

from mpm_lig_post.errors import InputError
from mpm_lig_post.footing import footing, surcharge
from mpm_lig_post.liggghts import rayleigh_time_step

BYTES_PER_GRAIN = 4 * 1.1e6 / 400  # the engine's measured 2.75 kB per grain (src/rve/spec.cpp), x4
MAX_GRAINS = 2_000_000
# The smallest problem the run can model: a footing and a block of a few grains at least (a
# smaller --scale gets the engine's neighbour-list overflow, not an answer).
MIN_B_OVER_D = 2.0
MIN_BLOCK_OVER_D = 8.0


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
    check_contact(need(rve, "contact", "materials[0].rve"), where)
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
    if B / d < MIN_B_OVER_D or min(scale * box_max) / d < MIN_BLOCK_OVER_D:
        raise InputError(f"--scale {scale:g}: a footing {B / d:.3g} and a block "
                         f"{min(scale * box_max) / d:.3g} grain diameters wide; the direct DEM "
                         f"needs B/d >= {MIN_B_OVER_D:g} and a block >= {MIN_BLOCK_OVER_D:g} d")
    return {"rve": rve, "qs": qs, "p0": p0, "e0": e0, "B": B, "box": scale * box_max,
            "grains": grains, "dt": dt, "speed": speed, "d": d, "rmin": rmin, "rmax": rmax,
            "thickness": float(rve.get("thickness", d)), "inertial": inertial,
            "prep": prep, "mesh": {"origin": scale * np.asarray(mesh["origin"], float),
                                   "size": scale * np.asarray(mesh["size"], float),
                                   "cells": [int(c) for c in mesh["cells"]]},
            "scale": scale}


def check_contact(contact, where):
    """The contact law's keys as src/rve/spec.cpp reads them: numbers, one of each pair."""
    path = "materials[0].rve.contact"
    if not isinstance(contact, dict):
        raise InputError(where(f"{path}: must be an object"))
    number(required(contact, "youngs_modulus", path), where(f"{path}.youngs_modulus"))
    for pair in (("friction", "friction_deg"), ("stiffness_ratio", "poisson_ratio"),
                 ("damping_ratio", "restitution")):
        given = [k for k in pair if k in contact]
        if len(given) != 1:
            raise InputError(where(f"{path}: needs one of {' or '.join(pair)}"))
        number(contact[given[0]], where(f"{path}.{given[0]}"), positive=False)
    if "friction_deg" in contact and not 0 <= contact["friction_deg"] < 90:
        raise InputError(where(f"{path}.friction_deg: must be in [0, 90), got "
                               f"{contact['friction_deg']!r}"))
    if "damping_ratio" in contact and not 0 < contact["damping_ratio"] < 1:
        raise InputError(where(f"{path}.damping_ratio: must be in (0, 1), got "
                               f"{contact['damping_ratio']!r}"))
    for key in ("rolling_friction", "cohesion_energy_density"):
        if key in contact:
            number(contact[key], where(f"{path}.{key}"), positive=False)


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


def contact_friction(rve):
    c = rve["contact"]
    return c["friction"] if "friction" in c else math.tan(math.radians(c["friction_deg"]))
