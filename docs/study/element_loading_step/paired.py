#!/usr/bin/python3
"""Paired differences of a loading-step study: each variant against the reference on the same
packing (seed), mean ± standard error over the seeds, for the scalar quantities.

    paired.py STUDY_FOLDER/accuracy_cost.json [...] [--json OUT]
"""
import argparse
import json
import math
import sys


def paired(report):
    variants = [v for v in report["variants"] if v.get("status") == "done"]
    reference = {v["seed"]: v for v in variants if v["reference"]}
    rows = []
    settings = {json.dumps(v["settings"], sort_keys=True) for v in variants if not v["reference"]}
    for setting in sorted(settings, key=lambda s: list(json.loads(s).values())):
        runs = [v for v in variants if json.dumps(v["settings"], sort_keys=True) == setting]
        row = {"settings": json.loads(setting), "packings": len(runs),
               "work_ratio": sum(v["particle_steps"] for v in runs)
               / sum(reference[v["seed"]]["particle_steps"] for v in runs)}
        for q in ("peak phi", "phi at 10-15 %", "max psi"):
            d = [v["values"][q] - reference[v["seed"]]["values"][q] for v in runs]
            mean = sum(d) / len(d)
            sd = math.sqrt(sum((x - mean) ** 2 for x in d) / (len(d) - 1))
            row[q] = {"mean": mean, "standard_error": sd / math.sqrt(len(d)),
                      "reference_mean": sum(reference[v["seed"]]["values"][q] for v in runs)
                      / len(runs)}
        rows.append(row)
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("reports", nargs="+")
    p.add_argument("--json")
    a = p.parse_args()
    out = {}
    for path in a.reports:
        try:
            with open(path) as f:
                report = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"paired.py: {path}: {e}")
        out[report["title"]] = paired(report)
        print(report["title"])
        print("| loading step | packings | work | peak φ′ (ref mean) | φ′ 10–15 % | ψ_max |")
        print("|---|---|---|---|---|---|")
        for r in out[report["title"]]:
            cells = [f"{r[q]['mean']:+.2f} ± {r[q]['standard_error']:.2f}° "
                     f"({r[q]['reference_mean']:.2f}°)" for q in ("peak phi", "phi at 10-15 %",
                                                               "max psi")]
            print(f"| {r['settings']} | {r['packings']} | {r['work_ratio']:.3f} | "
                  + " | ".join(cells) + " |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
