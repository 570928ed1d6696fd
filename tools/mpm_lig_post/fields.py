"""results.h5 reader (layout of src/io/field_writer.h): one group /step_NNNNNN per output
step with attributes time and step, `positions` (n x 3) and the point fields."""
import contextlib
import os

import numpy as np

from .errors import InputError
from .requirements import install_hint

try:
    import h5py
except ImportError:  # reported when a field file is actually needed
    h5py = None

# What h5py raises on a damaged file (bad superblock, truncated, corrupt object headers or
# chunks); h5py keeps the HDF5 library's own error stack quiet, the message names the file.
H5_ERRORS = (OSError, RuntimeError, KeyError, ValueError, TypeError)


def _open(path):
    if h5py is None:
        raise InputError(f"{path}: reading it needs h5py: {install_hint(['h5py'])}")
    if os.path.isdir(path):
        raise InputError(f"{path}: is a folder, not a file")
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    try:
        return h5py.File(path, "r")
    except H5_ERRORS as e:
        raise InputError(f"{path}: not a readable HDF5 file ({e}): damaged, truncated or "
                         "still being written") from None


@contextlib.contextmanager
def damaged(path):
    """Turn h5py's errors while reading `path` into an InputError naming it."""
    try:
        yield
    except H5_ERRORS as e:
        raise InputError(f"{path}: damaged HDF5 file ({type(e).__name__}: {e})") from None


class FieldFile:
    """Open results.h5; `steps` lists the output steps in order."""

    def __init__(self, path):
        self.path = path
        self.h5 = _open(path)
        with damaged(path):
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
        with damaged(self.path):
            return StepFields(self.path, self.h5[self._groups[step]], step)


class StepFields:
    """One output step: time, step and its datasets by name."""

    def __init__(self, path, group, step):
        self.path, self.group, self.step = path, group, step
        self.time = float(group.attrs.get("time", np.nan))

    def names(self):
        with damaged(self.path):
            return list(self.group)

    def __getitem__(self, name):
        with damaged(self.path):
            if name not in self.group:
                raise InputError(f"{self.path}: step {self.step}: missing dataset '{name}' "
                                 f"(has: {', '.join(self.group)})")
            return np.asarray(self.group[name][()])


def every_item(path):
    """Every dataset and attribute of an HDF5 file as {"group/name": array,
    "group/name@attribute": array}: what bit-identity checks compare."""
    out = {}
    with _open(path) as f, damaged(path):
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                out[name] = obj[()]
            for key, value in obj.attrs.items():
                out[name + "@" + key] = np.asarray(value)
        f.visititems(visit)
    return out
