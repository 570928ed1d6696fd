"""The direct DEM's grains: radii drawn and centres placed as src/rve/packing.cpp does, a
periodic cell repeated into a larger one, and the contact fabric of a packing."""

import numpy as np

from mpm_lig_post.errors import InputError


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




def tile(xy, radii, velocities, cell, tiles):
    """A periodic packing repeated tiles x tiles times: centres, radii and velocities of the
    larger periodic cell (its images continue across every seam as across the cell's own
    faces, so the larger packing has the cell's void ratio, stress and fabric)."""
    shifts = np.array([(i * cell[0], j * cell[1]) for j in range(tiles) for i in range(tiles)])
    n = len(xy)
    big_xy = (xy[None, :, :] + shifts[:, None, :]).reshape(-1, 2)
    return (big_xy, np.tile(radii, len(shifts)), np.tile(velocities, (len(shifts), 1)),
            (tiles * cell[0], tiles * cell[1]), n * len(shifts))


def fabric(xy, radii, cell, origin):
    """Contact fabric of a periodic packing from its geometry (grains that overlap): the number
    of contacts, the mean coordination number 2 Nc / N, and the anisotropy of the contact
    normals a = 2 (l1 - l2) / (l1 + l2), l the eigenvalues of the fabric tensor <n (x) n>
    (0 for an isotropic packing), with the direction of l1 in degrees from x."""
    from scipy.spatial import cKDTree  # noqa: imported on use

    box = np.asarray(cell, float)
    wrapped = np.mod(xy - np.asarray(origin, float), box)
    wrapped = np.minimum(wrapped, np.nextafter(box, 0))  # inside [0, L) for the periodic tree
    tree = cKDTree(wrapped, boxsize=box)
    pairs = tree.query_pairs(2.0 * float(radii.max()), output_type="ndarray")
    d = wrapped[pairs[:, 1]] - wrapped[pairs[:, 0]]
    d -= box * np.round(d / box)
    length = np.hypot(d[:, 0], d[:, 1])
    touching = length < radii[pairs[:, 0]] + radii[pairs[:, 1]]
    n = d[touching] / length[touching, None]
    if not len(n):
        return {"contacts": 0, "coordination": 0.0, "anisotropy": 0.0, "direction_deg": 0.0}
    phi = n.T @ n / len(n)
    values, vectors = np.linalg.eigh(phi)
    return {"contacts": int(len(n)), "coordination": 2.0 * len(n) / len(xy),
            "anisotropy": float(2.0 * (values[1] - values[0]) / values.sum()),
            "direction_deg": float(np.degrees(np.arctan2(vectors[1, 1], vectors[0, 1])) % 180.0)}
