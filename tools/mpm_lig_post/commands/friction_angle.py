"""Macroscopic friction angle from drained biaxial/triaxial element tests.

usage: friction_angle.py RUN_DIR RUN_DIR [...] [--residual A B] [--volume-at E [E ...]]
                         [--json OUT.json]

Each RUN_DIR holds history.csv and summary.json of one mpm_lig element test. For every run the
peak state is the row of largest stress ratio (σ1 − σ3)/(σ1 + σ3) (principal stresses,
compression positive; in-plane for 2D runs). A straight line through the peak states in the
plane s = (σ1 + σ3)/2, t = (σ1 − σ3)/2 (Mohr–Coulomb: t = s sin φ' + c' cos φ') gives φ' and c'.
With runs at two or more confining pressures the fit separates friction from cohesion; the
per-run mobilised angles are printed too. --residual A B adds each run's residual angle: the
mean mobilised angle over the rows whose axial strain (the most compressive of e_xx, e_yy,
e_zz, positive in compression) lies in [A, B], and the mean over the runs (for a softening soil, e.g. 0.10 0.15).
--volume-at E ... adds each run's volumetric strain e_xx + e_yy + e_zz (dilation positive) at
those axial strains, interpolated between rows, and the mean over the runs.
"""
from mpm_lig_post.requirements import require

require("numpy")

import json  # noqa: E402
import math  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.quantities import peak_ratio_row, principal_stresses  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402

STRESS_COLUMNS = ("s_xx", "s_yy", "s_zz", "s_xy", "s_xz", "s_yz")


class ElementRun:
    """One element test's summary.json and history.csv, read once, with its principal
    stresses."""

    def __init__(self, run_dir):
        self.summary = read_json(f"{run_dir}/summary.json")
        if "dimension" not in self.summary:
            raise InputError(f"{run_dir}/summary.json: missing key 'dimension'")
        self.history_path = f"{run_dir}/history.csv"
        self.table = read_history(self.history_path)
        require_columns(self.table, STRESS_COLUMNS, self.history_path)
        self.s1, self.s3 = principal_stresses(self.table, self.summary["dimension"])

    def axial_strain(self):
        """Each row's axial strain: the most compressive of e_xx, e_yy, e_zz, compression
        positive."""
        require_columns(self.table, ("e_xx", "e_yy", "e_zz"), self.history_path)
        # Strains are tension positive; a dilating sample's lateral strain may exceed the axial
        # one.
        return -np.min([self.table["e_xx"], self.table["e_yy"], self.table["e_zz"]], axis=0)


def peak_state(run):
    """(stress ratio, σ1, σ3) at the row of largest stress ratio."""
    s1, s3 = run.s1, run.s3
    k = peak_ratio_row(s1, s3)
    if k is None:
        raise InputError(f"{run.history_path}: no loaded state")
    return (s1[k] - s3[k]) / (s1[k] + s3[k]), s1[k], s3[k]


def volume_at(run, strains):
    """Volumetric strain (dilation positive) at each axial strain of `strains`."""
    axial = run.axial_strain()
    volume = run.table["e_xx"] + run.table["e_yy"] + run.table["e_zz"]
    if max(strains) > axial.max() + 1e-9:  # the last row's strain, to its rounding
        raise InputError(f"{run.history_path}: --volume-at {max(strains):g} beyond the largest "
                         f"axial strain {axial.max():.4g}")
    if np.any(np.diff(axial) < 0):
        raise InputError(f"{run.history_path}: the axial strain does not grow monotonically")
    return [float(np.interp(e, axial, volume)) for e in strains]


def residual_angle(run, low, high):
    """Mean mobilised friction angle [deg] over the rows with axial strain in [low, high]."""
    axial = run.axial_strain()
    s1, s3 = run.s1, run.s3
    rows = (axial >= low) & (axial <= high) & (s1 + s3 > 0)
    if not rows.any():
        raise InputError(f"{run.history_path}: no row with axial strain in [{low:g}, {high:g}] "
                         f"(largest {axial.max():.4g})")
    ratio = (s1[rows] - s3[rows]) / (s1[rows] + s3[rows])
    return float(np.degrees(np.arcsin(np.clip(ratio, -1.0, 1.0))).mean())


def main():
    parser = cli.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--residual", nargs=2, type=cli.non_negative, metavar=("A", "B"),
                        help="also the mean mobilised angle over axial strains in [A, B]")
    parser.add_argument("--volume-at", nargs="+", type=cli.positive, metavar="E",
                        help="also the volumetric strain at these axial strains")
    parser.add_argument("--json", help="write the result here")
    args = parser.parse_args()
    cli.writable_file(args.json, "--json file")
    if args.residual and not args.residual[0] < args.residual[1] < 1.0:
        raise InputError(f"--residual {args.residual[0]:g} {args.residual[1]:g}: expected "
                         "0 <= A < B < 1 (axial strains)")
    s_points, t_points, rows = [], [], []
    for run_dir in args.runs:
        run = ElementRun(run_dir)
        ratio, s1, s3 = peak_state(run)
        s, t = 0.5 * (s1 + s3), 0.5 * (s1 - s3)
        s_points.append(s)
        t_points.append(t)
        rows.append({"run": run_dir, "test": run.summary.get("test"), "sigma1": s1, "sigma3": s3,
                     "mobilised_friction_deg": math.degrees(math.asin(ratio))})
        if args.residual:
            rows[-1]["residual_friction_deg"] = residual_angle(run, *args.residual)
        if args.volume_at:
            rows[-1]["volumetric_strain_at"] = dict(zip(map(str, args.volume_at),
                                                        volume_at(run, args.volume_at)))
    volume_heads = "".join(f" {'e_vol@' + format(e, 'g'):>10s}" for e in args.volume_at or [])
    extra = (f" {'phi_res [deg]':>13s}" if args.residual else "") + volume_heads
    print(f"{'run':40s} {'sigma3 [kPa]':>12s} {'sigma1 [kPa]':>12s} {'phi_mob [deg]':>13s}{extra}")
    for r in rows:
        extra = f" {r['residual_friction_deg']:13.2f}" if args.residual else ""
        extra += "".join(f" {v:10.4f}" for v in r.get("volumetric_strain_at", {}).values())
        print(f"{r['run']:40s} {r['sigma3']/1e3:12.1f} {r['sigma1']/1e3:12.1f} "
              f"{r['mobilised_friction_deg']:13.2f}{extra}")
    result = {"runs": rows}
    if args.residual:
        mean = sum(r["residual_friction_deg"] for r in rows) / len(rows)
        result["residual_friction_deg"] = mean
        print(f"residual angle over axial strain {args.residual[0]:g}-{args.residual[1]:g}, mean of "
              f"{len(rows)} runs: {mean:.2f} deg")
    if args.volume_at:
        result["volumetric_strain_at"] = {
            str(e): sum(r["volumetric_strain_at"][str(e)] for r in rows) / len(rows)
            for e in args.volume_at}
        print("volumetric strain, mean of " + f"{len(rows)} runs: " + ", ".join(
            f"{v:.4f} at {e}" for e, v in result["volumetric_strain_at"].items()))
    spread = (max(s_points) - min(s_points)) / (sum(s_points) / len(s_points))
    if len(rows) >= 2 and spread < 0.2:
        print("the runs' mean stresses at peak differ by less than 20 %: no fit (give runs at "
              "clearly different confining pressures)")
    elif len(rows) >= 2:
        slope, intercept = np.polyfit(s_points, t_points, 1)
        slope = min(max(slope, -1.0), 1.0)
        phi = math.asin(slope)
        cohesion = intercept / math.cos(phi)
        result.update({"friction_angle_deg": math.degrees(phi), "cohesion_pa": cohesion})
        print(f"Mohr-Coulomb fit of {len(rows)} peak states: phi' = {math.degrees(phi):.2f} deg, "
              f"c' = {cohesion/1e3:.2f} kPa")
    else:
        print("one run only: give runs at two or more confining pressures for a fit")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=2)


def entry():
    """The command: tools/friction_angle.py in a checkout, mpm-lig-friction-angle installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
