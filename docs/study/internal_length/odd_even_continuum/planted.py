#!/usr/bin/python3
"""The odd-even probe's Mohr-Coulomb footing (mc_soft.json) with the DEM cases' planted
pattern: alternate columns of points given two soils whose peak friction differs by
CONTRAST degrees (as two packings cloned to alternate columns differ), on h = B/8 or B/16.
Whether the continuum then fills with the column-by-column alternation, and on which mesh,
says whether B/16's mode is the discretisation's answer to a planted imperfection or the
DEM packings' own. With --scattered each cell (one point) draws its soil by the splitmix64
hash of its point's index, as `packing_order` "scattered" draws packings (points numbered
along x first from the soil box's corner at the origin).

usage: planted.py --cells-per-width 4|8|16 [--contrast 1.0] [--scattered] -o CASE.json
"""
import argparse
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def split64(i):
    """splitmix64 of the point's index (the MPM's packing_order "scattered" draws by it)."""
    mask = (1 << 64) - 1
    z = (i + 0x9E3779B97F4A7C15) & mask
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
    return z ^ (z >> 31)


def planted_case(cells_per_width, contrast, scattered):
    case = json.load(open(os.path.join(HERE, "mc_soft.json")))
    width = case["rigid_bodies"][0]["width"][0]
    h = width / cells_per_width
    size = case["mesh"]["size"]
    case["mesh"]["cells"] = [round(size[0] / h), round(size[1] / h)]
    strong = case["materials"][0]
    weak = copy.deepcopy(strong)
    weak["id"] = 2
    weak["friction_deg"] = strong["friction_deg"] - contrast
    case["materials"].append(weak)
    body = case["bodies"][0]
    top = body["box"]["max"][1]
    columns, rows = round(body["box"]["max"][0] / h), round(top / h)
    bodies = []
    for j in range(rows if scattered else 1):
        for i in range(columns):
            k = (split64(j * columns + i) % 2) if scattered else i % 2
            y0, y1 = (j * h, (j + 1) * h) if scattered else (0.0, top)
            bodies.append(dict(copy.deepcopy(body), material=1 + k,
                               box={"min": [i * h, y0], "max": [(i + 1) * h, y1]}))
    case["bodies"] = bodies
    surcharge = case["boundary_conditions"][3]["points"]
    surcharge["min"][1] = top - 0.8 * h  # the top row of points, on either mesh
    order = "cells scattered by a hash" if scattered else "alternate columns"
    case["title"] = (f"odd-even probe: B/{cells_per_width} footing on a softening "
                     f"Mohr-Coulomb soil, peak friction {contrast:g} deg lower in {order}")
    case["_about"] = ("Written by planted.py (docs/methods.md \u00a77): mc_soft.json with the "
                      "DEM cases' packing pattern planted as two soils.")
    case.pop("_run", None)
    return case


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cells-per-width", type=int, choices=(4, 8, 16), required=True)
    p.add_argument("--contrast", type=float, default=1.0)
    p.add_argument("--scattered", action="store_true")
    p.add_argument("-o", "--output", required=True)
    a = p.parse_args()
    with open(a.output, "w") as f:
        json.dump(planted_case(a.cells_per_width, a.contrast, a.scattered), f, indent=1)


if __name__ == "__main__":
    main()
