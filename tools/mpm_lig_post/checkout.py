"""Where the source tree is, for the tools' defaults that name a checkout's files (build/mpm_lig,
tests/hard, docs/): this package lives in its tools/ folder."""
import os

SOURCE_TREE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def path(*parts):
    """A path inside the source tree."""
    return os.path.join(SOURCE_TREE, *parts)
