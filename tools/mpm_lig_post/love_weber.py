"""The grains' own stress over a set of discs (Love-Weber): the contact part
(1/V) sum over the set's grains p and their contacts c of f_c (x) (x_c - x_p), the contact point
x_c on the branch vector at r_p / (r_p + r_q) of it, minus the kinetic part
(1/V) sum m v' (x) v' (v' the velocity about the set's mean). A contact between two grains of
the set counts as f (x) l (l the branch vector from the grain the force acts on to the other);
one that leaves the set counts its half arm, so windows add up to the whole. Tension positive,
N/m^2 with V = area x thickness (the discs' thickness, as the RVEs)."""
import numpy as np


def branch_vectors(xy_first, xy_second, period=None):
    """second - first, by the minimum image along the periodic axes of `period` (lx, ly or
    None per axis)."""
    l = xy_second - xy_first
    if period is not None:
        for axis, length in enumerate(period):
            if length:
                l[:, axis] -= length * np.round(l[:, axis] / length)
    return l


def window_stress(members, xy, radii, contacts, area, thickness, masses=None, velocities=None,
                  period=None, symmetric=True):
    """2 x 2 Cauchy stress (tension positive) of the grains where `members` (bool per grain) is
    true. `contacts`: (first, second, fx, fy) with first / second grain indices into xy and
    (fx, fy) the force on `first` from `second`; `area` the set's area [m^2]. With masses
    (per grain) and velocities (n x 2) the kinetic part is included. symmetric=False keeps the
    antisymmetric part (the grains' rolling torques and angular accelerations over V)."""
    first, second, force = contacts
    first = np.asarray(first, int)
    second = np.asarray(second, int)
    force = np.asarray(force, float).reshape(-1, 2)
    l = branch_vectors(xy[first], xy[second], period)
    share_first = radii[first] / (radii[first] + radii[second])
    # on `first`: f at arm share_first * l; on `second`: -f at arm -(1 - share_first) * l
    arm_first = share_first[:, None] * l
    arm_second = -(1.0 - share_first)[:, None] * l
    total = np.zeros((2, 2))
    a = members[first]
    total += np.einsum("ki,kj->ij", force[a], arm_first[a])
    b = members[second]
    total += np.einsum("ki,kj->ij", -force[b], arm_second[b])
    if masses is not None and velocities is not None and np.any(members):
        m = masses[members]
        v = velocities[members]
        v = v - (m @ v) / m.sum()
        total -= np.einsum("k,ki,kj->ij", m, v, v)
    sigma = total / (area * thickness)
    return 0.5 * (sigma + sigma.T) if symmetric else sigma


def invariants(sigma):
    """(p, q) of a plane 2 x 2 stress (tension positive) as a 2D element test writes them
    (docs/outputs.md §3): p = -(s_xx + s_yy)/2, q = the radius of Mohr's circle, so that q/p is
    the sine of the mobilised friction angle."""
    sxx, syy, sxy = sigma[..., 0, 0], sigma[..., 1, 1], sigma[..., 0, 1]
    p = -0.5 * (sxx + syy)
    q = np.sqrt(0.25 * (sxx - syy) ** 2 + sxy ** 2)
    return p, q
