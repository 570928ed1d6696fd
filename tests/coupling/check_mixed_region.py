"""A DEM region under a calibrated continuum region (tests/coupling/mixed_region.json): the
continuum points follow their Mohr-Coulomb material's elastic constrained modulus
M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) and lateral ratio nu / (1 - nu) (within 1e-5), and the
vertical stress carried across the interface is the same in both regions (within 10 %: the
column is in equilibrium, the two regions' stiffnesses differ).

usage: check_mixed_region.py CASE.json OUTPUT_DIR"""
import json
import sys

import h5py
import numpy as np


def main():
    case, out = json.load(open(sys.argv[1])), sys.argv[2]
    continuum = next(m for m in case["materials"] if m["type"] == "mohr_coulomb")
    young, nu = continuum["youngs_modulus"], continuum["poisson_ratio"]
    modulus = young * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    with h5py.File(out + "/results.h5") as f:
        steps = sorted(k for k in f if k.startswith("step_"))
        first, last = f[steps[0]], f[steps[-1]]
        material = last["material"][()]
        ds = last["stress"][()] - first["stress"][()]
        de = last["strain"][()] - first["strain"][()]
    ids = sorted(set(material.tolist()))
    cont = material == ids[[m["id"] for m in case["materials"]].index(continuum["id"])]
    failures = []
    if not np.all(np.isfinite(ds)):
        failures.append("non-finite stress")
    stiffness = ds[cont, 1] / de[cont, 1] / modulus
    lateral = ds[cont, 0] / ds[cont, 1] / (nu / (1 - nu))
    if np.abs(stiffness - 1).max() > 1e-5 or np.abs(lateral - 1).max() > 1e-5:
        failures.append(f"continuum points off their calibrated moduli: dsigma_yy/(M deps_yy) "
                        f"{stiffness}, lateral ratio / (nu/(1-nu)) {lateral}")
    dem_load, cont_load = ds[~cont, 1].mean(), ds[cont, 1].mean()
    if abs(dem_load / cont_load - 1) > 0.1:
        failures.append(f"vertical stress change {dem_load:.4g} Pa (DEM) vs {cont_load:.4g} Pa "
                        "(continuum): not carried across the interface")
    if not (cont.any() and (~cont).any()) or abs(cont_load) < 1e3:
        failures.append("the column was not loaded or has no points of one of the regions")
    print(f"continuum: dsigma_yy/(M deps_yy) {stiffness.min():.6f}-{stiffness.max():.6f}, "
          f"lateral {lateral.min():.6f}-{lateral.max():.6f}; dsigma_yy DEM {dem_load / 1e3:.3f} "
          f"kPa, continuum {cont_load / 1e3:.3f} kPa")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


main()
