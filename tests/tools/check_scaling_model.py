#!/usr/bin/python3
"""tools/scaling_model.py on synthetic cost records whose makespans are known by hand.

Record A: 8 points of constant cost 8, 7, ..., 1 DEM steps (grains 1, no fixed cost), 10 steps.
  2 ranks: round-robin loads 20 | 16 -> efficiency 36 / 40; LPT (8, 5, 4, 1 | 7, 6, 3, 2)
  18 | 18 -> 1; the balancer moves the 2 (closest to half the difference 4) -> 1, with
  --persistence 1 (the costs are constant). With --persistence 0 the costs above the floor
  (the fewest steps, 1) count for the coming update only: moving the 2 gains 20 - 18 once and
  loses 5 - 4 on the floor's nine updates after it (3 points against 5): no move, 36 / 40.
  8 ranks: one point each, makespan 8 -> 36 / 64 for all; 16 ranks -> 36 / 128.
Record B: the textbook LPT case, points 3, 5, 3, 4, 3 on 2 ranks: LPT 10 (optimum 9), bound 9.
Also: a fixed cost per update is counted, the wall time is makespan / rate + gather, bad
input ends with exit 2 and one line naming the file or option (more in
check_tool_robustness.py)."""
import json
import os
import subprocess
import sys
import tempfile

from synthetic import write_cost_record as write_record

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "scaling_model.py")


def run(args):
    p = subprocess.run([sys.executable, TOOL] + args, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)


def close(a, b):
    return abs(a - b) <= 1e-12 * max(1.0, abs(b))


with tempfile.TemporaryDirectory() as tmp:
    a = os.path.join(tmp, "a.h5")
    write_record(a, [8, 7, 6, 5, 4, 3, 2, 1], 10)
    out = os.path.join(tmp, "a.json")
    code, text, err = run([a, "--ranks", "2,8,16", "--move-cost", "0", "--threshold", "0",
                           "--persistence", "1", "--rate", "100", "--json", out,
                           "--plot", os.path.join(tmp, "a.png")])
    expect(code == 0, "record A: exit %d: %s" % (code, err))
    if code == 0:
        rows = {row["ranks"]: row for row in json.load(open(out))["rows"]}
        e2 = rows[2]["efficiency"]
        expect(close(e2["round_robin"], 36 / 40), "A, 2 ranks round-robin %s" % e2)
        expect(close(e2["lpt"], 1.0), "A, 2 ranks LPT %s" % e2)
        expect(close(e2["balancer"], 1.0), "A, 2 ranks balancer %s" % e2)
        expect(rows[2]["migrations"] == 1, "A, 2 ranks: %s moves, not 1" % rows[2]["migrations"])
        for k in ("round_robin", "balancer", "lpt", "bound"):
            expect(close(rows[8]["efficiency"][k], 36 / 64), "A, 8 ranks %s" % rows[8])
            expect(close(rows[16]["efficiency"][k], 36 / 128), "A, 16 ranks %s" % rows[16])
        # Wall: round-robin makespan 20 per step x 10 steps / rate 100 + the gather.
        w = rows[2]["wall_seconds"]["round_robin"] - rows[2]["gather_seconds"]
        expect(close(w, 2.0), "A, 2 ranks round-robin wall %s, not 2 s + gather" % w)
        expect(rows[2]["gather_seconds"] > 0, "no gather time at 2 ranks")
        expect(os.path.getsize(os.path.join(tmp, "a.png")) > 1000, "no plot")
    code, text, err = run([a, "--ranks", "2", "--move-cost", "0", "--threshold", "0",
                           "--persistence", "0", "--rate", "100", "--json", out])
    expect(code == 0, "record A, persistence 0: exit %d: %s" % (code, err))
    if code == 0:
        row = json.load(open(out))["rows"][0]
        expect(row["migrations"] == 0, "A, persistence 0: %s moves, not 0" % row["migrations"])
        expect(close(row["efficiency"]["balancer"], 36 / 40), "A, persistence 0 %s" % row)
    # Record P (test_rve_balance.cpp, APeakThatPasses...): costs 10, 2, 2, 2 dealt to 2 ranks
    # (12 | 4), floor 2. Persistence 1: the 2 moves (10 | 6), 16 / 20; persistence 0.6: the
    # move would leave 1 point against 3 once the peak fades, none, 16 / 24.
    pk = os.path.join(tmp, "p.h5")
    write_record(pk, [10, 2, 2, 2], 5, floor_steps=2.0)
    for rho, moves, eff in (("1", 1, 16 / 20), ("0.6", 0, 16 / 24)):
        code, text, err = run([pk, "--ranks", "2", "--move-cost", "0", "--threshold", "0",
                               "--persistence", rho, "--rate", "1", "--json", out])
        expect(code == 0, "record P, persistence %s: exit %d: %s" % (rho, code, err))
        if code == 0:
            row = json.load(open(out))["rows"][0]
            expect(row["migrations"] == moves, "P, persistence %s: %s moves" % (rho, row))
            expect(close(row["efficiency"]["balancer"], eff), "P, persistence %s %s" % (rho, row))
    code, text, err = run([pk, "--persistence", "0.97"])
    expect(code == 2 and "--persistence" in err, "persistence 0.97 accepted: %s" % err)
    b = os.path.join(tmp, "b.h5")
    write_record(b, [3, 5, 3, 4, 3], 4)
    out = os.path.join(tmp, "b.json")
    code, text, err = run([b, "--ranks", "2", "--rate", "1", "--json", out])
    expect(code == 0, "record B: exit %d: %s" % (code, err))
    if code == 0:
        e = json.load(open(out))["rows"][0]["efficiency"]
        expect(close(e["lpt"], 18 / 20), "B: LPT efficiency %s, not 18 / 20" % e["lpt"])
        expect(close(e["bound"], 18 / 18), "B: bound %s, not 1 (9 = mean)" % e["bound"])
        # Round-robin: 3 + 3 + 3 | 5 + 4 -> 9 | 9.
        expect(close(e["round_robin"], 1.0), "B: round-robin %s" % e["round_robin"])
    # A fixed cost of 2 steps per update on record A: work (36 + 16), round-robin 28 | 24.
    c = os.path.join(tmp, "c.h5")
    write_record(c, [8, 7, 6, 5, 4, 3, 2, 1], 3, update_cost=2.0, grains=10.0)
    out = os.path.join(tmp, "c.json")
    code, text, err = run([c, "--ranks", "2", "--json", out])
    expect(code == 0, "record C: exit %d: %s" % (code, err))
    if code == 0:
        res = json.load(open(out))
        e = res["rows"][0]["efficiency"]
        expect(close(e["round_robin"], 52 / 56), "C: round-robin %s, not 52 / 56" % e)
        # Rate from the record: 3 steps x 52 x 10 particle-steps in 3 x 8 x 1e-3 s.
        expect(abs(res["rate"] / (3 * 52 * 10 / (3 * 8 * 1e-3)) - 1) < 1e-6,
               "C: rate %s" % res["rate"])
    for bad in ([os.path.join(tmp, "missing.h5")], [a, "--ranks", "two"], [tmp]):
        code, text, err = run(bad)
        expect(code == 2 and "Traceback" not in err and "scaling_model.py: error:" in err,
               "bad input %s: exit %d, stderr %s" % (bad, code, err[-300:]))

if failures:
    sys.exit("\n".join(failures))
print("scaling model: all checks passed")
