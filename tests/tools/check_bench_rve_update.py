"""bench_rve_update on a 50-grain packing: the --steps tables (same DEM steps for every sub-step
count: S/n updates), one per setup_every, as printed and as JSON; bad input exits 2 with a message
and no table. Timings are not checked (a benchmark's numbers are measured, not asserted).

usage: check_bench_rve_update.py BENCH CASE.json WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def expect(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def run(bench, *args):
    r = subprocess.run([bench, *args], capture_output=True, text=True, timeout=120)
    sys.stdout.write(r.stdout)
    sys.stderr.write(r.stderr)
    return r


def main(bench, case, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "bench.json")
    r = run(bench, case, "--grains", "50", "--steps", "20", "--substeps", "1,2,4", "--repeats", "1",
            "--setup-every", "1,4", "--varying", "--cpu-time", "--json", out)
    expect(r.returncode == 0, f"exit code {r.returncode}")
    expect(r.stdout.count("20 DEM steps on one path") == 2, "one printed table per setup_every")
    tables = json.load(open(out))["tables"]
    expect([t["setup_every"] for t in tables] == [1, 4], f"setup_every {tables}")
    for t in tables:
        expect(t["steps"] == 20 and t["updates"] is None and t["varying"], f"header {t}")
        expect([row["substeps"] for row in t["rows"]] == [1, 2, 4], f"rows {t['rows']}")
        for row in t["rows"]:
            expect(row["deform_seconds"] > 0 and row["update_seconds"] > 0, f"times {row}")
    bad = [([case, "--steps", "30", "--substeps", "1,20"], "divide --steps"),
           ([case, "--steps", "-4"], "--steps must be > 0"),
           ([case, "--grains", "40"], "rve.grains"),
           ([os.path.join(work, "missing.json")], "cannot read the case file")]
    for args, message in bad:
        r = run(bench, *args)
        expect(r.returncode == 2 and message in r.stderr, f"{args}: exit {r.returncode}")
    print("bench_rve_update: ok")


if __name__ == "__main__":
    main(*sys.argv[1:4])
