"""results.h5 reader (layout of src/io/field_writer.h): one group /step_NNNNNN per output
step with attributes time and step, `positions` (n x 3) and the point fields."""
import os

import numpy as np

from .errors import InputError

try:
    import h5py
except ImportError:  # reported when a field file is actually needed
    h5py = None


class FieldFile:
    """Open results.h5; `steps` lists the output steps in order."""

    def __init__(self, path):
        if h5py is None:
            raise InputError("python3-h5py is not installed (apt-get install python3-h5py)")
        if not os.path.isfile(path):
            raise InputError(f"{path}: file not found")
        self.path = path
        try:
            self.h5 = h5py.File(path, "r")
        except OSError as e:
            raise InputError(f"{path}: not a readable HDF5 file ({e})") from None
        groups = [name for name in self.h5 if name.startswith("step_")]
        if not groups:
            raise InputError(f"{path}: no output step (no group step_NNNNNN)")
        self._groups = {int(self.h5[g].attrs.get("step", int(g[5:]))): g for g in groups}
        self.steps = sorted(self._groups)

    def close(self):
        self.h5.close()

    def step(self, step=None):
        """The group of output step `step` (default: the last one)."""
        if step is None:
            step = self.steps[-1]
        if step not in self._groups:
            raise InputError(f"{self.path}: no output step {step} "
                             f"(steps {self.steps[0]} ... {self.steps[-1]}, {len(self.steps)} in all)")
        return StepFields(self.path, self.h5[self._groups[step]], step)


class StepFields:
    """One output step: time, step and its datasets by name."""

    def __init__(self, path, group, step):
        self.path, self.group, self.step = path, group, step
        self.time = float(group.attrs.get("time", np.nan))

    def names(self):
        return list(self.group)

    def __getitem__(self, name):
        if name not in self.group:
            raise InputError(f"{self.path}: step {self.step}: missing dataset '{name}' "
                             f"(has: {', '.join(self.group)})")
        return np.asarray(self.group[name][()])


def every_item(path):
    """Every dataset and attribute of an HDF5 file as {"group/name": array,
    "group/name@attribute": array}: what bit-identity checks compare."""
    if h5py is None:
        raise InputError("python3-h5py is not installed (apt-get install python3-h5py)")
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
            for key, value in obj.attrs.items():
                out[name + "@" + key] = np.asarray(value)
        f.visititems(visit)
    return out
