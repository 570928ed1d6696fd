"""Accuracy against cost: each variant's relative error against the reference (the mean over
the reference's seeds), the reference's seed-to-seed scatter as the noise floor, the Pareto
front of error over core-seconds, and the rate cost model with its prediction errors.

Errors are relative: a scalar |Q - Q_ref| / |Q_ref|; a curve the RMS over the reference's x of
the difference, over max |y_ref|; a per-cycle series the RMS of Q_c / Q_ref,c - 1 over the
cycles both have. A scalar whose reference can be near zero (angles) is absolute instead:
|Q - Q_ref| in its unit. The noise floor is the same measure's sample standard deviation over the
reference's seeds (n - 1 in the denominator).
"""
import math

import numpy as np

from .quantities import SCALAR, SERIES


def _curve_on(x_ref, curve):
    x, y = curve
    order = np.argsort(x)
    return np.interp(x_ref, np.asarray(x)[order], np.asarray(y)[order], left=np.nan,
                     right=np.nan)


def reference_value(kind, values):
    """The mean of the reference's seeds (values: one per seed, None where not reached)."""
    values = [v for v in values if v is not None]
    if not values:
        return None
    if kind == SCALAR:
        return float(np.mean(values))
    if kind == SERIES:
        n = min(len(v) for v in values)
        return np.mean([np.asarray(v[:n]) for v in values], axis=0)
    x = np.asarray(values[0][0])
    ys = np.array([_curve_on(x, v) for v in values])
    keep = ~np.isnan(ys).any(axis=0)
    return x[keep], ys[:, keep].mean(axis=0)


def deviation(kind, value, ref, absolute=False):
    """Signed (scalar) or RMS (curve, series) difference from the reference, relative (or, for
    an absolute scalar, in its unit)."""
    if value is None or ref is None:
        return None
    if kind == SCALAR:
        if absolute:
            return value - ref
        return (value - ref) / abs(ref) if ref != 0 else None
    if kind == SERIES:
        n = min(len(value), len(ref))
        if n == 0:
            return None
        return float(np.sqrt(np.mean((np.asarray(value[:n]) / ref[:n] - 1.0) ** 2)))
    x_ref, y_ref = ref
    y = _curve_on(x_ref, value)
    inside = ~np.isnan(y)
    scale = np.max(np.abs(y_ref))
    if not inside.any() or scale == 0:
        return None
    return float(np.sqrt(np.mean((y[inside] - y_ref[inside]) ** 2)) / scale)


def error(kind, value, ref, absolute=False):
    """The error (>= 0) of a value against the reference value: relative, or absolute."""
    d = deviation(kind, value, ref, absolute)
    return None if d is None else abs(d)


def noise_floor(kind, seed_values, ref, absolute=False):
    """The reference's seed-to-seed scatter in the error's own measure (None: fewer than 2)."""
    d = [deviation(kind, v, ref, absolute) for v in seed_values]
    d = [x for x in d if x is not None]
    if len(d) < 2:
        return None
    if kind == SCALAR:
        return float(np.std(d, ddof=1))
    return float(math.sqrt(sum(x * x for x in d) / (len(d) - 1)))


def pareto_front(points):
    """Indices of the points (cost, error) that no other point beats on both, by cost."""
    front, best = [], math.inf
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def cheapest_within(points, target):
    """Index of the cheapest point with error <= target, or None."""
    inside = [i for i, (_, e) in enumerate(points) if e <= target]
    return min(inside, key=lambda i: points[i][0]) if inside else None


def predict_costs(particle_steps, core_seconds):
    """The rate model: core-s = particle-steps / rate, the rate being the median of the OTHER
    variants' particle-steps per core-second (leave one out, so no variant predicts itself).
    Returns (predicted core-s, relative prediction error) per variant, and the overall rate."""
    rates = [p / c for p, c in zip(particle_steps, core_seconds)]
    predicted, errors = [], []
    for i, p in enumerate(particle_steps):
        others = rates[:i] + rates[i + 1:]
        rate = float(np.median(others)) if others else rates[i]
        predicted.append(p / rate)
        errors.append(p / rate / core_seconds[i] - 1.0)
    return predicted, errors, float(np.median(rates))


def predict_costs_with_updates(particle_steps, updates, core_seconds):
    """The rate model plus a fixed cost per RVE update (the engine's run set-up, the deformation
    fix, reading the stress and the health measures): core-s = particle-steps / rate +
    updates x t_update, both fitted by least squares to the OTHER variants (leave one out).
    Where fewer than two others are left, their particle-steps are proportional to their
    updates, or the fit is not positive, the rate model stands in.
    Returns (predicted core-s, relative prediction error) per variant, and (rate, t_update)
    fitted to all variants (None when that fit is not positive)."""
    ps, up, t = (np.asarray(a, dtype=float) for a in (particle_steps, updates, core_seconds))
    fallback, _, _ = predict_costs(particle_steps, core_seconds)

    def fit(rows):
        design = np.vstack([ps[rows], up[rows]]).T
        # Particle-steps proportional to updates (same sub-steps and grains everywhere) cannot
        # tell the two costs apart.
        if len(rows) < 2 or np.linalg.matrix_rank(design) < 2:
            return None
        (a, b), *_ = np.linalg.lstsq(design, t[rows], rcond=None)
        return (a, b) if a > 0 and b >= 0 else None

    predicted, errors = [], []
    for i in range(len(t)):
        coef = fit([j for j in range(len(t)) if j != i])
        p = coef[0] * ps[i] + coef[1] * up[i] if coef else fallback[i]
        predicted.append(float(p))
        errors.append(float(p / t[i] - 1.0))
    overall = fit(list(range(len(t))))
    return predicted, errors, (1.0 / overall[0], overall[1]) if overall else None
