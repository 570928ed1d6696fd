"""history.csv and summary.json / case-file readers. Every failure to read a file (absent, a
folder, unreadable, not text, not the expected format) is an InputError naming the file."""
import csv
import io
import json
import os

import numpy as np

from .errors import InputError


def read_text(path):
    """A text file's content; InputError naming the file when it cannot be read as UTF-8
    text (random bytes, a NUL byte, a folder, no permission)."""
    if os.path.isdir(path):
        raise InputError(f"{path}: is a folder, not a file")
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"{path}: cannot be read ({e.strerror})") from None
    try:
        text = data.decode("utf-8-sig")  # a byte-order mark (a spreadsheet's save) is no text
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not a text file (byte {e.start} is not UTF-8: damaged or "
                         "not the file the tool expects)") from None
    if "\0" in text:
        raise InputError(f"{path}: not a text file (NUL byte at {text.index(chr(0))}: damaged "
                         "or not the file the tool expects)")
    return text


class History(dict):
    """history.csv as {column: float array}; a missing column raises InputError naming the
    file and the columns it has."""

    def __init__(self, path, columns):
        super().__init__(columns)
        self.path = path

    def __missing__(self, name):
        raise InputError(f"{self.path}: missing column '{name}' (has: {', '.join(self)})")


def read_history(path):
    """history.csv (header row, then numbers) as a History {column: float array}."""
    text = read_text(path)
    try:
        rows = list(csv.reader(io.StringIO(text, newline="")))
    except csv.Error as e:
        raise InputError(f"{path}: not a CSV table ({e})") from None
    if not rows or not rows[0]:
        raise InputError(f"{path}: empty file (no header row)")
    header = [name.strip() for name in rows[0]]
    body = [(k + 2, r) for k, r in enumerate(rows[1:]) if r]
    if not body:
        raise InputError(f"{path}: no data rows")
    for line, r in body:
        if len(r) != len(header):
            raise InputError(f"{path}: line {line}: {len(r)} values but {len(header)} columns")
    try:
        data = np.array([[float(v) for v in r] for _, r in body])
    except ValueError as e:
        raise InputError(f"{path}: not a number ({e})") from None
    return History(path, {name: data[:, k] for k, name in enumerate(header)})


def require_columns(table, names, path):
    """Raise InputError naming the first of `names` that `table` lacks."""
    for name in names:
        if name not in table:
            raise InputError(f"{path}: missing column '{name}' (has: {', '.join(table)})")


def read_json(path, required=True):
    """A JSON file as a dict; None when it is absent and not required. Every file the tools read
    (case, summary, study) is a JSON object; anything else is refused here, once."""
    if not os.path.exists(path) and not required:
        return None
    text = read_text(path)
    if not text.strip():
        raise InputError(f"{path}: empty file (not valid JSON)")
    try:
        content = json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(content, dict):
        raise InputError(f"{path}: must be a JSON object, not a {type(content).__name__}")
    return content


def need(node, key, where, number=False):
    """node[key] of a JSON object read from `where`; InputError naming the key when it is
    missing (or, with number, not a finite number)."""
    if not isinstance(node, dict) or key not in node:
        raise InputError(f"{where}: missing key '{key}'")
    value = node[key]
    if number and (isinstance(value, bool) or not isinstance(value, (int, float))
                   or not np.isfinite(value)):
        raise InputError(f"{where}: {key}: expected a number, got {json.dumps(value)}")
    return value
