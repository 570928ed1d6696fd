"""Cost and error of runs against a reference run of the same problem (work avoidance: DEM
regions, sub-step rules, ...): DEM particle-steps and their ratio to the reference's, wall
seconds, and each quantity of the problem with its error against the reference's value.

usage: compare_cost.py REFERENCE_DIR RUN_DIR [...] [--case CASE.json] [--quantities PRESET]
                       [--sets K [--target E]] [--json OUT.json]

Every directory is an mpm_lig output folder (summary.json, history.csv). The quantities are
those of tools/accuracy_cost.py (preset element | cyclic | footing | footing_to_1 |
footing_deep, by default the one the case is about: footing = plateau mean of q/q_s over s/B in
[0.1, 0.4] and the peak up to s/B 0.4; footing_to_1 = the peak up to s/B 1.0 and the means over
0.1-0.4 and 0.4-1.0; footing_deep = the peak up to s/B 1.5 and the means over 0.1-0.4, 0.4-1.0
and 1.0-1.5; cyclic = cycle of liquefaction and G_sec per cycle). CASE.json (default: the reference's
case.json if it wrote one) tells the footing's width and surcharge. Errors are relative,
an angle's in degrees (as in tools/accuracy_cost.py).

With --sets K the same problem was run on K packing sets: the folders come K at a time, the
reference on sets 1..K first, then each setting on the same sets in the same order. Each
setting's signed error is taken against the reference on its own set, and read against the
reference's scatter between the sets (its sample standard deviation, relative to the mean):
"within" when every set's error is inside max(--target, scatter), and "bias" when the mean
error over the sets is outside its 95 % confidence interval around zero (Student's t: with two
sets only an error repeated almost exactly is called one)."""
from mpm_lig_post.requirements import require

require("numpy")

import json  # noqa: E402
import os  # noqa: E402

from mpm_lig_post import cli, packing_sets  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.quantities import Run, quantities  # noqa: E402
from mpm_lig_post.tables import need, read_json  # noqa: E402
from mpm_lig_post.tradeoff import error  # noqa: E402


def measured(d, case, measures):
    """One run folder's particle-steps, wall seconds and quantities (InputError naming it)."""
    if not os.path.isdir(d):
        raise InputError(f"{d}: no such output directory")
    summary = read_json(os.path.join(d, "summary.json"))
    if not summary.get("dem_particle_steps"):
        raise InputError(f"{d}/summary.json: no DEM particle-steps (dem_particle_steps "
                         "missing or 0: not a DEM run)")
    run = Run(d, case)
    values = {}
    for q in measures:
        try:
            values[q.name] = q.value(run)
        except InputError as e:
            raise InputError(f"{d}: {q.name}: {e}") from None
    where = os.path.join(d, "summary.json")
    return {"run": d, "particle_steps": need(summary, "dem_particle_steps", where, True),
            "wall_seconds": need(summary, "wall_seconds", where, True), "values": values}


def single_runs(rows, measures, json_file):
    """Each run against the one reference: the table and the json of single runs."""
    ref = rows[0]
    for r in rows:
        r["particle_steps_ratio"] = r["particle_steps"] / ref["particle_steps"]
        r["errors"] = {q.name: error(q.kind, r["values"][q.name], ref["values"][q.name],
                                     q.absolute) for q in measures}
    head = f"{'run':34s} {'p-steps':>10s} {'ratio':>7s} {'wall s':>8s}"
    for q in measures:
        head += f" {q.name[:20]:>20s} {'error':>8s}"
    print(head)
    for r in rows:
        line = (f"{r['run'][-34:]:34s} {r['particle_steps']:10.3g} "
                f"{r['particle_steps_ratio']:7.3f} {r['wall_seconds']:8.0f}")
        for q in measures:
            v, e = r["values"][q.name], r["errors"][q.name]
            shown = f"{v:.4g}" if isinstance(v, float) else ("-" if v is None else "series")
            line += f" {shown:>20s} {q.error_text(e):>8s}"
        print(line)
    if json_file:
        with open(json_file, "w") as f:
            json.dump(rows, f, indent=1, default=lambda x: None)  # series: not kept


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("reference")
    p.add_argument("runs", nargs="+")
    p.add_argument("--case")
    p.add_argument("--quantities")
    p.add_argument("--sets", type=int, default=1,
                   help="packing sets K: the folders come K at a time (the reference on sets "
                        "1..K, then each setting on the same sets in the same order)")
    p.add_argument("--target", type=float, default=0.03,
                   help="with --sets: the relative error accepted whatever the scatter "
                        "(default 0.03)")
    p.add_argument("--json")
    a = p.parse_args()
    cli.writable_file(a.json, "--json file")
    dirs = [a.reference] + a.runs
    if a.sets < 1 or len(dirs) % a.sets or len(dirs) == a.sets:
        raise InputError(f"--sets {a.sets}: {len(dirs)} folders are not a reference and at "
                         f"least one setting of {a.sets} packing set(s) each")
    if not 0 <= a.target < 1:
        raise InputError(f"--target {a.target}: expected a relative error in [0, 1)")
    case_file = a.case or os.path.join(a.reference, "case.json")
    if not os.path.isfile(case_file):
        raise InputError(f"{case_file}: no such case file (give --case)")
    case = read_json(case_file)
    measures = quantities(a.quantities, case, "--quantities")
    rows = [measured(d, case, measures) for d in dirs]
    if a.sets == 1:
        single_runs(rows, measures, a.json)
    else:
        packing_sets.report(rows, a.sets, measures, a.target, a.json)


def entry():
    """The command: tools/compare_cost.py in a checkout, mpm-lig-compare-cost installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
