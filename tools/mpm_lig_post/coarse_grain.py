"""Grain motion coarse-grained onto material points (tools/direct_dem.py): at each point a
Gaussian-weighted least-squares fit of the affine map X -> x of the grains around it gives the
deformation gradient F (so an affinely deformed packing returns its F exactly), hence the
Hencky strain and eps_q as mpm_lig's field writer defines them (src/mpm/recorder.cpp,
src/core/tensor.h), and the point's displacement; and a results.h5 / results.xdmf pair with
the layout of src/io/field_writer.cpp that tools/plot_fields.py and ParaView read."""
import os

import numpy as np

from .errors import InputError

# A point sees the grains within this many Gaussian widths.
REACH = 2.5


def affine_fit(reference, current, points, width):
    """(F (n x 2 x 2), displacement (n x 2), grains used (n)) at `points` (n x 2): weighted
    least squares of current - c = F (reference - C) over the grains within REACH x width of
    each point, c and C the weighted centroids; displacement = c + F (point - C) - point.
    Points with fewer than 3 grains in reach get F = identity and zero displacement."""
    from scipy.spatial import cKDTree  # noqa: imported on use

    tree = cKDTree(reference)
    n = len(points)
    F = np.tile(np.eye(2), (n, 1, 1))
    u = np.zeros((n, 2))
    used = np.zeros(n, int)
    for k, near in enumerate(tree.query_ball_point(points, REACH * width)):
        if len(near) < 3:
            continue
        X, x = reference[near], current[near]
        w = np.exp(-0.5 * np.sum((X - points[k]) ** 2, axis=1) / width ** 2)
        C = w @ X / w.sum()
        c = w @ x / w.sum()
        dX, dx = X - C, x - c
        A = (dX * w[:, None]).T @ dX
        if np.linalg.cond(A) > 1e8:
            continue
        F[k] = ((dx * w[:, None]).T @ dX) @ np.linalg.inv(A)
        u[k] = c + F[k] @ (points[k] - C) - points[k]
        used[k] = len(near)
    return F, u, used


def hencky(F2):
    """Hencky strain 1/2 log(F^T F) of in-plane deformation gradients, as 3 x 3 (plane strain)."""
    n = len(F2)
    out = np.zeros((n, 3, 3))
    C = np.einsum("kji,kjl->kil", F2, F2)
    values, vectors = np.linalg.eigh(C)
    logs = 0.5 * np.log(np.maximum(values, 1e-300))
    out[:, :2, :2] = np.einsum("kij,kj,klj->kil", vectors, logs, vectors)
    return out


def deviatoric_strain(strain):
    """eps_q = sqrt(2/3 e:e), e the deviatoric part (src/core/tensor.h)."""
    e = strain - np.trace(strain, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
    return np.sqrt(2.0 / 3.0 * np.einsum("kij,kij->k", e, e))


def mesh_points(origin, size, cells, box_min, box_max):
    """Cell centres of a mesh (one point per cell) inside a body box: the material points of
    a points_per_cell 1 body (n x 2), and the cell size."""
    h = np.asarray(size, float) / np.asarray(cells, float)
    xs = origin[0] + h[0] * (np.arange(cells[0]) + 0.5)
    ys = origin[1] + h[1] * (np.arange(cells[1]) + 0.5)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    pts = np.column_stack([X.ravel(), Y.ravel()])
    inside = np.all((pts >= np.asarray(box_min) - 1e-12) & (pts <= np.asarray(box_max) + 1e-12),
                    axis=1)
    return pts[inside], h


XDMF_HEAD = """<?xml version="1.0" ?>
<Xdmf Version="3.0">
 <Domain>
  <Grid Name="points" GridType="Collection" CollectionType="Temporal">
"""
XDMF_STEP = """   <Grid Name="{group}" GridType="Uniform">
    <Time Value="{time!r}"/>
    <Topology TopologyType="Polyvertex" NumberOfElements="{n}"/>
    <Geometry GeometryType="XYZ">
     <DataItem Dimensions="{n} 3" NumberType="Float" Precision="8" Format="HDF">{h5}:/{group}/positions</DataItem>
    </Geometry>
{attributes}   </Grid>
"""
XDMF_ATTRIBUTE = """    <Attribute Name="{name}" AttributeType="{kind}" Center="Node">
     <DataItem Dimensions="{dims}" NumberType="Float" Precision="8" Format="HDF">{h5}:/{group}/{name}</DataItem>
    </Attribute>
"""


class FieldOutput:
    """results.h5 (groups step_NNNNNN: attributes time and step, `positions` n x 3 and the
    fields) and results.xdmf beside it, rewritten after every step."""

    def __init__(self, directory, resume=False):
        try:
            import h5py
        except ImportError:
            raise InputError("python3-h5py is not installed (apt-get install python3-h5py)") from None
        self.h5py = h5py
        self.path = os.path.join(directory, "results.h5")
        self.xdmf = os.path.join(directory, "results.xdmf")
        if not resume or not os.path.isfile(self.path):
            with h5py.File(self.path, "w"):
                pass
        self._write_xdmf()

    def steps(self):
        with self.h5py.File(self.path, "r") as f:
            return sorted(int(g[5:]) for g in f if g.startswith("step_"))

    def add(self, step, time, positions, fields):
        """One output step: positions (n x 2 or 3) and {name: array (n), (n x 3) or (n x 3 x 3)}."""
        n = len(positions)
        xyz = np.zeros((n, 3))
        xyz[:, : positions.shape[1]] = positions
        with self.h5py.File(self.path, "a") as f:
            name = f"step_{step:06d}"
            if name in f:
                del f[name]
            g = f.create_group(name)
            g.attrs["time"] = float(time)
            g.attrs["step"] = int(step)
            g.create_dataset("positions", data=xyz)
            for key, value in fields.items():
                value = np.asarray(value, float)
                if value.ndim == 3:
                    value = value.reshape(n, 9)
                g.create_dataset(key, data=value)
        self._write_xdmf()

    def _write_xdmf(self):
        h5 = os.path.basename(self.path)
        text = [XDMF_HEAD]
        with self.h5py.File(self.path, "r") as f:
            for group in sorted(g for g in f if g.startswith("step_")):
                g = f[group]
                n = len(g["positions"])
                attributes = []
                for name in g:
                    if name == "positions":
                        continue
                    shape = g[name].shape
                    kind = {1: "Scalar", 3: "Vector", 9: "Tensor"}.get(
                        shape[1] if len(shape) > 1 else 1, "Matrix")
                    dims = " ".join(str(s) for s in shape)
                    attributes.append(XDMF_ATTRIBUTE.format(name=name, kind=kind, dims=dims, h5=h5,
                                                            group=group))
                text.append(XDMF_STEP.format(group=group, time=float(g.attrs["time"]), n=n, h5=h5,
                                             attributes="".join(attributes)))
        text.append("  </Grid>\n </Domain>\n</Xdmf>\n")
        with open(self.xdmf + ".tmp", "w") as out:
            out.write("".join(text))
        os.replace(self.xdmf + ".tmp", self.xdmf)


def point_fields(reference, current, points, width, cell_area):
    """The field writer's datasets at the points from the grains' reference and current
    centres (n x 2): positions, displacement, strain, deviatoric_strain, volume, material."""
    F, u, used = affine_fit(reference, current, points, width)
    strain = hencky(F)
    n = len(points)
    disp = np.zeros((n, 3))
    disp[:, :2] = u
    return points + u, {"displacement": disp, "strain": strain,
                        "deviatoric_strain": deviatoric_strain(strain),
                        "volume": cell_area * np.linalg.det(F),
                        "material": np.ones(n), "grains_used": used}
