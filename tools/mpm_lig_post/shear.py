"""Cyclic simple shear series shared by plot_shear.py and accuracy_cost.py: the shear strain,
stress and mean stress of either history layout, cycle numbers and the per-cycle table."""
import numpy as np

from .tables import require_columns

MPM_COLUMNS = ("shear_strain", "shear_stress", "mean_stress")


def shear_series(table, path):
    """(gamma, tau, p, cycle or None) from either history layout."""
    if any(name in table for name in MPM_COLUMNS):
        require_columns(table, MPM_COLUMNS, path)
        p = table["mean_stress"]
        if np.median(p) < 0:
            print("note: mean_stress is negative (tension positive): plotting p = -mean_stress")
            p = -p
        return table["shear_strain"], table["shear_stress"], p, table.get("cycle")
    strain = "gamma_xy" if "gamma_xy" in table else "e_xy"
    require_columns(table, ("s_xy", strain, "p"), path)
    gamma = table["gamma_xy"] if strain == "gamma_xy" else 2.0 * table["e_xy"]
    return gamma, table["s_xy"], table["p"], None


def count_cycles(gamma):
    """Cycle number (1, 2, ...) of each row from the strain path length: one cycle is
    4 gamma_a (0 -> +a -> -a -> 0); the row that closes a cycle belongs to it."""
    amplitude = np.max(np.abs(gamma))
    if amplitude <= 0:
        return np.ones(len(gamma), dtype=int)
    travelled = np.concatenate(([0.0], np.cumsum(np.abs(np.diff(gamma)))))
    return np.maximum(1, np.ceil(travelled / (4 * amplitude) - 1e-6)).astype(int)


def cycle_table(gamma, tau, p, cycle):
    """Per cycle: (cycle, gamma_a, tau_max, G_sec, p_end, p_end/p0)."""
    rows = []
    for c in np.unique(cycle):
        idx = np.flatnonzero(cycle == c)
        if idx[0] > 0:  # the cycle starts where the previous one ended
            idx = np.concatenate(([idx[0] - 1], idx))
        g, t = gamma[idx], tau[idx]
        hi, lo = np.argmax(g), np.argmin(g)
        span = g[hi] - g[lo]
        modulus = (t[hi] - t[lo]) / span if span > 0 else np.nan
        rows.append((int(c), 0.5 * span, np.max(np.abs(t)), modulus, p[idx[-1]],
                     p[idx[-1]] / p[0] if p[0] != 0 else np.nan))
    return rows


def cycles_to_liquefaction(gamma, p, fraction=0.1):
    """Cycles of strain path (4 gamma_a each) travelled when p first falls below fraction x p0,
    or None when it never does."""
    below = np.flatnonzero(p < fraction * p[0])
    amplitude = np.max(np.abs(gamma))
    if not below.size or amplitude <= 0:
        return None
    travelled = np.concatenate(([0.0], np.cumsum(np.abs(np.diff(gamma)))))
    return float(travelled[below[0]] / (4 * amplitude))
