"""The study file of tools/accuracy_cost.py: a base case, knobs (JSON paths into it) with their
values, the reference settings and the seeds that give the reference's scatter.

    {"base": "../cases/element_biaxial_2d_100kPa.json",    relative to the study file
     "set": {"analysis.axial_strain": 0.05},              optional: on every variant
     "sweep": [{"path": "rve.substeps.inertial_number", "values": [1e-4, 1e-3, 1e-2]},
               {"path": "rve.grains", "values": [100, 400]},
               {"path": "mesh.cells", "values": [[12, 14], [24, 28]],
                "also": {"boundary_conditions[3].points.min": [[0.1, 0.57], [0.1, 0.585]]}}],
     "mode": "one_at_a_time",                             or "grid" (the default)
     "reference": {"rve.substeps.inertial_number": 1e-4, "rve.grains": 400},
     "seeds": {"path": "rve.seed", "values": [1, 2, 3], "apply_to": "reference"},
     "quantities": "element"}                             element | cyclic | footing | list

A path is dot-separated keys with [i] for list entries: "materials[0].rve.grains". "also" moves
other paths with a knob, one value per knob value (e.g. a surface box that depends on the mesh).
"""
import copy
import hashlib
import itertools
import json
import os
import re

from .errors import InputError
from .tables import read_json

_TOKEN = re.compile(r"([^.\[\]]+)|\[(\d+)\]")


def split_path(path):
    """'materials[0].rve.grains' -> ['materials', 0, 'rve', 'grains']."""
    if not isinstance(path, str) or not path:
        raise InputError(f"knob path must be a non-empty string, got {path!r}")
    keys, pos = [], 0
    for m in _TOKEN.finditer(path):
        if m.start() != pos and path[pos:m.start()] != ".":
            raise InputError(f"knob path '{path}': cannot read it at '{path[pos:]}'")
        keys.append(m.group(1) if m.group(1) is not None else int(m.group(2)))
        pos = m.end()
    if pos != len(path):
        raise InputError(f"knob path '{path}': cannot read it at '{path[pos:]}'")
    return keys


def _child(node, key):
    if isinstance(key, int):
        return node[key] if isinstance(node, list) and key < len(node) else None
    return node.get(key) if isinstance(node, dict) else None


def get_path(case, path):
    """The value at `path`; InputError naming the first missing step."""
    node = case
    walked = ""
    for key in split_path(path):
        walked += f"[{key}]" if isinstance(key, int) else (f".{key}" if walked else key)
        nxt = _child(node, key)
        if nxt is None:
            have = ", ".join(sorted(node)) if isinstance(node, dict) else f"{type(node).__name__}"
            raise InputError(f"unknown knob path '{path}': the case has no '{walked}' "
                             f"(there: {have})")
        node = nxt
    return node


def set_path(case, path, value, create=False):
    """Set the value at `path` (its parent must exist; the key too unless `create`)."""
    keys = split_path(path)
    parent = get_path(case, _join(keys[:-1])) if len(keys) > 1 else case
    last = keys[-1]
    if isinstance(last, int):
        if not isinstance(parent, list) or last >= len(parent):
            raise InputError(f"unknown knob path '{path}': no list entry [{last}]")
    elif not isinstance(parent, dict):
        raise InputError(f"unknown knob path '{path}': '{_join(keys[:-1])}' is not an object")
    elif last not in parent and not create:
        raise InputError(f"unknown knob path '{path}': the case has no key '{last}' there "
                         f"(there: {', '.join(sorted(parent))}); put it in \"set\" first")
    parent[last] = copy.deepcopy(value)


def _join(keys):
    out = ""
    for k in keys:
        out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else k)
    return out


def short_name(path):
    """The knob's last key, for labels: 'rve.substeps.inertial_number' -> 'inertial_number'."""
    keys = [k for k in split_path(path) if not isinstance(k, int)]
    return keys[-1] if keys else path


class Variant:
    """One run of the study: its settings (path -> value), seed and whether it is the reference."""

    def __init__(self, settings, seed=None, reference=False):
        self.settings = dict(settings)
        self.seed = seed
        self.reference = reference
        self.name = ""
        self.folder = ""

    def label(self, knobs):
        parts = [f"{short_name(p)}={self.settings[p]:g}" if isinstance(self.settings[p], float)
                 else f"{short_name(p)}={self.settings[p]}" for p in knobs]
        if self.seed is not None:
            parts.append(f"seed={self.seed}")
        return ", ".join(parts)


class Study:
    """A checked study file."""

    def __init__(self, path):
        self.path = path
        spec = read_json(path)
        here = os.path.dirname(os.path.abspath(path))
        base = _need(spec, "base", path)
        if not isinstance(base, str) or not base:
            raise InputError(f"{path}: base: expected the base case's file name, got "
                             f"{json.dumps(base)}")
        self.base_path = base if os.path.isabs(base) else os.path.join(here, base)
        self.base = read_json(self.base_path)
        _absolute_files(self.base, os.path.dirname(os.path.abspath(self.base_path)))
        for key in spec:
            if key not in ("base", "set", "sweep", "mode", "reference", "seeds", "quantities",
                           "title") and not key.startswith("_"):
                raise InputError(f"{path}: unknown key '{key}'")
        self.title = spec.get("title", os.path.splitext(os.path.basename(path))[0])
        changes = spec.get("set", {})
        if not isinstance(changes, dict):
            raise InputError(f"{path}: set: expected an object path -> value")
        for p, v in changes.items():
            set_path(self.base, p, v, create=True)
        self.also = {}
        self.knobs, self.values = self._sweep(spec, path)
        self.mode = spec.get("mode", "grid")
        if self.mode not in ("grid", "one_at_a_time"):
            raise InputError(f"{path}: mode: expected 'grid' or 'one_at_a_time', got '{self.mode}'")
        self.reference = self._reference(spec, path)
        self.seed_path, self.seeds, self.seeds_apply_to = self._seeds(spec, path)
        self.quantities = spec.get("quantities")

    def _sweep(self, spec, path):
        sweep = _need(spec, "sweep", path)
        if not isinstance(sweep, list) or not sweep:
            raise InputError(f"{path}: sweep: expected a non-empty list of {{path, values}}")
        knobs, values = [], {}
        for i, knob in enumerate(sweep):
            where = f"{path}: sweep[{i}]"
            p = _need(knob, "path", where)
            v = _need(knob, "values", where)
            if not isinstance(v, list) or not v:
                raise InputError(f"{where}.values: expected a non-empty list")
            if p in values:
                raise InputError(f"{where}: knob '{p}' given twice")
            get_path(self.base, p)
            knobs.append(p)
            values[p] = v
            self.also[p] = self._also(knob, v, where)
        return knobs, values

    def _also(self, knob, values, where):
        """Paths that move with a knob, one value per knob value (a mesh-dependent box)."""
        also = knob.get("also", {})
        if not isinstance(also, dict):
            raise InputError(f"{where}.also: expected an object path -> values")
        for q, v in also.items():
            if not isinstance(v, list) or len(v) != len(values):
                raise InputError(f"{where}.also.{q}: expected {len(values)} values, one per "
                                 "value of the knob")
            get_path(self.base, q)
        return also

    def _reference(self, spec, path):
        ref = spec.get("reference")
        if not isinstance(ref, dict):
            raise InputError(f"{path}: missing reference (an object knob path -> the value of "
                             f"the most accurate settings)")
        for p in self.knobs:
            if p not in ref:
                raise InputError(f"{path}: reference: missing the value of knob '{p}'")
            if ref[p] not in self.values[p]:
                raise InputError(f"{path}: reference.{p} = {ref[p]} is not one of the sweep's "
                                 f"values {self.values[p]}")
        for p in ref:
            if p not in self.values:
                raise InputError(f"{path}: reference: '{p}' is not a knob of the sweep")
        return dict(ref)

    def _seeds(self, spec, path):
        seeds = spec.get("seeds")
        if seeds is None:
            return None, [], "reference"
        where = f"{path}: seeds"
        p = _need(seeds, "path", where)
        v = _need(seeds, "values", where)
        if not isinstance(v, list) or len(v) < 2:
            raise InputError(f"{where}.values: give two or more seeds (the scatter needs them)")
        if p in self.values:
            raise InputError(f"{where}.path: '{p}' is also a knob of the sweep")
        get_path(self.base, p)
        apply_to = seeds.get("apply_to", "reference")
        if apply_to not in ("reference", "all"):
            raise InputError(f"{where}.apply_to: expected 'reference' or 'all', got '{apply_to}'")
        return p, list(v), apply_to

    def variants(self):
        """Every run of the study, the reference first, named v000, v001, ... in this order; each
        runs in a folder named after its settings, so that adding values keeps the folders."""
        if self.mode == "grid":
            settings = [dict(zip(self.knobs, combo))
                        for combo in itertools.product(*(self.values[k] for k in self.knobs))]
        else:
            settings = [dict(self.reference)]
            for k in self.knobs:
                settings += [{**self.reference, k: v} for v in self.values[k]
                             if v != self.reference[k]]
        settings.sort(key=lambda s: s != self.reference)
        out = []
        for s in settings:
            is_ref = s == self.reference
            if self.seeds and (is_ref or self.seeds_apply_to == "all"):
                out += [Variant(s, seed, is_ref) for seed in self.seeds]
            else:
                out.append(Variant(s, None, is_ref))
        for k, v in enumerate(out):
            v.name = f"v{k:03d}"
            v.folder = re.sub(r"[^A-Za-z0-9.+-]+", "_", v.label(self.knobs).replace("=", "-"))
        if len({v.folder for v in out}) < len(out):  # knobs with the same last key
            for v in out:
                v.folder += "_" + hashlib.sha1(json.dumps(v.settings, sort_keys=True).encode()
                                               ).hexdigest()[:8]
        return out

    def case_of(self, variant):
        """The variant's case: the base with its settings (and seed) applied."""
        case = copy.deepcopy(self.base)
        for p, value in variant.settings.items():
            set_path(case, p, value)
            for q, linked in self.also.get(p, {}).items():
                set_path(case, q, linked[self.values[p].index(value)])
        if variant.seed is not None:
            set_path(case, self.seed_path, variant.seed)
        return case


FILE_KEYS = ("restart_file",)


def _absolute_files(node, folder):
    """File names a case gives relative to its own folder, made absolute: the variants'
    cases live elsewhere."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(
        node, list) else []
    for key, value in list(items):
        if key in FILE_KEYS and isinstance(value, str) and not os.path.isabs(value):
            node[key] = os.path.join(folder, value)
        else:
            _absolute_files(value, folder)


def _need(node, key, where):
    if not isinstance(node, dict) or key not in node:
        raise InputError(f"{where}: missing key '{key}'")
    return node[key]


def write_case(case, path):
    """A variant's case file (indented JSON)."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        json.dump(case, f, indent=2)
        f.write("\n")
