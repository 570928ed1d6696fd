"""A small reader for the ASCII legacy-VTK polydata the RVE snapshots are written in
(src/io/vtk_snapshot.cpp): POINTS, VERTICES, LINES, and SCALARS / VECTORS in POINT_DATA and
CELL_DATA. numpy only."""

import numpy as np

from .errors import InputError
from .tables import read_text


class PolyData:
    """points (n x 3), cells {"VERTICES"|"LINES"|...: list of index arrays},
    point_data and cell_data {name: array (n,) or (n, 3)}."""

    def __init__(self, path):
        self.path = path
        self.points = np.zeros((0, 3))
        self.cells = {}
        self.point_data = {}
        self.cell_data = {}

    def lines(self):
        """Two-point line cells as an (m, 2, 3) array of end points."""
        segments = self.cells.get("LINES", [])
        if any(len(c) != 2 for c in segments):
            raise InputError(f"{self.path}: LINES with more than two points are not supported")
        if not segments:
            return np.zeros((0, 2, 3))
        return self.points[np.array(segments)]

    def field(self, name, where="point"):
        """A named POINT_DATA (where="point") or CELL_DATA array; InputError if absent."""
        data = self.point_data if where == "point" else self.cell_data
        if name not in data:
            have = ", ".join(data) or "none"
            raise InputError(f"{self.path}: missing {where} data '{name}' (has: {have})")
        return data[name]


class _Tokens:
    def __init__(self, path, words):
        self.path, self.words, self.pos = path, words, 0

    def more(self):
        return self.pos < len(self.words)

    def next(self, what):
        if not self.more():
            raise InputError(f"{self.path}: file ends where {what} was expected")
        self.pos += 1
        return self.words[self.pos - 1]

    def integer(self, what):
        word = self.next(what)
        try:
            return int(word)
        except ValueError:
            raise InputError(f"{self.path}: expected {what}, got '{word}'") from None

    def numbers(self, count, what):
        if self.pos + count > len(self.words):
            raise InputError(f"{self.path}: file ends inside {what}")
        try:
            values = np.array(self.words[self.pos:self.pos + count], dtype=float)
        except ValueError:
            raise InputError(f"{self.path}: non-numeric value in {what}") from None
        self.pos += count
        return values


def read_polydata(path):
    """Parse one legacy-VTK ASCII POLYDATA file."""
    lines = read_text(path).split("\n", 4)
    header = (lines + [""] * 4)[:4]
    rest = lines[4] if len(lines) > 4 else ""
    if not header[0].startswith("# vtk DataFile"):
        raise InputError(f"{path}: not a legacy VTK file (first line '{header[0].strip()}')")
    if header[2].strip().upper() != "ASCII":
        raise InputError(f"{path}: only ASCII legacy VTK is supported, got '{header[2].strip()}'")
    if header[3].split()[-1:] != ["POLYDATA"]:
        raise InputError(f"{path}: expected DATASET POLYDATA, got '{header[3].strip()}'")
    poly = PolyData(path)
    tokens = _Tokens(path, rest.split())
    target = None  # the attribute dict SCALARS/VECTORS go to
    size = 0
    while tokens.more():
        key = tokens.next("a keyword").upper()
        if key == "POINTS":
            n = tokens.integer("the point count")
            tokens.next("the point type")
            poly.points = tokens.numbers(3 * n, "POINTS").reshape(n, 3)
        elif key in ("VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS"):
            n = tokens.integer(f"the {key} count")
            flat = tokens.numbers(tokens.integer(f"the {key} size"), key).astype(int)
            cells, k = [], 0
            for _ in range(n):
                if k >= len(flat):
                    raise InputError(f"{path}: {key}: {n} cells do not fit in its size")
                cells.append(flat[k + 1:k + 1 + flat[k]])
                k += 1 + flat[k]
            poly.cells[key] = cells
        elif key in ("POINT_DATA", "CELL_DATA"):
            size = tokens.integer(f"the {key} count")
            target = poly.point_data if key == "POINT_DATA" else poly.cell_data
        elif key in ("SCALARS", "VECTORS", "NORMALS"):
            if target is None:
                raise InputError(f"{path}: {key} before POINT_DATA / CELL_DATA")
            name = tokens.next("a data name")
            tokens.next("a data type")
            if key == "SCALARS":
                # optional component count, then LOOKUP_TABLE name
                word = tokens.next("LOOKUP_TABLE")
                components = 1
                if word.upper() != "LOOKUP_TABLE":
                    if not word.isdigit():
                        raise InputError(f"{path}: SCALARS {name}: '{word}' is neither a "
                                         "component count nor LOOKUP_TABLE")
                    components = int(word)
                    tokens.next("LOOKUP_TABLE")
                tokens.next("the lookup table name")
                values = tokens.numbers(size * components, name)
                target[name] = values if components == 1 else values.reshape(size, components)
            else:
                target[name] = tokens.numbers(3 * size, name).reshape(size, 3)
        else:
            raise InputError(f"{path}: unsupported legacy-VTK keyword '{key}'")
    return poly
