#!/usr/bin/python3
"""Bad recorded paths are refused before anything runs or is created.

usage: replay_bad_inputs.py MPM_LIG WORK_DIR

Each case below is an element test "recorded_path" on a 2D RVE whose path file has one
problem. `mpm_lig --validate` and a run must both exit 2 with a message naming the JSON path,
the file and the row (or step group) of the problem; the run's output folder must not exist
afterwards. The results.h5 files are written here in the layout of io::FieldWriter.
"""
import json
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

RVE = {"dimension": 2, "grains": 60, "radius": {"min": 0.003, "max": 0.007}, "density": 2650,
       "contact": {"youngs_modulus": 7e8, "poisson_ratio": 0.3, "friction_deg": 26.6,
                   "damping_ratio": 0.1},
       "time_step_fraction": 0.15, "preparation": {"confining_pressure": 1e5}}

GOOD = ["time,F11,F12,F21,F22", "0,1,0,0,1", "1,0.999,0,0,0.999", "2,0.998,0.001,0,0.998"]


def csv_with(*changes):
    """GOOD with line i replaced by text, for each (i, text)."""
    lines = list(GOOD)
    for i, text in changes:
        lines[i] = text
    return "\n".join(lines) + "\n"


def results_h5(file, points=4, steps=3, deformation=True, bad_step=None, stride=1):
    """A FieldWriter-like results.h5 of a dem_rve material with id 3, written every `stride`
    steps: F compressing y by 1e-3 per output step, step `bad_step` inverted."""
    with h5py.File(file, "w") as f:
        for k in range(0, stride * steps, stride):
            g = f.create_group(f"step_{k:06d}")
            g.attrs["step"] = np.int64(k)
            g.attrs["time"] = 1e-3 * k
            g["positions"] = np.zeros((points, 3))
            g["material"] = np.full(points, 3, dtype=np.int32)
            g["dem_substeps_m3"] = np.full(points, 20.0 if k else 0.0)
            F = np.tile(np.eye(3).reshape(9), (points, 1))
            F[:, 4] = 1 - 1e-3 * k
            if k == bad_step:
                F[:, 4] = -1.0
            if deformation:
                g["deformation_gradient"] = F


CSV_CASES = [
    # name, CSV text, regex of the message
    ("det_negative", csv_with((2, "1,-0.5,0,0,0.999")),
     r"analysis\.path\.csv: '.*det_negative\.csv' row 2 \(line 3\): det F = -0\.49.*, must be > 0"),
    ("nan", csv_with((3, "2,0.998,nan,0,0.998")),
     r"analysis\.path\.csv: '.*nan\.csv' row 3 \(line 4\): F12 is nan"),
    ("missing_column", "time,F11,F12,F21\n0,1,0,0\n1,1,0,0\n",
     r"analysis\.path\.csv: '.*missing_column\.csv' line 1: missing column F22"),
    ("missing_time", "F11,F12,F21,F22\n1,0,0,1\n1,0,0,1\n",
     r"analysis\.path\.csv: .* line 1: missing column time"),
    ("three_d_for_2d_rve",
     "time,F11,F12,F13,F21,F22,F23,F31,F32,F33\n0,1,0,0,0,1,0,0,0,1\n1,1,0,0.001,0,1,0,0,0,1\n",
     r"analysis\.path\.csv: '.*three_d_for_2d_rve\.csv' row 2 \(line 3\): a 2D RVE takes plane "
     r"deformation only"),
    ("time_not_increasing", csv_with((3, "1,0.998,0.001,0,0.998")),
     r"analysis\.path\.csv: '.*time_not_increasing\.csv' row 3 \(line 4\): time 1 is not after "
     r"the previous row's 1"),
    ("not_a_number", csv_with((2, "1,0.999,0,abc,0.999")),
     r"row 2 \(line 3\): F21 is 'abc', not a number"),
    ("short_row", csv_with((2, "1,0.999,0")),
     r"row 2 \(line 3\): 3 values for 5 columns"),
    ("unknown_column", "time,F11,F12,F21,F22,F99\n0,1,0,0,1,0\n",
     r"line 1: unknown column 'F99'"),
    ("one_row", "time,F11,F12,F21,F22\n0,1,0,0,1\n",
     r"holds 1 recorded state\(s\): a path needs at least two"),
    ("bad_substeps", "time,F11,F12,F21,F22,substeps\n0,1,0,0,1,0\n1,1,0,0,0.999,2.5\n",
     r"row 2 \(line 3\): substeps is 2\.5, must be a whole number >= 0"),
]

H5_CASES = [
    # name, results.h5 options, path node options, regex
    ("unknown_point", {}, {"point": 7},
     r"analysis\.path\.point: no point 7: '.*unknown_point\.h5' holds 4 points \(0 \.\.\. 3\)"),
    ("no_deformation", {"deformation": False}, {"point": 1},
     r"analysis\.path\.results: '.*no_deformation\.h5' step_000000 has no dataset "
     r"deformation_gradient .*output\.deformation_gradient true"),
    ("inverted_step", {"bad_step": 2}, {"point": 1},
     r"analysis\.path\.results: '.*inverted_step\.h5' step_000002: det F = -1, must be > 0"),
    ("recorded_substeps_gap", {"stride": 2}, {"point": 1, "substeps": "recorded"},
     r"analysis\.path\.substeps: '.*recorded_substeps_gap\.h5' step_000002: follows "
     r"step_000000: recorded sub-steps need every MPM step written"),
]

OTHER_CASES = [
    # name, analysis node, regex
    ("both_sources", {"test": "recorded_path", "path": {"csv": "ok.csv", "results": "ok.h5",
                                                         "point": 0}},
     r"analysis\.path: give exactly one of csv .* and results"),
    ("missing_file", {"test": "recorded_path", "path": {"csv": "absent.csv"}},
     r"analysis\.path\.csv: no such file '.*absent\.csv'"),
    ("strain_increment", {"test": "recorded_path", "path": {"csv": "ok.csv"},
                          "strain_increment": 1e-4},
     r"analysis\.strain_increment"),
    # a free volume needs the mean stress to hold: column p, finite and > 0
    ("free_without_p", {"test": "recorded_path", "path": {"csv": "ok.csv", "volume": "free"}},
     r"analysis\.path\.volume: free needs a CSV path \(csv\) with a column p"),
    ("free_results", {"test": "recorded_path", "path": {"results": "ok.h5", "point": 3,
                                                        "volume": "free"}},
     r"analysis\.path\.volume: free needs a CSV path"),
    ("free_p_zero", {"test": "recorded_path", "path": {"csv": "p_zero.csv", "volume": "free"}},
     r"analysis\.path\.volume: '.*p_zero\.csv' row 2 \(line 3\): p is 0, must be finite"),
    ("free_p_nan", {"test": "recorded_path", "path": {"csv": "p_nan.csv", "volume": "free"}},
     r"analysis\.path\.volume: '.*p_nan\.csv' row 3 \(line 4\): p is nan"),
    ("volume_unknown", {"test": "recorded_path", "path": {"csv": "ok.csv", "volume": "loose"}},
     r"analysis\.path\.volume"),
    ("free_tolerance", {"test": "recorded_path", "path": {"csv": "ok_p.csv", "volume": "free",
                                                          "pressure_tolerance": 0.5}},
     r"analysis\.path\.pressure_tolerance"),
]

GOOD_P = ["time,F11,F12,F21,F22,p", "0,1,0,0,1,1e5", "1,0.999,0,0,0.999,1.1e5",
          "2,0.998,0.001,0,0.998,1.2e5"]


def expect_refusal(mpm_lig, case_file, out, regex, failures):
    name = os.path.basename(case_file)
    for command in ([mpm_lig, "--validate", case_file], [mpm_lig, case_file, "--output", out]):
        p = subprocess.run(command, capture_output=True, text=True)
        said = p.stdout + p.stderr
        if p.returncode != 2 or not re.search(regex, said):
            failures.append(f"{name} ({command[1]}): exit {p.returncode}, said {said.strip()!r}"
                            f", expected exit 2 and /{regex}/")
    if os.path.exists(out):
        failures.append(f"{name}: {out} was created")


def main():
    mpm_lig, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, "ok.csv"), "w") as f:
        f.write(csv_with())
    for name, row, text in (("ok_p", 1, GOOD_P[1]), ("p_zero", 2, "1,0.999,0,0,0.999,0"),
                            ("p_nan", 3, "2,0.998,0.001,0,0.998,nan")):
        lines = list(GOOD_P)
        lines[row] = text
        with open(os.path.join(work, name + ".csv"), "w") as f:
            f.write("\n".join(lines) + "\n")
    results_h5(os.path.join(work, "ok.h5"))
    cases = []
    for name, text, regex in CSV_CASES:
        with open(os.path.join(work, name + ".csv"), "w") as f:
            f.write(text)
        cases.append((name, {"test": "recorded_path", "path": {"csv": name + ".csv"}}, regex))
    for name, options, path, regex in H5_CASES:
        results_h5(os.path.join(work, name + ".h5"), **options)
        cases.append((name, {"test": "recorded_path", "path": dict(path, results=name + ".h5")},
                      regex))
    failures = []
    for name, analysis, regex in cases + OTHER_CASES:
        case_file = os.path.join(work, name + ".json")
        with open(case_file, "w") as f:
            json.dump({"rve": RVE, "analysis": dict(analysis, type="element_test")}, f)
        expect_refusal(mpm_lig, case_file, os.path.join(work, name + "_out"), regex, failures)
    # The good files themselves pass (so that every refusal above is the file's problem).
    for name, path in (("ok_csv", {"csv": "ok.csv"}), ("ok_h5", {"results": "ok.h5", "point": 3}),
                       ("ok_free", {"csv": "ok_p.csv", "volume": "free"}),
                       ("ok_recorded", {"results": "ok.h5", "point": 3, "substeps": "recorded"})):
        case_file = os.path.join(work, name + ".json")
        with open(case_file, "w") as f:
            json.dump({"rve": RVE, "analysis": {"type": "element_test", "test": "recorded_path",
                                                "path": path}}, f)
        p = subprocess.run([mpm_lig, "--validate", case_file], capture_output=True, text=True)
        if p.returncode != 0:
            failures.append(f"{name}: a good path refused: {(p.stdout + p.stderr).strip()}")
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print(f"{len(cases) + len(OTHER_CASES)} bad paths refused (exit 2, nothing created)")


main()
