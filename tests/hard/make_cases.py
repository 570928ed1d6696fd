#!/usr/bin/python3
"""Writes the MPM hard-case inputs of this folder (run it after changing them here; the JSON
files are kept in the repository). Every case is a 1-cell-wide column whose node rows all have a
prescribed velocity, so the motion of the DEM-backed points is known in closed form."""
import json
import math

RVE = {"engine": "liggghts", "dimension": 2, "grains": 60, "radius": {"min": 0.003, "max": 0.007},
       "density": 2650, "seed": 3,
       "contact": {"youngs_modulus": 6e8, "stiffness_ratio": 0.8, "friction_deg": 28.6,
                   "damping_ratio": 0.1},
       "time_step_fraction": 0.15, "preparation": {"confining_pressure": 1e5},
       "substeps": {"fixed": 20}}


def row(y, width, direction, velocity, function=None):
    bc = {"type": "velocity", "direction": direction, "velocity": velocity,
          "nodes": {"box": {"min": [0, y], "max": [width, y]}}}
    if function:
        bc["function"] = function
    return bc


def column(title, cells_high, body_high, dt, steps, rows, output, rve=RVE, points=1):
    width = 0.05
    return {"title": title, "dimension": 2,
            "analysis": {"type": "mpm", "time_step": {"fixed": dt}, "end": {"steps": steps}},
            "mesh": {"origin": [0, 0], "size": [width, width * cells_high],
                     "cells": [1, cells_high]},
            "materials": [{"id": 1, "type": "dem_rve", "packings": 1, "rve": rve}],
            "bodies": [{"material": 1, "box": {"min": [0, 0], "max": [width, width * body_high]},
                        "points_per_cell": points}],
            "boundary_conditions": rows(width), "output": output}


def simple_shear_rows(cells, rate, function, extra=()):
    """v_y = 0 everywhere, base fixed, v_x = rate * y on every node row (homogeneous shear)."""
    def rows(width):
        out = [{"type": "roller", "direction": "y",
                "nodes": {"box": {"min": [0, 0], "max": [width, width * cells]}}},
               {"type": "fixed", "nodes": {"face": "y-"}}]
        out += [row(width * k, width, "x", rate * width * k, function) for k in range(1, cells + 1)]
        return out
    return rows


# Liquefaction in an MPM run: undrained cyclic simple shear of a 2-point column, gamma_a = 2 %,
# 50 steps per quarter cycle (the square velocity wave makes gamma a triangle between +-2 %),
# 6.5 cycles. Measured: p' < 1 % p0' from step 690 (cycle 4) on.
period, amplitude = 0.04, 0.02
layer = column("Hard case: undrained cyclic simple shear of a 60-disc column through liquefaction",
               2, 2, 2e-4, 1300, simple_shear_rows(2, 4 * amplitude / period,
                                                      {"type": "square", "period": period}),
               {"every": 500, "history_every": 5,
                "simple_shear": {"material": 1, "boundary_condition": 3}})
layer["materials"][0]["rve"] = dict(RVE, substeps={"inertial_number": 0.001, "min": 20,
                                                   "max": 400})
json.dump(layer, open("mpm_liquefaction.json", "w"), indent=1)

# Extension: v_y = a y on every row: det F = exp(a t) = 1.5 at the end; the body fills 2 of 4
# cells at the start and 3 at the end.
a = 5.0
steps = math.ceil(math.log(1.5) / a / 2e-4)
def extension_rows(width):
    out = [{"type": "roller", "direction": "x",
            "nodes": {"box": {"min": [0, 0], "max": [width, width * 4]}}},
           {"type": "fixed", "nodes": {"face": "y-"}}]
    return out + [row(width * k, width, "y", a * width * k) for k in range(1, 5)]
ext = column("Hard case: a DEM-backed column pulled apart to det F = 1.5", 4, 2, 2e-4, steps,
             extension_rows, {"every": steps, "history_every": 5}, points=2)
ext["_about"] = "v_y = %g y on every node row for %d steps of 2e-4 s: det F = exp(%g t) = 1.5" % (
    a, steps, a)
json.dump(ext, open("mpm_extension.json", "w"), indent=1)

# Large shear: monotonic simple shear to gamma = 5 (five cell-basis reductions of the RVE).
# The square wave keeps its sign for the first quarter period: a period of 4 t_end makes the
# shear monotonic and gives the simple-shear history columns.
rate, dt = 10.0, 2e-4
shear = column("Hard case: simple shear of a DEM-backed column to gamma = 500 %", 1, 1, dt,
               round(5.0 / rate / dt),
               simple_shear_rows(1, rate, {"type": "square", "period": 4 * 5.0 / rate}),
               {"every": 500, "history_every": 1,
                "simple_shear": {"material": 1, "boundary_condition": 2}},
               rve=dict(RVE, substeps={"fixed": 100}))
# Periodic along x (a laterally infinite layer): the points cross the seam instead of the edge.
shear["mesh"].update(size=[0.1, 0.05], cells=[2, 1], periodic=["x"])
shear["bodies"][0]["box"]["max"] = [0.1, 0.05]
for bc in shear["boundary_conditions"]:
    bc["nodes"].get("box", {}).get("max", [0])[0:1] = [0.1]
json.dump(shear, open("mpm_large_shear.json", "w"), indent=1)

# A body carried out of the mesh: every node moves with v_x = 0.5 m/s; the point (0.075 m from
# the mesh's far edge) leaves after 0.15 s = 750 steps; checkpoints every 100 steps.
def carried(width):
    return [{"type": "velocity", "direction": d, "velocity": v,
             "nodes": {"box": {"min": [0, 0], "max": [2 * width, width]}}}
            for d, v in (("x", 0.5), ("y", 0.0))]
out = column("Hard case: a DEM-backed point carried out of the mesh", 1, 1, 2e-4, 1000, carried,
             {"every": 100, "history_every": 10, "checkpoint_every": 100})
out["mesh"]["size"], out["mesh"]["cells"] = [0.1, 0.05], [2, 1]
json.dump(out, open("mpm_leaves_mesh.json", "w"), indent=1)

# Rigid rotation by 360 degrees: every node turns about the body's centre (boundary condition
# `rotation`), so L is a pure spin at every point; 1000 steps of 2e-4 s, fields every 45 degrees.
turn_steps, turn_dt = 1000, 2e-4
omega = 2 * math.pi / (turn_steps * turn_dt)
def turning(width):
    return [{"type": "rotation", "center": [0.1, 0.1], "angular_velocity": omega,
             "nodes": {"box": {"min": [0, 0], "max": [4 * width, 4 * width]}}}]
turn = column("Hard case: a DEM-backed body turned rigidly by 360 degrees", 4, 2, turn_dt,
              turn_steps, turning, {"every": turn_steps // 8, "history_every": 10})
turn["mesh"].update(size=[0.2, 0.2], cells=[4, 4])
turn["bodies"][0]["box"] = {"min": [0.05, 0.05], "max": [0.15, 0.15]}
turn["_about"] = "omega = 2 pi / (%d x %g s): one full turn" % (turn_steps, turn_dt)
json.dump(turn, open("mpm_rotation.json", "w"), indent=1)
# Its twin at rest (the same nodes held still): what the packings do on their own over those
# 1000 updates, against which the turned stresses are compared.
still = json.loads(json.dumps(turn))
still["title"] = "Hard case: the rigid-rotation body held still (its reference)"
still["boundary_conditions"][0]["angular_velocity"] = 0.0
still["_about"] = "the twin of mpm_rotation.json with omega = 0"
json.dump(still, open("mpm_rotation_still.json", "w"), indent=1)

# A velocity step on a boundary: the top of a 2-point column is pressed at 10 cm/s from rest
# (a step at t = 0: strain rate 1/s), and the velocity reverses at once at t = 0.01 s (strain
# 1 %) and again at 0.03 s: steps of 20 cm/s in one MPM step; 0.04 s in all. The RVEs'
# sub-steps follow the strain rate (inertial number).
def pressed(velocity, period):
    def rows(width):
        return [{"type": "roller", "direction": "x",
                 "nodes": {"box": {"min": [0, 0], "max": [width, 2 * width]}}},
                {"type": "fixed", "nodes": {"face": "y-"}},
                row(2 * width, width, "y", -velocity, {"type": "square", "period": period})]
    return rows
step_rve = dict(RVE, substeps={"inertial_number": 0.001, "min": 10, "max": 400})
jump = column("Hard case: velocity steps (pressed from rest, reversed twice) on the top of a "
              "DEM-backed column", 2, 2, 2e-4, 200, pressed(0.1, 0.04),
              {"every": 5, "history_every": 1}, rve=step_rve)
json.dump(jump, open("mpm_velocity_step.json", "w"), indent=1)
# Its broken variant: a step to 20 m/s (compression 4 % per MPM step) with sub-steps held at 10
# and positions remapped: the DEM cannot follow, the health check must stop the run naming
# the point.
violent = column("Hard case (broken on purpose): a velocity step far too fast for the DEM", 2, 2,
                 2e-4, 100, pressed(20.0, 0.4), {"every": 100},
                 rve=dict(RVE, substeps={"fixed": 10}, affine_motion="remap_positions"))
json.dump(violent, open("mpm_velocity_step_too_fast.json", "w"), indent=1)

# A tiny DEM footing pushed to d/B = 1.5: a rough strip (B = 0.1 m, half model) at 1 m/s into a
# 0.3 x 0.35 m block of 42 DEM-backed points (h = B/2) under a 20 kPa surcharge, 0.15 s.
footing = {
    "title": "Hard case: a tiny DEM footing pushed to d/B = 1.5",
    "dimension": 2,
    "analysis": {"type": "mpm", "shape_function": "gimp", "damping": 0.1,
                 "volumetric_smoothing": True, "time_step": {"cfl": 0.5}, "end": {"time": 0.15}},
    "mesh": {"origin": [0, 0], "size": [0.3, 0.45], "cells": [6, 9]},
    "materials": [{"id": 1, "type": "dem_rve", "packings": 1,
                   "rve": dict(RVE, substeps={"inertial_number": 0.003, "min": 10, "max": 200})}],
    "bodies": [{"material": 1, "box": {"min": [0, 0], "max": [0.3, 0.35]},
                "points_per_cell": 1}],
    "boundary_conditions": [
        {"type": "roller", "direction": "x", "nodes": {"face": "x-"}},
        {"type": "roller", "direction": "x", "nodes": {"face": "x+"}},
        {"type": "fixed", "nodes": {"face": "y-"}},
        {"type": "traction", "traction": [0, -2e4],
         "points": {"min": [0.05, 0.3], "max": [0.3, 0.35]}}],
    "rigid_bodies": [{"type": "footing", "center": [0.0], "width": [0.1], "base": 0.35,
                      "velocity": 1.0, "interface": "rough", "keep_points_out": True}],
    "output": {"every": 300, "history_every": 10}}
json.dump(footing, open("mpm_footing_deep.json", "w"), indent=1)

# A free surface unloaded: a column prepared at 100 kPa with nothing on its top (no surcharge)
# springs up and falls back under gravity to rest at its own weight (1-2 kPa): the stress of a
# DEM-backed body goes from p0' to almost zero without NaN or a lost grain. Damping 0.1, 0.3 s.
def held_sides(width):
    return [{"type": "roller", "direction": "x",
             "nodes": {"box": {"min": [0, 0], "max": [width, 3 * width]}}},
            {"type": "fixed", "nodes": {"face": "y-"}}]
free = column("Hard case: the free surface of a DEM-backed column unloaded to zero stress", 3, 2,
              2e-4, 1500, held_sides, {"every": 250, "history_every": 10})
free["analysis"]["damping"] = 0.1
free["gravity"] = [0, -9.81]
json.dump(free, open("mpm_free_surface.json", "w"), indent=1)
