"""A Mohr-Coulomb continuum calibrated from a packing's own element tests, for the parts of an
MPM case where grains need not be simulated (a `dem_rve` region beside a continuum region).

usage: calibrate_continuum.py RUN_DIR RUN_DIR [...] [--id N] [--reference-pressure PA]
                              [--small-strain 1e-3] [--grain-density 2650]
                              [--residual LO HI] [--json OUT.json]

Each RUN_DIR holds history.csv and summary.json of one drained biaxial (2D) or triaxial (3D)
element test of the same packing, at two or more confining pressures. From them:
  - phi', c': a straight line through the peak states in the plane s = (s1 + s3)/2,
    t = (s1 - s3)/2 (t = s sin phi' + c' cos phi'; a negative intercept is reported and c' set
    to 0, the material being cohesionless);
  - psi: the largest dilatancy angle of the reference run, sin psi = -de_v / (2 de_1 - de_v)
    (at most phi');
  - E, nu: secant over the first SMALL_STRAIN of axial strain of the reference run (the run whose
    confining pressure is closest to PA; default the middle one): plane strain in 2D,
    nu/(1 - nu) = -de_3/de_1 and E = (1 - nu^2) ds1/de_1; axisymmetric in 3D, nu = -de_3/de_1,
    E = ds1/de_1;
  - density: grain density / (1 + e0), e0 the reference run's prepared void ratio;
  - with --residual LO HI, the softening (mohr_coulomb's "softening"): phi_r the runs' mean
    mobilised angle over axial strain LO ... HI, and kappa_r the mean over runs of the
    deviatoric strain sqrt(2/3 de:de) (de the strain's deviator) travelled from each run's
    peak to its first state at or below its own residual angle (psi_r = 0: critical state).
Prints a table per run and the material block, ready for the case's "materials" list; --json
writes both. A soil's stiffness grows with pressure: calibrate at the pressure of the region.
"""
from mpm_lig_post.requirements import require

require("numpy")

import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.quantities import (NotReached, Run, max_dilatancy, mobilised,  # noqa: E402
                                     peak_ratio_row, principal_series)
from mpm_lig_post.tables import need, read_json  # noqa: E402


def read_run(directory):
    if not os.path.isdir(directory):
        raise InputError(f"{directory}: no such output directory")
    where = os.path.join(directory, "summary.json")
    summary = read_json(where)
    for key in ("dimension", "confining_pressure", "preparation"):
        if key not in summary:
            raise InputError(f"{where}: missing key '{key}' (a drained biaxial "
                             "or triaxial element test is needed)")
    need(summary, "confining_pressure", where, number=True)
    need(summary["preparation"], "void_ratio", where + ": preparation", number=True)
    if summary["dimension"] not in (2, 3):
        raise InputError(f"{where}: dimension: expected 2 or 3, got {summary['dimension']!r}")
    run = Run(directory, {"rve": {"dimension": summary["dimension"]}})
    s1, s3, e1, ev = principal_series(run.history, summary["dimension"])
    return run, summary, s1, s3, e1, ev


def peak_point(s1, s3):
    """(s, t) = ((s1 + s3) / 2, (s1 - s3) / 2) at the peak stress ratio."""
    k = peak_ratio_row(s1, s3)
    if k is None:
        raise InputError("no loaded state in the run")
    return 0.5 * (s1[k] + s3[k]), 0.5 * (s1[k] - s3[k])


def elastic_secant(summary, s1, e1, ev, small_strain):
    """E, nu from the first `small_strain` of axial strain (secant from the start)."""
    reached = np.nonzero(e1 >= small_strain)[0]
    if len(reached) == 0 or reached[0] < 1:
        raise InputError(f"the run does not reach an axial strain of {small_strain:g} after its "
                         "first increment")
    k = reached[0]
    d1, de1 = s1[k] - s1[0], e1[k] - e1[0]
    lateral = (ev[k] - ev[0]) - de1
    if summary["dimension"] == 3:
        lateral /= 2.0
        nu = -lateral / de1
        return d1 / de1, nu
    ratio = -lateral / de1  # nu / (1 - nu) in plane strain
    nu = ratio / (1.0 + ratio)
    return (1.0 - nu * nu) * d1 / de1, nu


def deviatoric_travel(e1, ev, dimension, start, end):
    """sqrt(2/3 de:de) of the strain change between rows start and end (principal axes fixed:
    axial e1, the lateral strain from e_v; plane strain has no out-of-plane strain)."""
    de1 = e1[end] - e1[start]
    dlat = (ev[end] - ev[start]) - de1
    strain = [de1, dlat, 0.0] if dimension == 2 else [de1, 0.5 * dlat, 0.5 * dlat]
    dev = np.array(strain) - sum(strain) / 3.0
    return math.sqrt(2.0 / 3.0 * float(dev @ dev))


def softening(runs, lo, hi):
    """(phi_r [deg], kappa_r, per-run rows) of the runs' softening from peak to residual."""
    rows = []
    for (run, summary, *_) in runs:
        phi, e1, ev = mobilised(run)
        inside = (e1 >= lo) & (e1 <= hi)
        if not inside.any():
            raise InputError(f"{run.directory}: the run ends at {100 * e1.max():.3g} % axial "
                             f"strain, before the residual window {100 * lo:g}-{100 * hi:g} %")
        residual = float(np.mean(phi[inside]))
        peak = int(np.argmax(phi))
        reached = np.nonzero((np.arange(len(phi)) > peak) & (phi <= residual))[0]
        if len(reached) == 0:
            raise InputError(f"{run.directory}: the mobilised angle never falls to its residual "
                             f"{residual:.2f} deg after the peak")
        kappa = deviatoric_travel(e1, ev, summary["dimension"], peak, int(reached[0]))
        rows.append({"run": run.directory, "peak_deg": float(phi[peak]),
                     "residual_deg": residual, "peak_axial_strain": float(e1[peak]),
                     "residual_reached_at_axial_strain": float(e1[reached[0]]),
                     "softening_strain": kappa})
    return (float(np.mean([r["residual_deg"] for r in rows])),
            float(np.mean([r["softening_strain"] for r in rows])), rows)


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("runs", nargs="+")
    p.add_argument("--id", type=cli.non_negative_int, default=2,
                   help="material id of the block (default 2)")
    p.add_argument("--reference-pressure", type=cli.positive,
                   help="Pa: the run for E, nu, psi and density (default the middle pressure)")
    p.add_argument("--small-strain", type=cli.positive, default=1e-3)
    p.add_argument("--grain-density", type=cli.positive, default=2650.0)
    p.add_argument("--residual", type=cli.non_negative, nargs=2, metavar=("LO", "HI"),
                   help="axial strain window of the residual angle: adds the softening")
    p.add_argument("--json")
    a = p.parse_args()
    if a.residual is not None and not a.residual[0] < a.residual[1] < 1.0:
        raise InputError(f"--residual {a.residual[0]:g} {a.residual[1]:g}: LO < HI < 1 needed")
    cli.writable_file(a.json, "--json file")
    if a.small_strain >= 1.0:
        raise InputError(f"--small-strain {a.small_strain:g}: an axial strain below 1 is needed")
    if len(a.runs) < 2:
        raise InputError("give element tests at two or more confining pressures")
    runs = [read_run(d) for d in a.runs]
    pressures = [r[1]["confining_pressure"] for r in runs]
    if (max(pressures) - min(pressures)) < 0.2 * np.mean(pressures):
        raise InputError("the confining pressures differ by less than 20 %: no strength fit")
    order = np.argsort(pressures)
    if a.reference_pressure is None:
        ref = int(order[len(order) // 2])
    else:
        ref = int(np.argmin([abs(x - a.reference_pressure) for x in pressures]))
    rows = []
    for (run, summary, s1, s3, e1, ev) in runs:
        s, t = peak_point(s1, s3)
        young, poisson = elastic_secant(summary, s1, e1, ev, a.small_strain)
        rows.append({"run": run.directory, "confining_pressure": summary["confining_pressure"],
                     "peak_s": s, "peak_t": t, "youngs_modulus": young, "poisson_ratio": poisson,
                     "mobilised_friction_deg": math.degrees(math.asin(t / s))})
    slope, intercept = np.polyfit([r["peak_s"] for r in rows], [r["peak_t"] for r in rows], 1)
    if not 0.0 < slope < 1.0:
        raise InputError(f"the peak states give sin phi' = {slope:.3g}: no Mohr-Coulomb fit "
                         "(runs at clearly different pressures of one packing are needed)")
    phi = math.asin(slope)
    cohesion = intercept / math.cos(phi)
    run, summary, *_ = runs[ref]
    try:
        measured_psi = max_dilatancy()(run)
    except NotReached:
        measured_psi = None
    psi = 0.0 if measured_psi is None else min(max(measured_psi, 0.0), math.degrees(phi))
    notes = []
    if measured_psi is None or psi != measured_psi:
        notes.append("psi " + ("not measurable (the run is too short)" if measured_psi is None
                               else f"{measured_psi:.2f} deg kept within 0 ... phi'"))
    void_ratio = summary["preparation"]["void_ratio"]
    material = {"id": a.id, "type": "mohr_coulomb",
                "density": round(a.grain_density / (1.0 + void_ratio), 1),
                "youngs_modulus": float(f"{rows[ref]['youngs_modulus']:.4g}"),
                "poisson_ratio": round(min(max(rows[ref]["poisson_ratio"], 0.0), 0.49), 3),
                "cohesion": round(max(cohesion, 0.0), 1),
                "friction_deg": round(math.degrees(phi), 2),
                "dilatancy_deg": round(psi, 2),
                "_calibrated_from": ", ".join(r["run"] for r in rows)}
    soft_rows = []
    if a.residual is not None:
        phi_r, kappa_r, soft_rows = softening(runs, *a.residual)
        material["softening"] = {"residual_friction_deg": round(min(phi_r, math.degrees(phi)), 2),
                                 "residual_dilatancy_deg": 0.0,
                                 "plastic_strain": float(f"{kappa_r:.4g}")}
    print(f"{'run':40s} {'p0 [kPa]':>9s} {'phi_mob':>8s} {'E [MPa]':>9s} {'nu':>6s}")
    for i, r in enumerate(rows):
        print(f"{r['run'][-40:]:40s} {r['confining_pressure'] / 1e3:9.1f} "
              f"{r['mobilised_friction_deg']:8.2f} {r['youngs_modulus'] / 1e6:9.1f} "
              f"{r['poisson_ratio']:6.3f}{'  (reference)' if i == ref else ''}")
    print(f"Mohr-Coulomb fit of {len(rows)} peak states: phi' = {math.degrees(phi):.2f} deg, "
          f"c' = {cohesion / 1e3:.2f} kPa" + (" (negative: set to 0)" if cohesion < 0 else ""))
    if not 0.0 <= rows[ref]["poisson_ratio"] <= 0.49:
        notes.append(f"nu {rows[ref]['poisson_ratio']:.3f} kept within 0 ... 0.49")
    for r in soft_rows:
        print(f"{r['run'][-40:]:40s} peak {r['peak_deg']:.2f} deg at "
              f"{100 * r['peak_axial_strain']:.2f} %, residual {r['residual_deg']:.2f} deg first "
              f"at {100 * r['residual_reached_at_axial_strain']:.2f} %: deviatoric strain "
              f"{r['softening_strain']:.4f}")
    for n in notes:
        print("note: " + n)
    print(json.dumps(material))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"runs": rows, "material": material, "fitted_cohesion": cohesion,
                       "softening_runs": soft_rows}, f, indent=1)


def entry():
    """The command: tools/calibrate_continuum.py in a checkout, mpm-lig-calibrate-continuum installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
