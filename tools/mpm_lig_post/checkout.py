"""Where the source tree is, for the tools' defaults that name a checkout's files (build/mpm_lig,
tests/hard, docs/): this package lives in its tools/ folder."""
import os
import shutil

from .errors import InputError

SOURCE_TREE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def path(*parts):
    """A path inside the source tree."""
    return os.path.join(SOURCE_TREE, *parts)


def find_mpm_lig(given=None):
    """The mpm_lig executable: `given`, else this checkout's build/mpm_lig, else the PATH's."""
    candidates = [given] if given else [path("build", "mpm_lig"), shutil.which("mpm_lig")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return os.path.abspath(c)
    raise InputError(f"mpm_lig executable not found ({given or 'build/mpm_lig or PATH'}): "
                     "give --mpm-lig PATH (build it: cmake --build build --target mpm_lig)")
