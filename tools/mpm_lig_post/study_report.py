"""Collect a study's finished variants (summary.json, history.csv) into errors and costs, and
write them: the printed table, accuracy_cost.json, .csv, .md (Markdown table) and .png."""
import csv
import json
import os
import textwrap

import numpy as np

from . import figures
from .errors import InputError
from .quantities import SCALAR, Run
from .tables import read_json, read_text
from .tradeoff import (cheapest_within, error, noise_floor, pareto_front, predict_costs,
                       predict_costs_with_updates,
                       reference_value)

COST_AXES = ("core-seconds", "cpu-seconds", "particle-steps")


def _cost(summary, ranks, cpu):
    """wall s, core-s (wall x ranks), CPU s (None: not measured), the stepping parts of both
    (without packing preparation and output), particle-steps, DEM updates (RVEs x steps)."""
    wall = float(summary["wall_seconds"])
    ranks = int(summary.get("ranks", ranks))
    split = summary.get("time_split", {})
    stepping = wall - split.get("preparation", 0.0) - split.get("output", 0.0)
    steps = summary.get("mpm_steps", summary.get("increments", 0))
    rves = summary.get("rve_count", 1)
    return {"wall_seconds": wall, "ranks": ranks, "core_seconds": wall * ranks,
            "stepping_core_seconds": stepping * ranks,
            "particle_steps": float(summary.get("dem_particle_steps", 0.0)),
            "rve_steps": float(rves * steps),
            "cpu_seconds": cpu,
            "stepping_cpu_seconds": None if cpu is None else cpu * stepping / wall}


def _measure(run, measures):
    """{quantity: value (None: not reached)}, {quantity: why not reached}."""
    values, why = {}, {}
    for q in measures:
        try:
            values[q.name], reason = q.evaluate(run)
        except InputError as e:
            raise InputError(f"{run.directory}: {q.name}: {e}") from None
        if reason:
            why[q.name] = reason
    return values, why


def target_text(q, t):
    return f"{t:g} {q.unit}".rstrip() if q.absolute else f"{100 * t:g} %"


def _read_number(path):
    try:
        with open(path) as f:
            return float(f.read())
    except (OSError, ValueError):
        return None


def _settings_groups(done, axis):
    """The finished variants grouped by their settings (the seeds of one setting together):
    name (members' names joined by '+'), label (without the seed), members, mean cost."""
    groups = {}
    for r in done:
        groups.setdefault(json.dumps(r["settings"], sort_keys=True), []).append(r)
    out = []
    for rows in groups.values():
        label = rows[0]["label"]
        if rows[0]["seed"] is not None:
            label = label.replace(f", seed={rows[0]['seed']}", "").replace(
                f"seed={rows[0]['seed']}", "")
        out.append({"name": "+".join(r["name"] for r in rows), "label": label,
                    "members": [r["name"] for r in rows], "reference": rows[0]["reference"],
                    axis: sum(r[axis] for r in rows) / len(rows), "errors": {}, "rows": rows})
    return out


def collect(study, variants, measures, output, ranks, axis="core_seconds"):
    """Per variant: status, settings, cost and quantity values; then errors against the
    reference's seed mean, noise floors, Pareto fronts and the cost model."""
    rows = []
    for v in variants:
        d = os.path.join(output, "variants", v.folder)
        row = {"name": v.name, "folder": v.folder, "label": v.label(study.knobs),
               "settings": v.settings,
               "seed": v.seed, "reference": v.reference, "status": "not run"}
        summary = read_json(os.path.join(d, "run", "summary.json"), required=False)
        code = read_text(os.path.join(d, "exit_code")).strip() if os.path.isfile(
            os.path.join(d, "exit_code")) else None
        if summary is not None and code == "0":
            row["status"] = "done"
            row.update(_cost(summary, ranks, _read_number(os.path.join(d, "cpu_seconds"))))
            case = read_json(os.path.join(d, "case.json"))
            row["values"], row["not_reached"] = _measure(Run(os.path.join(d, "run"), case),
                                                         measures)
        elif code is not None:
            row["status"] = f"failed (exit {code})"
        rows.append(row)
    done = [r for r in rows if r["status"] == "done"]
    refs = [r for r in done if r["reference"]]
    if not refs:
        raise InputError(f"{output}: the reference variant has not finished: no errors to measure")
    if any(r[axis] is None for r in done):
        raise InputError(f"{output}: cost '{axis}' not measured for every variant (runs made "
                         "before CPU time was recorded): choose another --cost")
    result = {"title": study.title, "base": study.base_path, "knobs": study.knobs,
              "cost_axis": axis,
              "reference": study.reference, "seeds": study.seeds, "variants": rows,
              "quantities": {}}
    settings = _settings_groups(done, axis)
    result["settings"] = settings
    for q in measures:
        seed_values = [r["values"][q.name] for r in refs]
        ref = reference_value(q.kind, seed_values)
        floor = noise_floor(q.kind, seed_values, ref, q.absolute)
        for r in done:
            r.setdefault("errors", {})[q.name] = error(q.kind, r["values"][q.name], ref,
                                                       q.absolute)
        # A setting run on several packings is one point: the error of its packings' mean
        # (the scatter between them is the noise floor's business, not the setting's).
        for g in settings:
            values = [r["values"][q.name] for r in g["rows"]]
            # A setting whose packings did not all reach the quantity (one never liquefied) has
            # no mean to compare: no error rather than the mean of the lucky ones.
            g["errors"][q.name] = (None if any(v is None for v in values)
                                   else error(q.kind, reference_value(q.kind, values), ref,
                                              q.absolute))
        points = [(g[axis], g["errors"][q.name]) for g in settings
                  if g["errors"][q.name] is not None]
        names = [g["name"] for g in settings if g["errors"][q.name] is not None]
        front = [names[i] for i in pareto_front(points)]
        recommended = {}
        for t in q.targets:
            i = cheapest_within(points, t)
            recommended[target_text(q, t)] = names[i] if i is not None else None
        info = result["quantities"][q.name] = {
            "kind": q.kind, "unit": q.unit, "error": "absolute" if q.absolute else "relative",
            "noise_floor": floor,
            "reference_value": ref if q.kind == SCALAR or ref is None else "mean of seeds",
            "pareto_front": front, "recommended": recommended}
        if ref is None:
            reasons = [r["not_reached"][q.name] for r in refs if q.name in r["not_reached"]]
            info["not_reached"] = reasons[0] if reasons else "no value"
        elif not q.absolute and q.kind == SCALAR and floor is not None and floor >= 0.5:
            unit = f" {q.unit}" if q.unit else ""
            info["note"] = (f"the reference's seeds scatter by {100 * floor:.3g} % of its value "
                            f"({ref:.3g}{unit}): near zero a relative error means nothing; "
                            "give the quantity \"error\": \"absolute\"")
        short = {r["name"]: r["not_reached"][q.name] for r in done if q.name in r["not_reached"]}
        if ref is not None and short:
            info["not_reached_by"] = short
    for g in settings:
        del g["rows"]
    timed = "stepping_cpu_seconds" if axis == "cpu_seconds" else "stepping_core_seconds"
    if len(done) >= 2 and all(r["particle_steps"] > 0 for r in done):
        predicted, errs, rate = predict_costs([r["particle_steps"] for r in done],
                                              [r[timed] for r in done])
        for r, p, e in zip(done, predicted, errs):
            r["predicted_stepping_core_seconds"], r["prediction_error"] = p, e
        worst = max(done, key=lambda r: abs(r["prediction_error"]))
        predicted2, errs2, fitted = predict_costs_with_updates(
            [r["particle_steps"] for r in done], [r["rve_steps"] for r in done],
            [r[timed] for r in done])
        for r, p, e in zip(done, predicted2, errs2):
            r["predicted_with_updates"], r["prediction_error_with_updates"] = p, e
        worst2 = max(done, key=lambda r: abs(r["prediction_error_with_updates"]))
        result["cost_model"] = {
            "rule": "stepping core-s = particle-steps / rate; rate = median particle-steps per "
                    "stepping core-second of the other variants (leave one out)",
            "timed_by": timed,
            "rate_particle_steps_per_core_second": rate,
            "worst_prediction_error": worst["prediction_error"], "worst_variant": worst["name"],
            "with_updates": {
                "rule": "stepping core-s = particle-steps / rate + RVE updates x t_update, "
                        "least squares on the other variants (leave one out)",
                "rate_particle_steps_per_core_second": fitted[0] if fitted else None,
                "seconds_per_update": fitted[1] if fitted else None,
                "worst_prediction_error": worst2["prediction_error_with_updates"],
                "worst_variant": worst2["name"]}}
    return result


def _fmt(x, spec=".4g"):
    return "-" if x is None else format(x, spec)


def _pct(x):
    return "-" if x is None else f"{100 * x:.3g} %"


def print_table(result, measures):
    names = [q.name for q in measures]
    head = f"{'variant':6s} {'settings':44s} " + " ".join(f"{n[:18]:>18s} {'err':>8s}"
                                                          for n in names)
    head += f" {'wall s':>8s} {'core-s':>8s} {'CPU s':>8s} {'p-steps':>9s} {'model':>7s}"
    print(head)
    for r in result["variants"]:
        line = f"{r['name']:6s} {r['label'][:44]:44s} "
        if r["status"] != "done":
            print(line + r["status"])
            continue
        for q in measures:
            v = r["values"][q.name]
            shown = _fmt(v) if isinstance(v, float) else ("curve" if v is not None else "-")
            line += f"{shown:>18s} "
            line += f"{q.error_text(r['errors'][q.name]):>8s} "
        cpu = "-" if r["cpu_seconds"] is None else f"{r['cpu_seconds']:.1f}"
        line += (f"{r['wall_seconds']:8.1f} {r['core_seconds']:8.1f} {cpu:>8s} "
                 f"{r['particle_steps']:9.3g} "
                 f"{_pct(r.get('prediction_error')):>7s}")
        print(line)
    for q in measures:
        info = result["quantities"][q.name]
        if "not_reached" in info:
            print(f"{q.name}: not reached by the reference: {info['not_reached']}")
            continue
        print(f"{q.name}: {info['error']} error, noise floor {q.error_text(info['noise_floor'])}, "
              f"Pareto front {' '.join(info['pareto_front'])}; cheapest within "
              + ", ".join(f"{t}: {v or 'none'}" for t, v in info["recommended"].items()))
        if "note" in info:
            print(f"{q.name}: note: {info['note']}")
        for name, why in info.get("not_reached_by", {}).items():
            print(f"{q.name}: not reached by {name}: {why}")
    if "cost_model" in result:
        m = result["cost_model"]
        print(f"cost model: {m['rate_particle_steps_per_core_second']:.4g} particle-steps per "
              f"core-s; worst prediction error {100 * m['worst_prediction_error']:+.1f} % "
              f"({m['worst_variant']})")
        w = m["with_updates"]
        fitted = ("" if w["seconds_per_update"] is None else
                  f"{w['rate_particle_steps_per_core_second']:.4g} particle-steps per core-s + "
                  f"{1e3 * w['seconds_per_update']:.3g} ms per RVE update; ")
        print(f"cost model with a fixed cost per update: {fitted}worst prediction error "
              f"{100 * w['worst_prediction_error']:+.1f} % ({w['worst_variant']})")


def _jsonable(x):
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_jsonable(v) for v in x]
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    return x


def write_csv(result, measures, path):
    cost = ["wall_seconds", "core_seconds", "stepping_core_seconds", "cpu_seconds",
            "stepping_cpu_seconds", "particle_steps",
            "predicted_stepping_core_seconds", "prediction_error", "rve_steps",
            "predicted_with_updates", "prediction_error_with_updates"]
    knobs = result["knobs"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["variant", "status", "reference", "seed", *knobs, *cost,
                    *[c for q in measures
                      for c in (q.name, f"{q.name} error" + (f" [{q.unit}]" if q.absolute
                                                               else ""))]])
        for r in result["variants"]:
            row = [r["name"], r["status"], int(r["reference"]), r["seed"] if r["seed"] is not None
                   else "", *[r["settings"][k] for k in knobs], *[r.get(c, "") for c in cost]]
            for q in measures:
                v = r.get("values", {}).get(q.name)
                e = r.get("errors", {}).get(q.name)
                row += [v if isinstance(v, float) else "", "" if e is None else e]
            w.writerow(row)


def _short_label(row, result):
    """The settings that differ from the reference's (and the seed): 'ref' for the reference."""
    from .study_spec import short_name
    parts = [f"{short_name(k)}={v:g}" if isinstance(v, float) else f"{short_name(k)}={v}"
             for k, v in row["settings"].items() if v != result["reference"][k]]
    if row["seed"] is not None:
        parts.append(f"seed {row['seed']}")
    return "\n".join(parts) if parts else "ref"


def draw(result, measures, path, dpi):
    done = [r for r in result["variants"] if r["status"] == "done"]
    n = len(measures)
    cols = min(n, 2)
    rows_ = (n + cols - 1) // cols
    fig, axes = figures.subplots(rows_, cols, figsize=(6.2 * cols, 4.6 * rows_), squeeze=False)
    for ax, q in zip(axes.flat, measures):
        info = result["quantities"][q.name]
        axis = result["cost_axis"]
        pts = [(r[axis], r["errors"][q.name], r) for r in done
               if r["errors"][q.name] is not None]
        if not pts:
            # Say why in the picture, not with an empty panel.
            why = info.get("not_reached", "no variant has a value")
            ax.text(0.5, 0.5, textwrap.fill(why, 40), ha="center",
                    va="center", transform=ax.transAxes, fontsize=9)
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(f"{q.name}: not reached" if "not_reached" in info else q.name)
            continue
        # Errors drawn in % (relative) or in the quantity's unit (absolute); 0 at floor_y.
        scale, unit = (1.0, q.unit) if q.absolute else (100.0, "%")
        floor_y = 1e-4 * scale if q.absolute else 1e-4
        ys = [max(e, floor_y) for _, e, _ in pts]
        for (c, _, r), y in zip(pts, ys):
            ax.plot(c, scale * y, "s" if r["reference"] else "o", color="C1" if r["reference"]
                    else "C0", ms=5)
            ax.annotate(_short_label(r, result), (c, scale * y), fontsize=6,
                        xytext=(3, 3), textcoords="offset points")
        groups = {g["name"]: g for g in result["settings"]}
        for g in groups.values():
            if len(g["members"]) > 1 and g["errors"][q.name] is not None:
                ax.plot(g[axis], scale * max(g["errors"][q.name], floor_y), "D", mfc="none",
                        color="C3", ms=7)
        front = [groups[name] for name in info["pareto_front"]]
        ax.step([g[axis] for g in front],
                [scale * max(g["errors"][q.name], floor_y) for g in front],
                where="post", color="C3", lw=1.2,
                label="Pareto front (a setting on several packings: their mean, ◇)")
        if info["noise_floor"]:
            ax.axhspan(scale * floor_y, scale * info["noise_floor"], color="0.85", zorder=0,
                       label=f"noise floor (seeds) {q.error_text(info['noise_floor'])}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel({"core_seconds": "cost [core-seconds: wall x ranks]",
                       "cpu_seconds": "cost [CPU core-seconds]",
                       "particle_steps": "cost [DEM particle-steps]"}[axis])
        ax.set_ylabel(f"error of {q.name} [{unit}] (0 drawn at {scale * floor_y:g})")
        ax.set_title(q.name)
        ax.legend(loc="best", frameon=False, fontsize=8)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle(f"accuracy against cost: {result['title']}")
    fig.tight_layout()
    figures.save(fig, path, dpi)


def write_markdown(result, measures, path):
    """The table as Markdown (for docs): settings, each quantity with its error, costs."""
    names = [q.name for q in measures]
    lines = ["| variant | settings | " + " | ".join(f"{n} (error)" for n in names)
             + " | particle-steps | core-s | CPU s | model error (rate / + updates) |",
             "|---" * (len(names) + 6) + "|"]
    for r in result["variants"]:
        if r["status"] != "done":
            lines.append(f"| {r['name']} | {r['label']} | " + " | ".join("" for _ in names)
                         + f" | {r['status']} | | | |")
            continue
        cells = []
        for q in measures:
            v, e = r["values"][q.name], r["errors"][q.name]
            shown = _fmt(v) if isinstance(v, float) else ("curve" if v is not None else "-")
            cells.append(f"{shown} ({q.error_text(e)})")
        cpu = "-" if r["cpu_seconds"] is None else f"{r['cpu_seconds']:.0f}"
        lines.append(f"| {r['name']}{' (ref)' if r['reference'] else ''} | {r['label']} | "
                     + " | ".join(cells)
                     + f" | {r['particle_steps']:.3g} | {r['core_seconds']:.0f} | {cpu} | "
                     + f"{_pct(r.get('prediction_error'))} / "
                     + f"{_pct(r.get('prediction_error_with_updates'))} |")
    if any(len(g["members"]) > 1 for g in result["settings"]):
        lines.append("")
        lines.append("| setting | packings | " + " | ".join(f"{n} error of the mean" for n in names)
                     + f" | mean {result['cost_axis'].replace('_', ' ')} |")
        lines.append("|---" * (len(names) + 3) + "|")
        axis = result["cost_axis"]
        for g in result["settings"]:
            lines.append(f"| {g['label'] or 'reference'} | {g['name']} | "
                         + " | ".join(q.error_text(g["errors"][q.name]) for q in measures)
                         + f" | {g[axis]:.4g} |")
    lines.append("")
    lines.append("| quantity | noise floor | Pareto front | cheapest within | error |")
    lines.append("|---|---|---|---|---|")
    for q in measures:
        info = result["quantities"][q.name]
        if "not_reached" in info:
            lines.append(f"| {q.name} | not reached: {info['not_reached']} | | | |")
            continue
        rec = " / ".join(f"{t}: {v or 'none'}" for t, v in info["recommended"].items())
        lines.append(f"| {q.name} | {q.error_text(info['noise_floor'])} | "
                     f"{' '.join(info['pareto_front'])} | {rec} | {info['error']} |")
        if "note" in info:
            lines.append(f"| {q.name} | note: {info['note']} | | | |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_report(study, result, measures, output, dpi):
    print_table(result, measures)
    with open(os.path.join(output, "accuracy_cost.json"), "w") as f:
        json.dump(_jsonable(result), f, indent=1)
    write_csv(result, measures, os.path.join(output, "accuracy_cost.csv"))
    write_markdown(result, measures, os.path.join(output, "accuracy_cost.md"))
    draw(result, measures, os.path.join(output, "accuracy_cost.png"), dpi)
    print(f"wrote {output}/accuracy_cost.json, accuracy_cost.csv, accuracy_cost.md")
