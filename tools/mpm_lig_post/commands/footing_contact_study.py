"""The footing's two contacts (nodes, penalty) against the closed forms, at two time steps.

usage: footing_contact_study.py WORK [--mpm-lig PATH] [--json FILE] [--quick]

Runs cases/mpm/prandtl_tresca_penalty.json (rough, Tresca: q_u = (2 + pi) c_u) on meshes of
h = B/4, B/8, B/20 (the case's) and B/40, and cases/mpm/vesic_mohr_coulomb.json (rough,
phi 28.1 deg, psi 0: q_u = N_q q0, h = B/10), each with "contact": "nodes", "penalty" and
"penalty" pressing the whole footprint ("penalty_edge_inset": false), at CFL 0.5 and 0.25 (B/40 at 0.5 only), into WORK (runs already there are reused). Prints a
markdown table of q_u over its closed form, q_u the mean over d/B 0.015-0.03 as in the footing
tests; --json writes it with every fifth history row of each run (docs/footing_contact.md).
--quick: Prandtl on B/4 and B/8 only.
"""
from argparse import ArgumentParser
import csv
import json
import math
import os
import subprocess

from mpm_lig_post import checkout, cli
from mpm_lig_post.errors import InputError

WINDOW = (0.015, 0.03)  # d/B; B = 1 m in both cases


def prandtl(contact, cfl, cells_per_width):
    """Prandtl's case with this contact, step and mesh h = B / cells_per_width."""
    with open(checkout.path("cases", "mpm", "prandtl_tresca_penalty.json")) as f:
        case = json.load(f)
    if cells_per_width != 20:  # the case's own mesh is B/20 on 2.0 x 1.35 m
        n = cells_per_width
        case["mesh"]["size"] = [2.0, 1.5]
        case["mesh"]["cells"] = [2 * n, round(1.5 * n)]
    return set_up(case, contact, cfl), (2.0 + math.pi) * 1.0e4


def vesic(contact, cfl):
    with open(checkout.path("cases", "mpm", "vesic_mohr_coulomb.json")) as f:
        case = json.load(f)
    phi = math.radians(case["materials"][0]["friction_deg"])
    nq = math.tan(math.pi / 4 + phi / 2) ** 2 * math.exp(math.pi * math.tan(phi))
    return set_up(case, contact, cfl), nq * 1.0e4


# The contacts compared: the case keys of each.
CONTACTS = {"nodes": {"contact": "nodes"},
            "penalty": {"contact": "penalty"},
            "penalty, whole footprint": {"contact": "penalty", "penalty_edge_inset": False}}


def set_up(case, contact, cfl):
    case["rigid_bodies"][0].update(CONTACTS[contact])
    case["analysis"]["time_step"]["cfl"] = cfl
    case["analysis"]["end"]["time"] = 0.31  # d/B 0.031 at 0.1 m/s
    case["output"] = {"fields": False, "every": 1000}
    return case


def collapse(run_dir):
    """Mean q over WINDOW, and the history's (d/B, q) rows."""
    with open(os.path.join(run_dir, "history.csv")) as f:
        rows = [(float(r["settlement"]), float(r["q"])) for r in csv.DictReader(f)]
    inside = [q for s, q in rows if WINDOW[0] <= s <= WINDOW[1]]
    if len(inside) < 10:
        raise InputError(f"{run_dir}: fewer than 10 history rows in d/B {WINDOW}")
    return sum(inside) / len(inside), rows


def run(mpm_lig, work, name, case):
    folder = os.path.join(work, name)
    if not os.path.isfile(os.path.join(folder, "summary.json")):
        with open(folder + ".json", "w") as f:
            json.dump(case, f, indent=1)
        done = subprocess.run([mpm_lig, folder + ".json", "--output", folder],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            raise InputError(f"{name}: mpm_lig exit {done.returncode}: "
                             f"{done.stderr.strip()[-400:]}")
    return collapse(folder)


def plans(quick):
    """(problem, mesh, contact, cfl, case, exact) of every run."""
    out = []
    for n in (4, 8) if quick else (4, 8, 20, 40):
        for contact in CONTACTS:
            for cfl in (0.5, 0.25) if n <= 20 else (0.5,):
                out.append(("prandtl", f"B/{n}", contact, cfl, *prandtl(contact, cfl, n)))
    if not quick:
        for contact in CONTACTS:
            for cfl in (0.5, 0.25):
                out.append(("vesic", "B/10", contact, cfl, *vesic(contact, cfl)))
    return out


def table(results):
    lines = ["| problem | mesh | contact | CFL 0.5 | CFL 0.25 | 0.25 / 0.5 |",
             "|---|---|---|---|---|---|"]
    keys = []
    for r in results:
        if (r["problem"], r["mesh"], r["contact"]) not in keys:
            keys.append((r["problem"], r["mesh"], r["contact"]))
    for key in keys:
        by_cfl = {r["cfl"]: r["q_over_exact"] for r in results
                  if (r["problem"], r["mesh"], r["contact"]) == key}
        half, quarter = by_cfl[0.5], by_cfl.get(0.25)
        tail = f"{quarter:.4f} | {quarter / half:.4f}" if quarter else "- | -"
        lines.append(f"| {key[0]} | {key[1]} | {key[2]} | {half:.4f} | {tail} |")
    return "\n".join(lines)


def main():
    p = ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("work", metavar="WORK", help="folder for the runs (reused when run again)")
    p.add_argument("--mpm-lig", help="the executable (default: build/mpm_lig, else PATH)")
    p.add_argument("--json", help="write the table and the histories here")
    p.add_argument("--quick", action="store_true", help="Prandtl on B/4 and B/8 only")
    a = p.parse_args()
    mpm_lig = checkout.find_mpm_lig(a.mpm_lig)
    cli.writable_folder(a.work, "work folder")
    cli.writable_file(a.json, "--json file")
    os.makedirs(a.work, exist_ok=True)
    results = []
    for problem, mesh, contact, cfl, case, exact in plans(a.quick):
        label = contact.replace(", whole footprint", "_footprint")
        name = f"{problem}_{mesh.replace('/', '')}_{label}_cfl{cfl:g}"
        q, rows = run(mpm_lig, a.work, name, case)
        results.append({"problem": problem, "mesh": mesh, "contact": contact, "cfl": cfl,
                        "q_over_exact": q / exact,
                        "history_s_q": [(round(d, 6), round(q)) for d, q in rows[::5]]})
    print(table(results))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"window_d_over_B": WINDOW, "runs": results}, f, separators=(",", ":"))


def entry():
    """The command: tools/footing_contact_study.py in a checkout, mpm-lig-footing-contact-study
    installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
