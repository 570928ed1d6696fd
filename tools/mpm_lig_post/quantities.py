"""What a run is about, measured from its history.csv (and case): each quantity maps a run to a
scalar, a curve (x, y) or a per-cycle series; tradeoff.py turns them into errors.

Element tests (drained biaxial / triaxial, compression positive, axial = the most compressed
axis): peak and 10-15 % mobilised friction angle sin(phi) = (s1 - s3) / (s1 + s3); the largest
dilatancy angle sin(psi) = -d e_v / (2 d e_1 - d e_v) (plane strain and axisymmetric alike)
from straight-line fits of e_v over sliding 2 % windows of e_1; the deviator q over axial strain.
Cyclic simple shear: the first cycle that ends with p' < 0.1 p'_0 and G_sec of every cycle.
Footing: mean q/q_s over s/B in [0.1, 0.4] and the peak q/q_s.

Angles are compared by their absolute difference in degrees (Quantity.absolute): a relative
error of an angle near zero (the dilatancy angle of a loose packing, a friction angle early in
a test) means nothing. A measure that the run does not reach raises NotReached with the reason.
"""
import math
import os

import numpy as np

from . import footing
from .errors import InputError
from .shear import count_cycles, cycle_table, shear_series
from .tables import read_history, require_columns

SCALAR, CURVE, SERIES = "scalar", "curve", "series"
# The errors the study recommends settings for: relative ones, and angles' in degrees (about
# 1, 4 and 12 % of a 25 deg friction angle, but the same for a dilatancy angle near zero).
RELATIVE_TARGETS = (0.01, 0.05, 0.15)
ANGLE_TARGETS = (0.25, 1.0, 3.0)


class NotReached(Exception):
    """The run does not reach the quantity (too short for its window, never liquefied): why."""


class Quantity:
    """name, kind (scalar | curve | series), unit and measure(run) -> value (raises NotReached
    with the reason when the run does not reach it). absolute: its error is |Q - Q_ref| in
    `unit` (angles, anything whose reference can be near zero), otherwise relative."""

    def __init__(self, name, kind, unit, measure, absolute=False, targets=RELATIVE_TARGETS):
        self.name, self.kind, self.unit, self.measure = name, kind, unit, measure
        self.absolute, self.targets = absolute, tuple(targets)

    def error_text(self, e, signed=False):
        """An error of this quantity for a table: '1.2 %' or '0.31 deg' ('-': none)."""
        if e is None:
            return "-"
        if self.absolute:
            return f"{e:{'+' if signed else ''}.3g} {self.unit}".rstrip()
        return f"{100 * e:{'+' if signed else ''}.3g} %"

    def evaluate(self, run):
        """(value, None), or (None, why) when the run does not reach the quantity."""
        try:
            return self.measure(run), None
        except NotReached as e:
            return None, str(e)

    def value(self, run):
        """The value, None when the run does not reach it."""
        return self.evaluate(run)[0]


class Run:
    """A finished run: its output directory (history.csv) and its case."""

    def __init__(self, directory, case):
        self.directory, self.case = directory, case
        self._history = None

    @property
    def history(self):
        if self._history is None:
            self._history = read_history(os.path.join(self.directory, "history.csv"))
        return self._history

    def columns(self, *names):
        path = os.path.join(self.directory, "history.csv")
        require_columns(self.history, names, path)
        return [self.history[n] for n in names]


# ---- element tests -------------------------------------------------------------------------

def principal_stresses(h, dimension):
    """(s1, s3) of every row: the largest and smallest compression-positive principal stresses
    (in-plane in 2D)."""
    names = ["xx", "yy", "zz", "xy", "xz", "yz"]
    missing = [f"s_{n}" for n in names if f"s_{n}" not in h]
    if missing:
        raise InputError(f"{getattr(h, 'path', 'history.csv')}: missing column '{missing[0]}' "
                         "(not an element test?)")
    s = np.zeros((len(h["s_xx"]), 3, 3))
    for (i, j), n in zip([(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)], names):
        s[:, i, j] = s[:, j, i] = -h[f"s_{n}"]
    if dimension == 2:
        s = s[:, :2, :2]
    eig = np.linalg.eigvalsh(s)
    return eig[:, -1], eig[:, 0]


def peak_ratio_row(s1, s3):
    """The row of largest stress ratio (s1 - s3) / (s1 + s3) among loaded rows (s1 + s3 > 0),
    or None when no row is loaded."""
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(s1 + s3 > 0, (s1 - s3) / (s1 + s3), -np.inf)
    k = int(np.argmax(ratio))
    return k if np.isfinite(ratio[k]) else None


def principal_series(h, dimension):
    """(s1, s3, e1, e_v): compression-positive principal stresses, axial and volumetric strain."""
    s1, s3 = principal_stresses(h, dimension)
    axial = int(np.argmin([h["e_xx"][-1], h["e_yy"][-1], h["e_zz"][-1]]))
    e1 = -h[["e_xx", "e_yy", "e_zz"][axial]]
    return s1, s3, e1, -h["e_vol"]


def _dimension(run):
    if "dimension" in run.case:
        return int(run.case["dimension"])
    return int(run.case.get("rve", {}).get("dimension", 3))


def mobilised(run):
    """(mobilised friction angle [deg], axial strain, volumetric strain) per history row,
    compression positive."""
    s1, s3, e1, ev = principal_series(run.history, _dimension(run))
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(s1 + s3 > 0, (s1 - s3) / (s1 + s3), 0.0)
    return np.degrees(np.arcsin(np.clip(ratio, -1, 1))), e1, ev


def peak_friction(run):
    return float(np.max(mobilised(run)[0]))


def window_friction(lo, hi):
    def measure(run):
        phi, e1, _ = mobilised(run)
        inside = (e1 >= lo) & (e1 <= hi)
        if not inside.any():
            raise NotReached(f"the run ends at {100 * e1.max():.3g} % axial strain, before "
                             f"{100 * lo:g}-{100 * hi:g} %")
        return float(np.mean(phi[inside]))
    return measure


def max_dilatancy(window=0.02):
    def measure(run):
        _, e1, ev = mobilised(run)
        best = None
        for k in range(len(e1)):
            inside = (e1 >= e1[k]) & (e1 <= e1[k] + window)
            if e1[k] + window > e1[-1] or inside.sum() < 3:
                break
            slope = np.polyfit(e1[inside], ev[inside], 1)[0]  # d e_v / d e_1
            sin_psi = -slope / (2.0 - slope)
            psi = math.degrees(math.asin(max(-1.0, min(1.0, sin_psi))))
            best = psi if best is None else max(best, psi)
        if best is None:
            raise NotReached(f"the run's {100 * e1[-1]:.3g} % axial strain holds no "
                             f"{100 * window:g} % window of three rows")
        return best
    return measure


def deviator_curve(run):
    s1, s3, e1, _ = principal_series(run.history, _dimension(run))
    return e1, s1 - s3


# ---- cyclic simple shear -------------------------------------------------------------------

def _cycles(run):
    """(cycle numbers, p' at each cycle's end, G_sec per cycle, p'_0) of a simple-shear history."""
    path = os.path.join(run.directory, "history.csv")
    gamma, tau, p, cycle = shear_series(run.history, path)
    cycle = count_cycles(gamma) if cycle is None else np.rint(cycle).astype(int)
    rows = cycle_table(gamma, tau, p, cycle)
    return (np.array([r[0] for r in rows]), np.array([r[4] for r in rows]),
            np.array([r[3] for r in rows]), p[0])


def liquefaction_cycle(run):
    numbers, p_end, _, p0 = _cycles(run)
    below = np.flatnonzero(p_end < 0.1 * p0)
    if not below.size:
        raise NotReached(f"p' stays above 0.1 p'_0 over the {len(numbers)} cycles run")
    return float(numbers[below[0]])


def secant_moduli(run):
    """G_sec of every complete cycle up to liquefaction (after it the modulus is ~0 and noise)."""
    numbers, p_end, modulus, p0 = _cycles(run)
    below = np.flatnonzero(p_end < 0.1 * p0)
    last = below[0] + 1 if below.size else len(numbers)
    return modulus[:last]


# ---- footing -------------------------------------------------------------------------------

def _footing_curve(run):
    settlement, q = run.columns("settlement", "q")
    width = footing.width(run.case, run.directory)
    return settlement / width, q / (footing.surcharge(run.case, run.directory) or 1.0)


def plateau(lo, hi):
    def measure(run):
        s, y = _footing_curve(run)
        inside = (s >= lo) & (s <= hi)
        if not inside.any() or s.max() < hi:
            raise NotReached(f"the run ends at s/B = {s.max():.3g}, before {lo:g}-{hi:g}")
        return float(np.mean(y[inside]))
    return measure


def footing_peak(hi):
    def measure(run):
        s, y = _footing_curve(run)
        inside = s <= hi
        if not inside.any():
            raise NotReached(f"no row with s/B <= {hi:g}")
        return float(np.max(y[inside]))
    return measure


# ---- any history column --------------------------------------------------------------------

REDUCERS = {"max": np.max, "min": np.min, "mean": np.mean, "final": lambda v: v[-1]}


def column_quantity(spec, where):
    """{"column": NAME, "reduce": max|min|mean|final, "x": COLUMN, "range": [a, b]} -> scalar;
    {"column": NAME, "curve": X_COLUMN} -> the whole curve over X (RMS error). A scalar whose
    reference can be near zero takes "error": "absolute" with "unit" and "targets" (the
    errors to recommend settings for, in that unit)."""
    if not isinstance(spec, dict) or "column" not in spec:
        raise InputError(f"{where}: expected an object with 'column'")
    name = spec["column"]
    mode = spec.get("error", "relative")
    if mode not in ("relative", "absolute"):
        raise InputError(f"{where}.error: expected 'relative' or 'absolute', got '{mode}'")
    targets = spec.get("targets", list(RELATIVE_TARGETS) if mode == "relative" else None)
    if not isinstance(targets, list) or not targets or any(
            isinstance(t, bool) or not isinstance(t, (int, float)) or not t > 0 for t in targets):
        raise InputError(f"{where}.targets: expected a list of errors > 0"
                         + (" in the column's unit (an absolute error needs them)"
                            if mode == "absolute" else ""))
    if mode == "absolute" and "curve" in spec:
        raise InputError(f"{where}.error: a curve's error is relative to its largest value")
    if "curve" in spec:
        x = spec["curve"]
        return Quantity(spec.get("name", f"{name}({x})"), CURVE, "",
                        lambda run: tuple(run.columns(x, name)))
    reduce = spec.get("reduce", "max")
    if reduce not in REDUCERS:
        raise InputError(f"{where}.reduce: expected one of {', '.join(REDUCERS)}, got '{reduce}'")
    window = spec.get("range")
    if window is not None and (not isinstance(window, list) or len(window) != 2 or "x" not in spec):
        raise InputError(f"{where}: 'range' needs 'x' (a column) and two numbers [a, b]")

    def measure(run):
        (y,) = run.columns(name)
        if window is not None:
            (x,) = run.columns(spec["x"])
            inside = (x >= window[0]) & (x <= window[1])
            if not inside.any():
                raise NotReached(f"no row with {spec['x']} in {window} (the run's "
                                 f"{spec['x']}: {x.min():.4g} ... {x.max():.4g})")
            y = y[inside]
        return float(REDUCERS[reduce](y))
    label = spec.get("name", f"{reduce} {name}" + (f" ({spec['x']} in {window})" if window else ""))
    return Quantity(label, SCALAR, spec.get("unit", ""), measure, mode == "absolute", targets)


PRESETS = {
    "element": lambda: [
        Quantity("peak phi", SCALAR, "deg", peak_friction, True, ANGLE_TARGETS),
        Quantity("phi at 10-15 %", SCALAR, "deg", window_friction(0.10, 0.15), True,
                 ANGLE_TARGETS),
        Quantity("max psi", SCALAR, "deg", max_dilatancy(), True, ANGLE_TARGETS),
        Quantity("q curve", CURVE, "Pa", deviator_curve)],
    "cyclic": lambda: [
        Quantity("liquefaction cycle", SCALAR, "", liquefaction_cycle),
        Quantity("G_sec per cycle", SERIES, "Pa", secant_moduli)],
    "footing": lambda: [
        Quantity("plateau q/q_s", SCALAR, "", plateau(0.1, 0.4)),
        Quantity("peak q/q_s", SCALAR, "", footing_peak(0.4))],
    # A footing pushed to d/B = 1.0 (the internal length's mesh study): the peak, the plateau
    # and the post-peak mean.
    "footing_to_1": lambda: [
        Quantity("peak q/q_s", SCALAR, "", footing_peak(1.0)),
        Quantity("q/q_s, s/B 0.1-0.4", SCALAR, "", plateau(0.1, 0.4)),
        Quantity("q/q_s, s/B 0.4-1.0", SCALAR, "", plateau(0.4, 1.0))],
    # A footing pushed to d/B = 1.5: the peak, the plateau and the two post-peak stages.
    "footing_deep": lambda: [
        Quantity("peak q/q_s", SCALAR, "", footing_peak(1.5)),
        Quantity("q/q_s, s/B 0.1-0.4", SCALAR, "", plateau(0.1, 0.4)),
        Quantity("q/q_s, s/B 0.4-1.0", SCALAR, "", plateau(0.4, 1.0)),
        Quantity("q/q_s, s/B 1.0-1.5", SCALAR, "", plateau(1.0, 1.5))],
}


def default_preset(case):
    analysis = case.get("analysis", {})
    if analysis.get("type") == "element_test":
        return "element"
    if case.get("rigid_bodies"):
        return "footing"
    if case.get("output", {}).get("simple_shear"):
        return "cyclic"
    raise InputError("cannot tell what the case is about: give \"quantities\" in the study "
                     "(element | cyclic | footing | footing_to_1 | footing_deep | a list of "
                     "history columns)")


def quantities(spec, case, where):
    """The study's quantities: a preset name, a list of presets and column specs, or the case's."""
    if spec is None:
        spec = default_preset(case)
    items = spec if isinstance(spec, list) else [spec]
    out = []
    for i, item in enumerate(items):
        if isinstance(item, str):
            if item not in PRESETS:
                raise InputError(f"{where}: quantities: unknown preset '{item}' "
                                 f"(expected {', '.join(PRESETS)} or a column object)")
            out += PRESETS[item]()
        else:
            out.append(column_quantity(item, f"{where}: quantities[{i}]"))
    return out
