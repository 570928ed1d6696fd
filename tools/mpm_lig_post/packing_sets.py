"""A setting's error read against the packings' own scatter: the same problem run on several
packing sets, the reference and each setting on every set (tools/compare_cost.py --sets)."""
import json
import math

import numpy as np

from .quantities import SCALAR
from .tradeoff import deviation

# Student's t at 95 % (two-sided) by degrees of freedom; beyond the table the value at 10,
# which errs on the side of calling fewer biases.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306,
       9: 2.262, 10: 2.228}


def scatter(kind, values, absolute):
    """The reference's spread between the sets in the error's own measure: the sample standard
    deviation, relative to the mean unless the quantity is absolute (None: fewer than two)."""
    values = [v for v in values if v is not None]
    if kind != SCALAR or len(values) < 2:
        return None
    spread = float(np.std(values, ddof=1))
    if absolute:
        return spread
    mean = float(np.mean(values))
    return spread / abs(mean) if mean != 0 else None


def verdict(errors, spread, target, absolute):
    """The errors of one setting on every set against the bound max(target, scatter):
    {"bound", "mean", "standard_error", "within", "bias"}: bias when the mean error is
    outside its 95 % confidence interval around zero (Student's t over the sets)."""
    known = [e for e in errors if e is not None]
    # An absolute quantity has no target of its own: without a scatter it has no bound.
    bound = max(spread or 0.0, target) if not absolute else spread
    out = {"bound": bound, "mean": None, "standard_error": None, "within": None, "bias": None}
    if len(known) < len(errors) or not known:
        return out
    out["mean"] = float(np.mean(known))
    if len(known) >= 2:
        out["standard_error"] = float(np.std(known, ddof=1) / math.sqrt(len(known)))
        t = T95[min(len(known) - 1, max(T95))]
        out["bias"] = bool(abs(out["mean"]) > t * out["standard_error"])
    if out["bound"] is not None:
        out["within"] = all(abs(e) <= out["bound"] for e in known)
    return out


def settings(rows, sets, measures, target):
    """The reference's rows (the first `sets`) and each setting's: per set its particle-steps
    ratio and signed errors against the reference on the same set; per quantity the verdict."""
    reference = rows[:sets]
    spreads = {q.name: scatter(q.kind, [r["values"][q.name] for r in reference], q.absolute)
               for q in measures}
    out = []
    for k in range(sets, len(rows), sets):
        group = rows[k:k + sets]
        per_set = []
        for r, ref in zip(group, reference):
            per_set.append({"run": r["run"], "reference": ref["run"],
                            "particle_steps_ratio": r["particle_steps"] / ref["particle_steps"],
                            "errors": {q.name: deviation(q.kind, r["values"][q.name],
                                                         ref["values"][q.name], q.absolute)
                                       for q in measures if q.kind == SCALAR}})
        work = sum(r["particle_steps"] for r in group) / sum(r["particle_steps"]
                                                             for r in reference)
        verdicts = {q.name: verdict([s["errors"][q.name] for s in per_set], spreads[q.name],
                                    target, q.absolute)
                    for q in measures if q.kind == SCALAR}
        out.append({"sets": per_set, "particle_steps_ratio": work, "verdicts": verdicts})
    return spreads, out


def report(rows, sets, measures, target, json_file):
    """Print the sets' table (the reference's values and scatter, each setting's signed errors
    and verdict) and write it as json."""
    spreads, results = settings(rows, sets, measures, target)
    scalars = [q for q in measures if q.kind == SCALAR]
    print(f"{'reference on set':40s} {'p-steps':>10s}" +
          "".join(f" {q.name[:20]:>20s}" for q in scalars))
    for r in rows[:sets]:
        print(f"{r['run'][-40:]:40s} {r['particle_steps']:10.3g}" +
              "".join(f" {fmt_value(r['values'][q.name]):>20s}" for q in scalars))
    print(f"{'scatter between the sets':51s}" +
          "".join(f" {q.error_text(spreads[q.name]):>20s}" for q in scalars))
    for result in results:
        print()
        print(f"{'setting on set':40s} {'ratio':>10s}" +
              "".join(f" {q.name[:20]:>20s}" for q in scalars))
        for s in result["sets"]:
            print(f"{s['run'][-40:]:40s} {s['particle_steps_ratio']:10.3f}" +
                  "".join(f" {q.error_text(s['errors'][q.name], signed=True):>20s}"
                          for q in scalars))
        print(f"{'all sets: work ratio, mean error':40s} {result['particle_steps_ratio']:10.3f}" +
              "".join(f" {q.error_text(result['verdicts'][q.name]['mean'], signed=True):>20s}"
                      for q in scalars))
        print(f"{'verdict (bound)':40s} {'':10s}" +
              "".join(f" {verdict_text(q, result['verdicts'][q.name]):>20s}" for q in scalars))
    if json_file:
        with open(json_file, "w") as f:
            json.dump({"sets": sets, "target": target,
                       "reference": [{"run": r["run"], "particle_steps": r["particle_steps"],
                                      "values": {q.name: r["values"][q.name] for q in scalars}}
                                     for r in rows[:sets]],
                       "scatter": spreads, "settings": results}, f, indent=1)


def fmt_value(v):
    return "-" if v is None else f"{v:.4g}"


def verdict_text(q, v):
    if v["within"] is None:
        return "-"
    text = ("within" if v["within"] else "outside") + f" ({q.error_text(v['bound'])})"
    return text + (", bias" if v["bias"] else "")
