"""The direct DEM's size effect (tools/direct_dem_compare.py --sizes): runs grouped by B/d with
the mean and standard deviation over their packings, and a least-squares fit of a load against
d/B (with the packings' void ratio as a second regressor where they differ), extrapolated to
d/B -> 0, the size at which a first-order multiscale answer, which has no length, applies."""
import math

import numpy as np


def groups(rows, key):
    """[(B/d, [values of `key` of the runs at that size])], sizes ascending; runs without the
    value (a window not reached) left out."""
    found = {}
    for r in rows:
        if r.get(key) is not None:
            found.setdefault(round(r["B_over_d"]), []).append(r[key])
    return sorted(found.items())


def summary(rows, key):
    """One row per size: n, mean, sample standard deviation (None for one packing)."""
    out = []
    for size, values in groups(rows, key):
        v = np.asarray(values, float)
        out.append({"B_over_d": size, "n": len(v), "mean": float(v.mean()),
                    "std": float(v.std(ddof=1)) if len(v) > 1 else None})
    return out


def fit(rows, key, e0=None):
    """Least squares of the runs' `key` against d/B (and e - e0 when the runs' void ratios are
    given and differ): {'at_infinity', 'its_se', 'slope', 'slope_se', 'void_ratio_slope',
    'residual_std', 'runs'}; None with fewer runs than parameters + 1."""
    used = [r for r in rows if r.get(key) is not None]
    y = np.array([r[key] for r in used], float)
    columns = [np.ones(len(used)), np.array([1.0 / r["B_over_d"] for r in used])]
    with_e = e0 is not None and all(r.get("void_ratio") is not None for r in used) and \
        len({round(r["void_ratio"], 4) for r in used}) > 1
    if with_e:
        columns.append(np.array([r["void_ratio"] - e0 for r in used]))
    A = np.column_stack(columns)
    if len(used) <= A.shape[1]:
        return None
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    residual = y - A @ coef
    dof = len(used) - A.shape[1]
    s2 = float(residual @ residual) / dof
    cov = s2 * np.linalg.inv(A.T @ A)
    result = {"at_infinity": float(coef[0]), "its_se": math.sqrt(cov[0, 0]),
              "slope": float(coef[1]), "slope_se": math.sqrt(cov[1, 1]),
              "residual_std": math.sqrt(s2), "runs": len(used), "dof": dof}
    if with_e:
        result.update(void_ratio_slope=float(coef[2]), void_ratio_slope_se=math.sqrt(cov[2, 2]))
    return result


def table(rows, keys, e0=None):
    """Markdown lines: per size the mean +- std of each key, then each key's fit."""
    lines = ["| B/d | packings | " + " | ".join(keys) + " |",
             "|---|---|" + "---|" * len(keys)]
    per_key = {k: {s["B_over_d"]: s for s in summary(rows, k)} for k in keys}
    sizes = sorted({s for k in keys for s in per_key[k]})
    for size in sizes:
        cells = []
        n = 0
        for k in keys:
            s = per_key[k].get(size)
            n = max(n, s["n"] if s else 0)
            cells.append("-" if s is None else f"{s['mean']:.2f}" +
                         (f" ± {s['std']:.2f}" if s["std"] is not None else ""))
        lines.append(f"| {size} | {n} | " + " | ".join(cells) + " |")
    for k in keys:
        f = fit(rows, k, e0)
        if f is None:
            lines.append(f"\n{k}: too few runs for a fit")
            continue
        text = (f"\n{k} = {f['at_infinity']:.2f} ± {f['its_se']:.2f} + ({f['slope']:.1f} ± "
                f"{f['slope_se']:.1f}) d/B")
        if "void_ratio_slope" in f:
            text += f" + ({f['void_ratio_slope']:.0f} ± {f['void_ratio_slope_se']:.0f}) (e - {e0})"
        lines.append(text + f"; {f['runs']} runs, residual {f['residual_std']:.2f}: as B/d -> "
                     f"infinity {f['at_infinity']:.2f} ± {f['its_se']:.2f}")
    return lines


def plot(ax, rows, key, multiscale, label):
    """The runs' `key` against B/d, the means with their standard deviations, the fit against
    d/B, and the multiscale values as horizontal lines."""
    sizes = np.array([r["B_over_d"] for r in rows if r.get(key) is not None])
    values = np.array([r[key] for r in rows if r.get(key) is not None])
    ax.plot(sizes, values, "o", ms=4, color="0.55", label="one packing")
    s = summary(rows, key)
    ax.errorbar([g["B_over_d"] for g in s], [g["mean"] for g in s],
                yerr=[g["std"] or 0 for g in s], fmt="s", color="C0", capsize=3,
                label="mean ± std over packings")
    f = fit(rows, key)
    if f:
        x = np.geomspace(max(10, sizes.min() / 2), 10 * sizes.max(), 50)
        ax.plot(x, f["at_infinity"] + f["slope"] / x, "-", color="C0", lw=0.8,
                label=f"fit: {f['at_infinity']:.1f} ± {f['its_se']:.1f} as B/d → ∞")
    for (name, value), colour in zip(multiscale.items(), ("k", "0.45")):
        ax.axhline(value, ls=":", color=colour, lw=1, label=f"multiscale {name}")
    ax.set_xscale("log")
    ax.set_xlabel("B/d")
    ax.set_ylabel(label)
