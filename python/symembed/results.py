"""Reading a results folder written by `symembed run` (or symembed.run, merge, eval).

A table (pairs.csv, curve.csv, shapes.csv, timings.csv, failures.csv, comparison.csv) becomes a
dict of columns in file order: each column a numpy float64 array when every cell is a number
(empty cells as NaN), else a numpy array of str. With frames=True each table is a pandas
DataFrame instead (pandas must be installed). summary.json becomes a dict.
"""

import csv
import json
import math
import os

import numpy as np

_VARIANT_TABLES = ("pairs", "curve", "shapes", "timings", "failures")


def _number(cell):
    if cell == "":
        return math.nan
    return float(cell)  # raises ValueError for text


def _column(cells):
    try:
        return np.array([_number(c) for c in cells], dtype=np.float64)
    except ValueError:
        return np.array(cells, dtype=str)


def read_table(path, frames=False):
    """A CSV file as {column: array} (see the module's doc), or a pandas DataFrame."""
    if frames:
        import pandas  # only when asked for: pandas is optional

        return pandas.read_csv(path, keep_default_na=False, na_values=[""])
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    for number, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise ValueError(
                f"{path}:{number}: {len(row)} cells, the header has {len(header)}"
            )
    return {name: _column([row[k] for row in body]) for k, name in enumerate(header)}


def _variant(folder, frames):
    out = {"name": os.path.basename(os.path.normpath(folder))}
    with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
        out["summary"] = json.load(f)
    for table in _VARIANT_TABLES:
        path = os.path.join(folder, table + ".csv")
        out[table] = read_table(path, frames) if os.path.exists(path) else None
    return out


def load_results(folder, frames=False):
    """The results of a run folder.

    folder: an experiment folder (OUT, holding variants.txt) or one variant's folder
    (OUT/VARIANT, holding summary.json).

    For a variant folder, returns {"name", "summary", "pairs", "curve", "shapes", "timings",
    "failures"}: summary.json as a dict, each table as described in the module's doc (None when
    the file is missing). For an experiment folder, returns {"variants": {name: that dict, ...}
    for the variants of variants.txt that have outputs, in its order, "comparison":
    comparison.csv's table (None when missing)}.

    Raises FileNotFoundError when the folder holds neither, ValueError for a malformed table.
    """
    folder = os.fspath(folder)
    if os.path.exists(os.path.join(folder, "summary.json")):
        return _variant(folder, frames)
    variants_txt = os.path.join(folder, "variants.txt")
    if not os.path.exists(variants_txt):
        raise FileNotFoundError(
            f"{folder}: not a results folder (no variants.txt, no summary.json)"
        )
    with open(variants_txt, encoding="utf-8") as f:
        names = [line.strip() for line in f if line.strip()]
    variants = {}
    for name in names:
        path = os.path.join(folder, name)
        if os.path.exists(os.path.join(path, "summary.json")):
            variants[name] = _variant(path, frames)
    comparison = os.path.join(folder, "comparison.csv")
    return {
        "variants": variants,
        "comparison": read_table(comparison, frames) if os.path.exists(comparison) else None,
    }
