"""Synthetic run outputs in the formats the mpm_lig writers produce:
history.csv as src/io/csv_history.cpp (header, %.17g values), legacy VTK as
src/io/vtk_snapshot.cpp, results.h5 as src/io/field_writer.cpp, a cost record as
src/coupling/cost_record.cpp (docs/outputs.md)."""
import os

import numpy as np


def write_history(directory, columns, rows):
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "history.csv"), "w") as f:
        f.write(",".join(columns) + "\n")
        for row in rows:
            f.write(",".join("%.17g" % v for v in row) + "\n")


def _polydata(path, title, points):
    out = open(path, "w")
    out.write(f"# vtk DataFile Version 3.0\n{title}\nASCII\nDATASET POLYDATA\n")
    out.write(f"POINTS {len(points)} double\n")
    for x in points:
        out.write("%.9g %.9g %.9g\n" % tuple(x))
    return out


def write_vtk_grains(path, centres, radii, velocities):
    n = len(centres)
    with _polydata(path, "mpm_lig RVE grains", centres) as out:
        out.write(f"VERTICES {n} {2 * n}\n")
        out.writelines(f"1 {i}\n" for i in range(n))
        out.write(f"POINT_DATA {n}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
        out.writelines("%.9g\n" % r for r in radii)
        out.write("VECTORS velocity double\n")
        out.writelines("%.9g %.9g %.9g\n" % tuple(v) for v in velocities)


def write_vtk_lines(path, starts, ends, name, scalars):
    n = len(starts)
    points = [p for pair in zip(starts, ends) for p in pair]
    with _polydata(path, "mpm_lig RVE " + name, points) as out:
        out.write(f"LINES {n} {3 * n}\n")
        out.writelines(f"2 {2 * i} {2 * i + 1}\n" for i in range(n))
        out.write(f"CELL_DATA {n}\nSCALARS {name} double 1\nLOOKUP_TABLE default\n")
        out.writelines("%.9g\n" % s for s in scalars)


def write_snapshot(prefix, centres, radii, contacts, forces, box):
    """Grains, contact lines (pairs of grain indices) and the cell (box: 3 edge vectors)."""
    centres = np.asarray(centres, float)
    write_vtk_grains(prefix + "_grains.vtk", centres, radii, np.zeros_like(centres))
    write_vtk_lines(prefix + "_contacts.vtk", [centres[i] for i, _ in contacts],
                    [centres[j] for _, j in contacts], "force", forces)
    h = np.asarray(box, float)
    a, b, edge = [], [], []
    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3
        for k in range(4):
            base = (k & 1) * h[u] + ((k >> 1) & 1) * h[w]
            a.append(base)
            b.append(base + h[axis])
            edge.append(axis)
    write_vtk_lines(prefix + "_cell.vtk", a, b, "edge_direction", edge)


def write_fields(directory, steps):
    """steps: list of (step, time, {name: array}); 'positions' required; (n, 6) arrays get
    the Voigt components attribute, int arrays are written as int32."""
    import h5py

    os.makedirs(directory, exist_ok=True)
    with h5py.File(os.path.join(directory, "results.h5"), "w") as f:
        for step, time, data in steps:
            g = f.create_group("step_%06d" % step)
            g.attrs["time"] = np.float64(time)
            g.attrs["step"] = np.int64(step)
            for name, values in data.items():
                values = np.asarray(values)
                if values.dtype.kind == "i":
                    g.create_dataset(name, data=values.astype("<i4"))
                else:
                    d = g.create_dataset(name, data=values.astype("<f8"))
                    if values.ndim == 2 and values.shape[1] == 6:
                        d.attrs["components"] = np.bytes_("xx yy zz xy xz yz")


def write_cost_record(path, steps_per_point, rows, update_cost=0.0, grains=1.0, seconds=1e-3,
                      floor_steps=None):
    """`rows` updates of points that each take the same sub-steps every update."""
    import h5py

    steps = np.tile(np.asarray(steps_per_point, dtype=np.int32), (rows, 1))
    with h5py.File(path, "w") as f:
        f["update"] = np.arange(1, rows + 1, dtype=np.int64)
        f["groups"] = np.ones(rows, dtype=np.int32)
        f["predicted_steps"] = steps
        f["measured_steps"] = steps
        f["seconds"] = np.full(steps.shape, seconds, dtype=np.float32)
        f["group"] = np.zeros(steps.shape, dtype=np.int32)
        f.attrs["grains"] = grains
        f.attrs["update_cost_steps"] = update_cost
        f.attrs["points"] = float(steps.shape[1])
        if floor_steps is not None:
            f.attrs["floor_steps"] = floor_steps
