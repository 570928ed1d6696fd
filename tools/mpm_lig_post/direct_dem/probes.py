"""Probes of a direct DEM (--probes): at chosen places, windows (the RVE's size unless given) that follow
their grains, with the window's deformation gradient (least squares of the grains' affine map
from the start of loading) and its grains' own stress (Love-Weber, love_weber.py) every
--probes-every s/B, in probes.csv. tools/replay_direct_dem.py drives RVEs along each window's F
and sets their stress beside the grains'."""
import math
import os

import numpy as np

from mpm_lig_post.direct_dem.cells import cells_volumetric, walled_areas
from mpm_lig_post.errors import InputError
from mpm_lig_post.love_weber import invariants, window_stress

# Named places: the window's centre at (x / B from the footing's axis, depth / B below the
# surface), clamped so that the window stays inside the block.
PLACES = {"wedge": (0.25, 0.35),     # under the footing, the rigid wedge
          "band": (0.65, 0.65),      # below the footing's edge, where the slip band runs
          "passive": (1.3, 0.3),     # beside the footing, the passive zone that heaves
          "far": (2.4, 2.0)}         # far away, the soil that hardly moves
# cells_volumetric: ln of the window's grains' summed Voronoi cells against the start of
# loading (cells.py), the grains' own volume change; det F of the least-squares F is not it.
COLUMNS = ("probe", "step", "time", "s_over_B", "F11", "F12", "F21", "F22", "s_xx", "s_yy",
           "s_xy", "p", "q", "grains", "contacts", "cells_volumetric")


# The numeric columns a reader of probes.csv takes (replay_direct_dem, mpm_probes).
READ_COLUMNS = ("s_over_B", "time", "F11", "F12", "F21", "F22", "s_xx", "s_yy", "s_xy", "p",
                 "q")
OPTIONAL_COLUMNS = ("cells_volumetric",)


def read_probes(run):
    """{probe: {column: array}} from RUN/probes.csv, rows in order."""
    path = os.path.join(run, "probes.csv")
    if not os.path.isfile(path):
        raise InputError(f"{path}: no probes (run tools/direct_dem.py with --probes)")
    with open(path) as f:
        header = f.readline().strip().split(",")
        rows = [line.strip().split(",") for line in f if line.strip()]
    missing = [c for c in ("probe",) + READ_COLUMNS if c not in header]
    if missing:
        raise InputError(f"{path}: no column {missing[0]}")
    probes = {}
    for k, row in enumerate(rows):
        if len(row) != len(header):
            raise InputError(f"{path}: row {k + 1} has {len(row)} values, the header "
                             f"{len(header)}")
        probes.setdefault(row[0], []).append(row)
    out = {}
    # cells_volumetric is read where the file has it (probes.csv of earlier tools has not)
    read = READ_COLUMNS + tuple(c for c in OPTIONAL_COLUMNS if c in header)
    for name, got in probes.items():
        try:
            table = {c: np.array([float(r[header.index(c)]) for r in got]) for c in read}
        except ValueError as e:
            raise InputError(f"{path}: probe {name}: {e}") from None
        if len(got) < 2:
            raise InputError(f"{path}: probe {name} has {len(got)} row; a path needs two")
        out[name] = table
    if not out:
        raise InputError(f"{path}: no probe rows")
    return out


def parse(names):
    """[(name, x/B, depth/B, side in grain diameters or None)] from NAME or
    NAME=X:DEPTH[:SIDE] (X, DEPTH in footing widths); InputError naming a bad one. A probe
    without its own SIDE takes --probe-window's."""
    probes = []
    for text in names:
        name, _, where = text.partition("=")
        side = None
        if where:
            try:
                values = [float(v) for v in where.split(":")]
            except ValueError:
                values = []
            if len(values) not in (2, 3):
                raise InputError(f"--probes {text}: give NAME or NAME=X:DEPTH[:SIDE] (X, DEPTH "
                                 "in footing widths, SIDE in grain diameters)")
            x, depth = values[:2]
            if not (math.isfinite(x) and math.isfinite(depth) and x >= 0 and depth >= 0):
                raise InputError(f"--probes {text}: X and DEPTH must be finite and >= 0")
            if len(values) == 3:
                side = values[2]
                if not (math.isfinite(side) and side > 0):
                    raise InputError(f"--probes {text}: SIDE must be a finite number of grain "
                                     "diameters > 0")
        elif name in PLACES:
            x, depth = PLACES[name]
        else:
            raise InputError(f"--probes {text}: no such place (named ones: "
                             f"{', '.join(PLACES)}; or NAME=X:DEPTH[:SIDE])")
        if not name.isidentifier():
            raise InputError(f"--probes {text}: a probe's name is letters, digits and _")
        probes.append((name, x, depth, side))
    if len({p[0] for p in probes}) != len(probes):
        raise InputError("--probes: a name given twice")
    return probes


def check_probes(pb, a):
    """The probes' names and windows, before anything runs: InputError naming the option."""
    lx, ly = pb["box"][0], pb["box"][1]
    for name, (_, side) in windows(pb, parse(a.probes), window_side(pb, a), lx, ly).items():
        if side > min(pb["box"]):
            raise InputError(f"--probes {name}: the window ({side:.3g} m, {side / pb['d']:.3g} "
                             f"d) is wider than the block ({min(pb['box']):.3g} m): choose a "
                             "smaller --probe-window or SIDE, or a larger --scale")


def window_side(pb, a):
    """The probes' window side [m]: --probe-window grain diameters, or the RVE's side."""
    return a.probe_window * pb["d"] if a.probe_window else rve_side(pb)


def rve_side(pb):
    """The side [m] of a square RVE of the case's own grains at its target void ratio."""
    rve = pb["rve"]
    mean_r2 = (pb["rmin"] ** 2 + pb["rmin"] * pb["rmax"] + pb["rmax"] ** 2) / 3.0
    return math.sqrt(int(rve.get("grains", 400)) * math.pi * mean_r2 * (1.0 + pb["e0"]))


def windows(pb, probes, side, lx, ly):
    """{name: (centre (2,), side)} in block coordinates: x from the axis, y up from the base,
    the surface at ly; clamped into the block. side: of the probes without their own."""
    out = {}
    for name, x, depth, own in probes:
        own_side = own * pb["d"] if own else side
        half = 0.5 * own_side
        cx = min(max(x * pb["B"], half), lx - half)
        cy = min(max(ly - depth * pb["B"], half), ly - half)
        out[name] = (np.array([cx, cy]), own_side)
    return out


def members(ref_xy, centre, side):
    """The grains whose centres at the start of loading lie in the square window."""
    return np.all(np.abs(ref_xy - centre) <= 0.5 * side, axis=1)


def window_F(ref_xy, cur_xy):
    """The least-squares affine map of the set's centres: x - c = F (X - C)."""
    dX = ref_xy - ref_xy.mean(axis=0)
    dx = cur_xy - cur_xy.mean(axis=0)
    return (dx.T @ dX) @ np.linalg.inv(dX.T @ dX)


class Probes:
    """Bound to a Run: what the probes are, and their rows at each output."""

    def __init__(self, run, names):
        self.run = run
        self.list = parse(names)
        self.side = window_side(run.pb, run.args)
        self.start_cells = None  # every grain's cell at the start of loading, on first use

    def header(self, path):
        with open(path, "w") as f:
            f.write(",".join(COLUMNS) + "\n")

    def file_columns(self, path):
        """The columns of probes.csv as its header has them: a run resumed from a checkpoint
        of an earlier tool, whose file has no cells_volumetric, goes on without it."""
        with open(path) as f:
            return f.readline().strip().split(",")

    def record(self, s):
        """One row per probe for the state now (s the settlement)."""
        run, pb = self.run, self.run.pb
        ids, xy, r, extra = run.grains_moving()
        index = {int(i): k for k, i in enumerate(ids)}
        ref = np.full((len(ids), 2), np.nan)
        where_ref = np.searchsorted(run.ref_ids, ids)
        known = (where_ref < len(run.ref_ids)) & \
            (run.ref_ids[np.minimum(where_ref, len(run.ref_ids) - 1)] == ids)
        ref[known] = run.ref_xy[where_ref[known]]
        first, second, force = run.contacts_now()
        contacts = (np.array([index[int(i)] for i in first], int),
                    np.array([index[int(i)] for i in second], int), force)
        path = os.path.join(run.out, "probes.csv")
        columns = self.file_columns(path)
        with_cells = "cells_volumetric" in columns
        if with_cells:  # a Voronoi tessellation of every grain: only for a file that keeps it
            reach = 4.0 * float(r.max())
            if self.start_cells is None:
                self.start_cells = walled_areas(run.ref_xy, run.lx, reach)
            start = np.full(len(ids), np.nan)
            start[known] = self.start_cells[where_ref[known]]
            now = walled_areas(xy, run.lx, reach)
        rows = []
        for name, (centre, side) in windows(pb, self.list, self.side, run.lx, run.ly).items():
            inside = known & members(np.nan_to_num(ref, nan=-1e30), centre, side)
            F = window_F(ref[inside], xy[inside])
            area = side * side * float(np.linalg.det(F))
            sigma = window_stress(inside, xy, r, contacts, area, pb["thickness"],
                                  extra["mass"], extra["velocity"])
            p, q = invariants(sigma)
            touching = int(np.count_nonzero(inside[contacts[0]] | inside[contacts[1]]))
            values = [name, "%d" % run.steps] + \
                ["%.12g" % v for v in (run.load_steps * pb["dt"], s / pb["B"], F[0, 0], F[0, 1],
                                       F[1, 0], F[1, 1], sigma[0, 0], sigma[1, 1],
                                       sigma[0, 1], p, q)] + \
                ["%d" % int(inside.sum()), "%d" % touching]
            if with_cells:
                values.append("%.12g" % cells_volumetric(start, now, r, inside))
            rows.append(dict(zip(COLUMNS, values)))
        with open(path, "a") as f:
            for row in rows:
                f.write(",".join(row[c] for c in columns) + "\n")
