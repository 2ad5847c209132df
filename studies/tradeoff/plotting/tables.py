"""Reading what adb-tradeoff wrote: the CSV columns, a header-checking reader, and
`Dataset`, everything the figures draw (distances.csv, summary.csv, cells.csv and
reliability.csv), already judged by the tool (studies/tradeoff/judging.cpp)."""

import csv
import math
import os
from collections import defaultdict
from typing import NamedTuple, Optional

DISTANCE_COLUMNS = (
    "model", "triangles", "method", "p_min", "k_min", "budget_us", "distance", "queries",
    "mean_us", "overlapping", "error_pct", "mean_confidence", "reference")
SUMMARY_COLUMNS = (
    "model", "triangles", "method", "p_min", "k_min", "budget_us", "queries", "overlapping",
    "mean_us", "p95_us", "error_pct", "mean_confidence", "mean_node_pairs",
    "speedup_vs_exact", "speedup_vs_gimpact", "speedup_vs_fcl")
SUMMARY_OPTIONAL = ("ece",)  # absent from runs before the calibration columns existed
CELL_COLUMNS = ("model", "triangles", "cell", "count")
RELIABILITY_COLUMNS = (
    "model", "triangles", "method", "p_min", "k_min", "budget_us", "bin", "bin_lo", "bin_hi",
    "count", "mean_confidence", "fraction_right")

PEERS = ("exact", "gimpact", "fcl")  # the methods ADB is compared with, in legend order
PEER_LABELS = {"exact": "exact (own tree)", "gimpact": "Bullet GImpact", "fcl": "FCL OBBRSS"}
PEER_COLOURS = {"exact": "black", "gimpact": "tab:red", "fcl": "tab:purple"}
WORK_PREFIX = "adb-work:"  # the CSVs name ADB under a work budget of N pairs adb-work:N
POOLED = "adb-pooled"  # summary and reliability rows over every ADB setting together
ADB_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:cyan", "tab:olive",
               "tab:brown", "tab:pink", "tab:gray", "gold", "navy", "teal", "salmon")
TRIANGLE_STYLES = (("-", "o"), ("--", "s"), (":", "^"), ("-.", "v"), ((0, (5, 1, 1, 1)), "D"))
DEFAULT_ADB = (0.99, 10)  # the paper's headline setting: p_min = 0.99, k_min = 10
DPI = 120
CELLS = 512  # 8 x 8 x 8 cells per node box


class InputError(Exception):
    """An input the plots cannot do without is missing or malformed."""


class Setting(NamedTuple):
    """One method with its parameters, None where they do not apply.

    method is "adb", "adb-work" (work budget in `work`, node pairs), POOLED, a peer, or one
    of the baselines "exact-cut", "box-first" (with budget_us) and "root-boxes".
    """
    method: str
    p_min: Optional[float] = None
    k_min: Optional[int] = None
    budget_us: Optional[float] = None
    work: Optional[int] = None

    def sort_key(self):
        # Peers first in PEERS order, then the rest by k_min, p_min, budget (none last).
        rank = PEERS.index(self.method) if self.method in PEERS else len(PEERS)
        return (rank, self.method, self.k_min or 0, self.p_min or 0.0,
                self.budget_us is None, self.budget_us or 0.0, self.work or 0)

    def label(self):
        if self.method not in ("adb", "adb-work"):
            return PEER_LABELS.get(self.method, self.method)
        text = "ADB p_min=%g k_min=%d" % (self.p_min, self.k_min)
        if self.budget_us is not None:
            text += ", budget %g µs" % self.budget_us
        if self.work is not None:
            text += ", work %d node pairs" % self.work
        return text


def _float(text):
    """Parse a possibly empty CSV cell; None when empty or not a number."""
    text = text.strip()
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _setting(method, p_min, k_min, budget):
    """The Setting of one CSV row; ValueError when an ADB row lacks its parameters."""
    method = method.strip().lower()
    if method in ("exact-cut", "box-first"):
        return Setting(method, budget_us=_float(budget))
    if method != "adb" and not method.startswith(WORK_PREFIX):
        return Setting(method)  # parameters mean nothing for the other methods
    p, k = _float(p_min), _float(k_min)
    if p is None or k is None:
        raise ValueError("ADB row without p_min/k_min")
    if method == "adb":
        return Setting("adb", p, int(round(k)), _float(budget))
    return Setting("adb-work", p, int(round(k)), work=int(method[len(WORK_PREFIX):]))


def open_table(path, required, optional=()):
    """Open a CSV file, check its header; return (file, reader, column index).

    The index holds every required column and those optional ones the header has.
    """
    try:
        # errors="replace": a garbled byte in a half-written file must not stop the plots.
        handle = open(path, newline="", encoding="utf-8", errors="replace")
    except OSError as error:
        raise InputError("%s: cannot read (%s)" % (path, error.strerror)) from None
    reader = csv.reader(handle)
    header = next(reader, None)
    if header is None:
        handle.close()
        raise InputError("%s: empty file, expected the header line %s" % (path, ",".join(required)))
    header = [name.strip() for name in header]
    missing = [name for name in required if name not in header]
    if missing:
        handle.close()
        raise InputError("%s: header lacks column%s %s" % (
            path, "s" if len(missing) > 1 else "", ", ".join(missing)))
    present = list(required) + [name for name in optional if name in header]
    return handle, reader, {name: header.index(name) for name in present}


def _table_rows(reader, col):
    """A table's rows as {column: text}; a non-empty row cut short comes as None."""
    width = max(col.values()) + 1
    for row in reader:
        if len(row) >= width:
            yield {name: row[index] for name, index in col.items()}
        elif row:
            yield None


def _key(cell):
    """The (model, triangles, Setting) a row is about; ValueError when it does not parse."""
    setting = _setting(cell["method"], cell["p_min"], cell["k_min"], cell["budget_us"])
    return (cell["model"].strip(), int(float(cell["triangles"])), setting)


class Point(NamedTuple):
    """One row of distances.csv: a setting's queries at one distance, judged by adb-tradeoff
    (error and confidence over the queries whose root boxes overlap; None where none did)."""
    queries: int
    mean_us: Optional[float]
    overlapping: int
    error_pct: Optional[float]
    mean_confidence: Optional[float]


class SummaryRow(NamedTuple):
    mean_us: Optional[float]
    error_pct: Optional[float]
    mean_confidence: Optional[float]
    speedup: dict  # peer method -> speed-up of this setting against it
    ece: Optional[float] = None  # expected calibration error, where the method estimates


class Bin(NamedTuple):
    """One confidence bin of reliability.csv; confidence and right are None when empty."""
    lo: float
    hi: float
    count: int
    confidence: Optional[float]
    right: Optional[float]


class Dataset:
    """Everything the figures need, read from one output directory as adb-tradeoff wrote it:
    the figures draw these numbers and compute no rates of their own."""

    ERROR_LABEL = "wrong answers, %\nof queries with overlapping root boxes"

    def __init__(self, directory):
        self.dir = directory
        self.skipped_rows = 0
        # (model, triangles, Setting) -> {distance: Point}, or None without distances.csv
        self.per_distance = None
        self.references = set()  # what adb-tradeoff judged against: "exact", "fcl"
        self.summary = {}  # (model, triangles, Setting) -> SummaryRow
        self.cells = None  # (model, triangles) -> [count] * 512, or None without cells.csv
        # (model, triangles, Setting) -> [Bin] in bin order, or None without reliability.csv
        self.reliability = None

    # ---- distances.csv
    def read_distances(self):
        path = os.path.join(self.dir, "distances.csv")
        if not os.path.exists(path):
            return  # runs before distances.csv existed: the per-distance figures are skipped
        handle, reader, col = open_table(path, DISTANCE_COLUMNS)
        per_distance = defaultdict(dict)
        with handle:
            for cell in _table_rows(reader, col):
                if cell is None:  # e.g. the cut-off last line of an interrupted run
                    self.skipped_rows += 1
                    continue
                try:
                    key = _key(cell)
                    point = Point(int(float(cell["queries"])), _float(cell["mean_us"]),
                                  int(float(cell["overlapping"])), _float(cell["error_pct"]),
                                  _float(cell["mean_confidence"]))
                    per_distance[key][float(cell["distance"])] = point
                    if cell["reference"].strip():
                        self.references.add(cell["reference"].strip())
                except ValueError:
                    self.skipped_rows += 1
        if self.skipped_rows:
            print("note: %d malformed or truncated row(s) in distances.csv ignored"
                  % self.skipped_rows)
        self.per_distance = per_distance

    # ---- summary.csv
    def read_summary(self):
        path = os.path.join(self.dir, "summary.csv")
        handle, reader, col = open_table(path, SUMMARY_COLUMNS, SUMMARY_OPTIONAL)
        with handle:
            for cell in _table_rows(reader, col):
                try:
                    key = _key(cell)
                except (TypeError, ValueError):  # TypeError: a row cut short (None)
                    continue
                speedup = {peer: _float(cell["speedup_vs_" + peer]) for peer in PEERS}
                self.summary[key] = SummaryRow(_float(cell["mean_us"]), _float(cell["error_pct"]),
                                               _float(cell["mean_confidence"]), speedup,
                                               _float(cell.get("ece", "")))
        if not self.summary:  # a header and nothing else: the run stopped before a model ended
            print("note: summary.csv has no rows: no model finished")

    # ---- cells.csv
    def read_cells(self):
        path = os.path.join(self.dir, "cells.csv")
        if not os.path.exists(path) or os.path.getsize(path) == 0:
            return
        handle, reader, col = open_table(path, CELL_COLUMNS)
        cells = {}
        with handle:
            for row in reader:
                if len(row) < len(col):
                    continue
                try:
                    key = (row[col["model"]].strip(), int(float(row[col["triangles"]])))
                    index, count = int(float(row[col["cell"]])), float(row[col["count"]])
                except ValueError:
                    continue
                if 0 <= index < CELLS:
                    cells.setdefault(key, [0.0] * CELLS)[index] = count
        self.cells = cells

    # ---- reliability.csv
    def read_reliability(self):
        path = os.path.join(self.dir, "reliability.csv")
        if not os.path.exists(path) or os.path.getsize(path) == 0:
            return
        handle, reader, col = open_table(path, RELIABILITY_COLUMNS)
        bins = defaultdict(dict)  # key -> {bin index: Bin}
        with handle:
            for cell in _table_rows(reader, col):
                try:
                    key = _key(cell)
                    index, count = int(float(cell["bin"])), int(float(cell["count"]))
                    lo, hi = float(cell["bin_lo"]), float(cell["bin_hi"])
                except (TypeError, ValueError):  # TypeError: a row cut short (None)
                    continue
                bins[key][index] = Bin(lo, hi, count, _float(cell["mean_confidence"]),
                                       _float(cell["fraction_right"]))
        self.reliability = {key: [by_index[i] for i in sorted(by_index)]
                            for key, by_index in bins.items()}

    # ---- look-ups
    def _keys(self):
        return list(self.per_distance or {}) + list(self.summary)

    def models(self):
        return sorted({key[0] for key in self._keys()})

    def triangle_counts(self, model):
        return sorted({key[1] for key in self._keys() if key[0] == model})

    def settings(self, model=None):
        found = {key[2] for key in self._keys() if model is None or key[0] == model}
        return sorted(found, key=Setting.sort_key)

    def reference_label(self):
        """What adb-tradeoff judged against (distances.csv's reference column)."""
        if self.references == {"exact"}:
            return "reference: own exact tree"
        if self.references == {"fcl"}:
            return "reference: FCL (no exact rows)"
        return "reference: " + ", ".join(sorted(self.references)) if self.references else "no reference"


def load(directory):
    if not os.path.isdir(directory):
        raise InputError("%s: no such directory" % directory)
    data = Dataset(directory)
    data.read_distances()
    data.read_summary()
    data.read_cells()
    data.read_reliability()
    return data
