"""The grains' own volumes: each grain's Voronoi cell in the block between its side planes.

The sum of a set of grains' cells is the area those grains occupy, whatever they do inside
(slip lines, rattlers); a least-squares affine fit of their centres is not: a slip line
through a window moves its fitted det F by per cents either way (docs/direct_dem.md, "The
grains' volume by their cells"). The side planes are frictionless rollers, so a grain beside
one sees its mirror image: mirrored across the plane, its cell ends there. Without the
mirror a window at the footing's axis (x = 0) counts the open space beyond the plane."""
import numpy as np
from scipy.spatial import Voronoi

# A cell larger than this many times its disc is one the free surface leaves open in effect.
LARGEST_CELL = 2.5


def voronoi_areas(xy):
    """Area of each point's Voronoi cell; nan where the cell is open."""
    v = Voronoi(xy)
    areas = np.full(len(xy), np.nan)
    for i, region in enumerate(v.point_region):
        corners = v.regions[region]
        if corners and -1 not in corners:
            x, y = v.vertices[corners].T
            areas[i] = 0.5 * abs(np.dot(x, np.roll(y, 1)) - np.dot(y, np.roll(x, 1)))
    return areas


def walled_areas(xy, width, reach):
    """Voronoi areas of grains between the side planes x = 0 and x = width, the grains within
    `reach` of a plane mirrored across it."""
    left = xy[xy[:, 0] < reach] * [-1.0, 1.0]
    right = xy[xy[:, 0] > width - reach] * [-1.0, 1.0] + [2.0 * width, 0.0]
    return voronoi_areas(np.vstack([xy, left, right]))[: len(xy)]


def closed(areas, radii):
    """Cells that are closed and no larger than LARGEST_CELL times their disc."""
    return np.isfinite(areas) & (np.nan_to_num(areas, nan=np.inf) <= LARGEST_CELL * np.pi *
                                 radii ** 2)


def cells_volumetric(start, now, radii, inside):
    """ln of the summed cells of the grains `inside` whose cells are closed at both times."""
    kept = inside & closed(start, radii) & closed(now, radii)
    if not kept.any():
        return float("nan")
    return float(np.log(now[kept].sum() / start[kept].sum()))
