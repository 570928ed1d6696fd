"""The footing a case describes, read one way by every footing tool (plot_footing.py,
footing_intrusion.py, footing_noise.py and the study's footing quantities): its first rigid body
and the surface surcharge q_s that normalises the load."""
import numpy as np

from .errors import InputError


def surcharge(case, source):
    """q_s [Pa]: the size of the vertical (last) component of the first traction boundary
    condition that has one; None when the case has no such traction. InputError naming
    `source` when boundary_conditions is not a list or a traction not a list of numbers."""
    conditions = case.get("boundary_conditions", [])
    if not isinstance(conditions, list):
        raise InputError(f"{source}: boundary_conditions is not a list")
    for i, bc in enumerate(conditions):
        if not isinstance(bc, dict) or bc.get("type") != "traction" or not bc.get("traction"):
            continue
        try:
            vertical = float(bc["traction"][-1])
        except (TypeError, ValueError, KeyError, IndexError):
            raise InputError(f"{source}: boundary_conditions[{i}].traction is not a list of "
                             "numbers") from None
        if vertical != 0.0:
            return abs(vertical)
    return None


def footing(case, source):
    """(centre, width, base) of rigid_bodies[0]: centre and width as float arrays, base a float.
    InputError naming `source` when the case has no such footing."""
    try:
        body = case["rigid_bodies"][0]
        centre = np.asarray(body["center"], float)
        width = np.asarray(body["width"], float)
        base = float(body["base"])
    except (KeyError, IndexError, TypeError, ValueError):
        raise InputError(f"{source}: no rigid_bodies[0] with center, width and base") from None
    return centre, width, base


def width(case, source):
    """B [m]: the first horizontal width of rigid_bodies[0] (the only footing value some tools need)."""
    try:
        return float(case["rigid_bodies"][0]["width"][0])
    except (KeyError, IndexError, TypeError, ValueError):
        raise InputError(f"{source}: no rigid_bodies[0].width") from None
