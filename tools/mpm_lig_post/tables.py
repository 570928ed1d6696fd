"""history.csv and summary.json / case-file readers."""
import csv
import json
import os

import numpy as np

from .errors import InputError


def read_history(path):
    """history.csv (header row, then numbers) as {column: float array}."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or not rows[0]:
        raise InputError(f"{path}: empty file (no header row)")
    header = [name.strip() for name in rows[0]]
    body = [r for r in rows[1:] if r]
    if not body:
        raise InputError(f"{path}: no data rows")
    try:
        data = np.array([[float(v) for v in r] for r in body])
    except ValueError as e:
        raise InputError(f"{path}: not a number ({e})") from None
    if data.shape[1] != len(header):
        raise InputError(f"{path}: {data.shape[1]} values per row but {len(header)} columns")
    return {name: data[:, k] for k, name in enumerate(header)}


def require_columns(table, names, path):
    """Raise InputError naming the first of `names` that `table` lacks."""
    for name in names:
        if name not in table:
            raise InputError(f"{path}: missing column '{name}' (has: {', '.join(table)})")


def read_json(path, required=True):
    """A JSON file as a dict; None when it is absent and not required. Every file the tools read
    (case, summary, study) is a JSON object; anything else is refused here, once."""
    if not os.path.isfile(path):
        if required:
            raise InputError(f"{path}: file not found")
        return None
    try:
        with open(path) as f:
            content = json.load(f)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(content, dict):
        raise InputError(f"{path}: must be a JSON object, not a {type(content).__name__}")
    return content
