#!/usr/bin/env python3
"""Plots for the ADB-tree accuracy/time trade-off benchmark (`adb-tradeoff`).

Usage:
    plot_tradeoff.py DIR          read DIR/queries.csv (+ summary.csv, cells.csv,
                                  reliability.csv) and write the PNG figures listed in
                                  PLOTS into DIR
    plot_tradeoff.py --self-test  build a small synthetic DIR, plot it, check the result

What this file holds, top to bottom:
  * the expected CSV columns and a header-checking reader;
  * `Dataset`: per-distance aggregates of queries.csv (two passes, so memory stays small
    however many queries were run), the per-setting summary (summary.csv, or derived from
    queries.csv when that file is missing or empty), the Fig. 8 cell counts and the
    calibration bins (reliability.csv);
  * one function per figure (paper Figs. 8-11 plus budget, scaling, speed-up, reliability
    and error-against-time plots); each returns a matplotlib Figure, or a string saying
    why it was skipped;
  * `main` and the `--self-test` (synthetic data generator and checks).

The spec is docs/benchmark.md (the paper's Figs. 8-11).
"""

import argparse
import contextlib
import csv
import importlib.util
import io
import math
import os
import random
import subprocess
import sys
import tempfile
import textwrap
import traceback
from collections import defaultdict
from typing import NamedTuple, Optional


SYSTEM_PYTHON = "/usr/bin/python3"

# Bound by load_matplotlib() only when there is something to plot: importing matplotlib
# takes most of a second, and bad input should be reported without that wait.
plt = Line2D = NullFormatter = colormaps = HALO = None


def ensure_matplotlib():
    """Make sure this interpreter has matplotlib, without paying for the import yet.

    `python3` on PATH may be a private interpreter (pyenv, venv) without Debian's
    python3-matplotlib while /usr/bin/python3 has it; re-running under the system
    interpreter then beats failing. The environment flag stops a re-exec loop.
    """
    if importlib.util.find_spec("matplotlib") is not None:
        return
    if (os.environ.get("PLOT_TRADEOFF_REEXEC") != "1" and os.path.exists(SYSTEM_PYTHON)
            and os.path.realpath(sys.executable) != os.path.realpath(SYSTEM_PYTHON)):
        os.environ["PLOT_TRADEOFF_REEXEC"] = "1"
        sys.stdout.flush()
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, os.path.abspath(__file__)] + sys.argv[1:])
    sys.exit("plot_tradeoff: matplotlib is not installed for %s "
             "(Debian: apt-get install python3-matplotlib)" % sys.executable)


def load_matplotlib():
    """Import matplotlib with the headless Agg backend into this module's globals."""
    global plt, Line2D, NullFormatter, colormaps, HALO
    if plt is not None:
        return
    import matplotlib
    matplotlib.use("Agg")
    colormaps = matplotlib.colormaps
    from matplotlib import patheffects
    HALO = patheffects.withStroke(linewidth=2, foreground="white")
    import matplotlib.pyplot
    from matplotlib.lines import Line2D
    from matplotlib.ticker import NullFormatter
    plt = matplotlib.pyplot


# --------------------------------------------------------------------------- inputs

QUERY_COLUMNS = (
    "model", "triangles", "method", "p_min", "k_min", "budget_us", "distance", "rotation",
    "a_qw", "a_qx", "a_qy", "a_qz", "a_tx", "a_ty", "a_tz",
    "b_qw", "b_qx", "b_qy", "b_qz", "b_tx", "b_ty", "b_tz",
    "collides", "confidence", "time_ns", "node_pairs")
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
WORK_PREFIX = "adb-work:"  # queries.csv names ADB under a work budget of N pairs adb-work:N
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


class Acc:
    """Running sums for one group of query rows."""
    __slots__ = ("n", "time_us", "conf_sum", "conf_n", "judged", "wrong")

    def __init__(self):
        self.n = self.conf_n = self.judged = self.wrong = 0
        self.time_us = self.conf_sum = 0.0

    def mean_us(self):
        return self.time_us / self.n if self.n else None

    def error_pct(self):
        return 100.0 * self.wrong / self.judged if self.judged else None


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
    """Everything the figures need, read from one output directory."""

    def __init__(self, directory):
        self.dir = directory
        self.skipped_rows = 0
        # (model, triangles, Setting) -> {distance: Acc}
        self.per_distance = defaultdict(lambda: defaultdict(Acc))
        self.reference_methods = set()
        self.summary = {}  # (model, triangles, Setting) -> SummaryRow
        self.summary_error_label = ""
        self.cells = None  # (model, triangles) -> [count] * 512, or None without cells.csv
        # (model, triangles, Setting) -> [Bin] in bin order, or None without reliability.csv
        self.reliability = None

    # ---- queries.csv
    def read_queries(self):
        path = os.path.join(self.dir, "queries.csv")
        reference = self._reference_answers(path)
        handle, reader, col = open_table(path, QUERY_COLUMNS)
        width = max(col.values()) + 1
        group_cols = [col[name] for name in
                      ("model", "triangles", "method", "p_min", "k_min", "budget_us", "distance")]
        pose_cols = [col[name] for name in ("model", "triangles", "distance", "rotation")]
        i_collides, i_time, i_conf = col["collides"], col["time_ns"], col["confidence"]
        # Keyed by the raw text of the grouping cells, so each group is parsed once rather
        # than once per row: real runs have millions of rows and few groups.
        groups = {}
        with handle:
            for row in reader:
                if len(row) < width:  # e.g. the cut-off last line of an interrupted run
                    self.skipped_rows += bool(row)
                    continue
                raw = tuple(row[i] for i in group_cols)
                acc = groups.get(raw)
                try:
                    if acc is None:
                        acc = groups[raw] = self._group(raw)
                    collides = float(row[i_collides]) != 0
                    time_ns = float(row[i_time])
                except ValueError:
                    self.skipped_rows += 1
                    continue
                acc.n += 1
                acc.time_us += time_ns / 1000.0
                confidence = _float(row[i_conf])
                if confidence is not None:
                    acc.conf_sum += confidence
                    acc.conf_n += 1
                truth = reference.get("\x1f".join([row[i] for i in pose_cols]))
                if truth is not None:
                    acc.judged += 1
                    acc.wrong += collides != truth
        if self.skipped_rows:
            print("note: %d malformed or truncated row(s) in queries.csv ignored"
                  % self.skipped_rows)

    def _group(self, raw):
        """The Acc for one (model, triangles, setting, distance); ValueError if unparsable."""
        model, triangles, method, p_min, k_min, budget, distance = raw
        setting = _setting(method, p_min, k_min, budget)
        return self.per_distance[(model.strip(), int(float(triangles)), setting)][float(distance)]

    def _reference_answers(self, path):
        """First pass: the exact answer per pose (own exact tree, else FCL)."""
        answers = {"exact": {}, "fcl": {}}
        handle, reader, col = open_table(path, QUERY_COLUMNS)
        width = max(col.values()) + 1
        pose_cols = [col[name] for name in ("model", "triangles", "distance", "rotation")]
        i_method, i_collides = col["method"], col["collides"]
        with handle:
            for row in reader:
                if len(row) < width:
                    continue
                method = row[i_method].strip().lower()
                if method in answers:
                    collides = _float(row[i_collides])
                    if collides is not None:
                        # The tool writes a pose with the same text for every method, so the
                        # raw cells identify it; parsing could only add rounding mismatches.
                        # One joined string per pose keeps the table small on big runs.
                        answers[method]["\x1f".join([row[i] for i in pose_cols])] = collides != 0
        merged, fcl = answers["exact"], answers["fcl"]
        self.reference_methods = {"exact"} if merged else set()
        for pose, answer in fcl.items():
            if pose not in merged:  # exact wins where both answered
                merged[pose] = answer
                self.reference_methods.add("fcl")
        return merged

    # ---- summary.csv (or derived from queries.csv)
    def read_summary(self):
        path = os.path.join(self.dir, "summary.csv")
        if not os.path.exists(path) or os.path.getsize(path) == 0:
            self._summary_from_queries("no summary.csv")
            return
        handle, reader, col = open_table(path, SUMMARY_COLUMNS, SUMMARY_OPTIONAL)
        width = max(col.values()) + 1
        with handle:
            for record in reader:
                if len(record) < width:
                    continue
                cell = {name: record[index] for name, index in col.items()}
                try:
                    setting = _setting(cell["method"], cell["p_min"], cell["k_min"],
                                       cell["budget_us"])
                    key = (cell["model"].strip(), int(float(cell["triangles"])), setting)
                except ValueError:
                    continue
                speedup = {peer: _float(cell["speedup_vs_" + peer]) for peer in PEERS}
                self.summary[key] = SummaryRow(_float(cell["mean_us"]), _float(cell["error_pct"]),
                                               _float(cell["mean_confidence"]), speedup,
                                               _float(cell.get("ece", "")))
        if not self.summary:  # a header and nothing else: the run stopped before summing up
            self._summary_from_queries("summary.csv has no rows")
            return
        self.summary_error_label = "wrong answers, %\nof queries with overlapping root boxes"
        self._fill_speedups()

    def _summary_from_queries(self, why):
        print("note: %s; summary figures use queries.csv, whose error rate counts all "
              "queries rather than only those with overlapping root boxes" % why)
        for key, by_distance in self.per_distance.items():
            total = Acc()
            for acc in by_distance.values():
                for name in Acc.__slots__:
                    setattr(total, name, getattr(total, name) + getattr(acc, name))
            confidence = total.conf_sum / total.conf_n if total.conf_n else None
            self.summary[key] = SummaryRow(total.mean_us(), total.error_pct(), confidence,
                                           {peer: None for peer in PEERS})
        self.summary_error_label = "wrong answers, % of all queries"
        self._fill_speedups()

    def _fill_speedups(self):
        """Fill empty speed-up cells from the mean times of the same model and size."""
        for (model, triangles, setting), row in list(self.summary.items()):
            for peer in PEERS:
                if row.speedup.get(peer) is not None or row.mean_us is None or row.mean_us <= 0:
                    continue
                other = self.summary.get((model, triangles, Setting(peer)))
                if other is not None and other.mean_us:
                    row.speedup[peer] = other.mean_us / row.mean_us

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
            for row in reader:
                if len(row) < len(col):
                    continue
                cell = {name: row[index] for name, index in col.items()}
                try:
                    setting = _setting(cell["method"], cell["p_min"], cell["k_min"],
                                       cell["budget_us"])
                    key = (cell["model"].strip(), int(float(cell["triangles"])), setting)
                    index, count = int(float(cell["bin"])), int(float(cell["count"]))
                    lo, hi = float(cell["bin_lo"]), float(cell["bin_hi"])
                except ValueError:
                    continue
                bins[key][index] = Bin(lo, hi, count, _float(cell["mean_confidence"]),
                                       _float(cell["fraction_right"]))
        self.reliability = {key: [by_index[i] for i in sorted(by_index)]
                            for key, by_index in bins.items()}

    # ---- look-ups
    def models(self):
        return sorted({key[0] for key in self.per_distance} | {key[0] for key in self.summary})

    def triangle_counts(self, model):
        return sorted({key[1] for key in list(self.per_distance) + list(self.summary)
                       if key[0] == model})

    def settings(self, model=None):
        keys = list(self.per_distance) + list(self.summary)
        found = {key[2] for key in keys if model is None or key[0] == model}
        return sorted(found, key=Setting.sort_key)

    def reference_label(self):
        if self.reference_methods == {"exact"}:
            return "reference: own exact tree"
        if self.reference_methods == {"fcl"}:
            return "reference: FCL (no exact rows)"
        return "reference: own exact tree, FCL where exact is missing"


def load(directory):
    if not os.path.isdir(directory):
        raise InputError("%s: no such directory" % directory)
    data = Dataset(directory)
    data.read_queries()
    data.read_summary()
    data.read_cells()
    data.read_reliability()
    return data


# --------------------------------------------------------------------------- figure helpers

def featured_adb(settings, cap):
    """The ADB settings without budget worth a line when there are too many for one plot.

    The paper's default first, then the two contrasts the paper (section 8) quotes (a
    smaller k_min at the same p_min, a smaller p_min at the same k_min), then the rest.
    """
    pool = [s for s in settings if s.method == "adb" and s.budget_us is None]
    if len(pool) <= cap:
        return pool
    default = next((s for s in pool if (s.p_min, s.k_min) == DEFAULT_ADB), None)
    if default is None:
        default = max(pool, key=lambda s: (s.k_min, s.p_min))
    same_p = [s for s in pool if s.p_min == default.p_min and s != default]
    same_k = [s for s in pool if s.k_min == default.k_min and s != default]
    chosen = [default]
    if same_p:
        chosen.append(min(same_p, key=lambda s: s.k_min))
    if same_k:
        chosen.append(min(same_k, key=lambda s: s.p_min))
    chosen += [s for s in pool if s not in chosen]
    return sorted(chosen[:cap], key=Setting.sort_key)


def colour_map(settings):
    """Stable colours: fixed ones for the peers, a palette for the ADB settings."""
    colours, adb_index = {}, 0
    # The paper's default setting takes the first palette colour in every figure.
    ordered = sorted(settings, key=lambda s: (s.method == "adb", (s.p_min, s.k_min) != DEFAULT_ADB))
    for setting in ordered:
        if setting.method in PEER_COLOURS:
            colours[setting] = PEER_COLOURS[setting.method]
        else:
            colours[setting] = ADB_COLOURS[adb_index % len(ADB_COLOURS)]
            adb_index += 1
    return colours


def subplot_grid(count, width=5.2, height=3.8, columns=None):
    columns = columns or min(count, 3)
    rows = math.ceil(count / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(width * columns, height * rows),
                             squeeze=False, layout="constrained")
    flat = [ax for line in axes for ax in line]
    for ax in flat[count:]:
        ax.set_visible(False)
    return fig, flat[:count]


def wrap_to_figure(fig, text, points):
    """`text` wrapped to the figure's width at a font of `points` size.

    The layout engines do not fit a figure title into the figure, so a long one overran
    narrow (one-panel) figures. DejaVu Sans averages under 0.6 em per character.
    """
    return textwrap.fill(text, max(20, int(fig.get_figwidth() * 72 / (0.6 * points))))


def fit_suptitle(fig, text):
    fig.suptitle(wrap_to_figure(fig, text, 12))  # suptitle's default size is "large", 12 pt


def log_if_wide(ax, values, axis="y"):
    """Log scale when positive values span more than about a decade."""
    values = [v for v in values if v is not None and v > 0]
    if values and max(values) / min(values) > 20:
        (ax.set_yscale if axis == "y" else ax.set_xscale)("log")


def pmin_scale(ax, values):
    # p_min values like 0.5, 0.9, 0.99, 0.999 crowd at 1 on a linear axis; a logit axis
    # spaces them evenly. It is undefined at 0 and 1, so fall back to linear there.
    if values and all(0 < v < 1 for v in values) and max(values) > 0.95:
        ax.set_xscale("logit")
        ax.set_xticks(sorted(set(values)))
        ax.set_xticklabels(["%g" % v for v in sorted(set(values))])
        ax.minorticks_off()


def set_value_ticks(ax, values, form="{:g}"):
    """Ticks at the measured x values (budgets, sizes), readable on a log axis too."""
    values = sorted(set(values))
    if values:
        ax.set_xticks(values)
        ax.set_xticklabels([form.format(v) for v in values])
        ax.xaxis.set_minor_formatter(NullFormatter())  # log axes would add 2x10^1-style labels


def triangle_legend(ax, counts):
    styles = [TRIANGLE_STYLES[i % len(TRIANGLE_STYLES)] for i in range(len(counts))]
    handles = [Line2D([], [], color="dimgray", linestyle=style, marker=marker, markersize=4,
                      label="%s triangles" % format(t, ","))
               for (style, marker), t in zip(styles, counts)]
    ax.legend(handles=handles, fontsize="small", loc="best", framealpha=0.8)


def setting_legend(fig, settings, colours, title=None):
    handles = [Line2D([], [], color=colours[s], linewidth=line_width(s) + 0.4, label=s.label())
               for s in settings]
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5),
               fontsize="small", title=title, frameon=False)


def largest_size(data, model):
    counts = data.triangle_counts(model)
    return counts[-1] if counts else None


def summary_value(data, model, triangles, setting, field):
    row = data.summary.get((model, triangles, setting))
    return getattr(row, field) if row is not None else None


def line_width(setting):
    # The paper's headline ADB setting is the line readers look for first.
    return 2.6 if setting.method == "adb" and (setting.p_min, setting.k_min) == DEFAULT_ADB \
        and setting.budget_us is None else 1.4


def per_distance_lines(data, model, setting, value, ax, colour):
    """Plot one line per triangle count of `value(acc)` against distance; return the y values."""
    plotted = []
    for rank, triangles in enumerate(data.triangle_counts(model)):
        series = data.per_distance.get((model, triangles, setting))
        if not series:
            continue
        points = [(d, value(acc)) for d, acc in sorted(series.items())]
        points = [(d, v) for d, v in points if v is not None]
        if not points:
            continue
        style, marker = TRIANGLE_STYLES[rank % len(TRIANGLE_STYLES)]
        ax.plot([p[0] for p in points], [p[1] for p in points], color=colour, linestyle=style,
                marker=marker, markersize=3.5, linewidth=line_width(setting))
        plotted += [p[1] for p in points]
    return plotted


# --------------------------------------------------------------------------- figures

def plot_time_vs_distance(data):
    """Paper Fig. 9: mean time per query against the distance of the two copies."""
    models = data.models()
    if not data.per_distance:
        return "queries.csv has no usable rows"
    every = data.settings()
    # Only the peers beside ADB: the baselines' budgets would bury the ADB lines.
    shown = [s for s in every if s.method in PEERS] + featured_adb(every, cap=4)
    colours = colour_map(shown)
    fig, axes = subplot_grid(len(models))
    for ax, model in zip(axes, models):
        values = []
        for setting in shown:
            values += per_distance_lines(data, model, setting, Acc.mean_us, ax, colours[setting])
        log_if_wide(ax, values)
        ax.set_title(model)
        ax.set_xlabel("distance of box centres (units of half the largest box edge)")
        ax.set_ylabel("mean time per query (µs)")
        ax.grid(True, which="both", alpha=0.3)
        triangle_legend(ax, data.triangle_counts(model))
    fit_suptitle(fig, "Query time vs distance (paper Fig. 9)")
    setting_legend(fig, shown, colours)
    return fig


def plot_error_vs_distance(data):
    """Paper Fig. 10: how often ADB answers wrongly, per distance."""
    # queries.csv does not say whether the two root boxes overlap (that needs the meshes),
    # so the per-distance rate here divides by all queries at that distance; the summary
    # figures use summary.csv's error_pct, which does count only overlapping queries.
    if not data.reference_methods:
        return "no exact or fcl rows to judge answers against"
    every = [s for s in data.settings() if s.method == "adb"]
    shown = featured_adb(every, cap=4)  # error curves are noisy: more lines stop being readable
    if not shown:
        return "no ADB rows without a time budget"
    colours = colour_map(shown)
    models = [m for m in data.models() if any(s.method == "adb" for s in data.settings(m))]
    fig, axes = subplot_grid(len(models))
    for ax, model in zip(axes, models):
        for setting in shown:
            per_distance_lines(data, model, setting, Acc.error_pct, ax, colours[setting])
        ax.set_title(model)
        ax.set_xlabel("distance of box centres (units of half the largest box edge)")
        ax.set_ylabel("wrong answers, %\nof queries at this distance")
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
        triangle_legend(ax, data.triangle_counts(model))
    fit_suptitle(fig, "ADB error vs distance (paper Fig. 10; %s)" % data.reference_label())
    setting_legend(fig, shown, colours)
    return fig


def _adb_grid(data, model, triangles):
    """{(p_min, k_min): SummaryRow} of the ADB settings without budget."""
    return {(s.p_min, s.k_min): row for (m, t, s), row in data.summary.items()
            if m == model and t == triangles and s.method == "adb" and s.budget_us is None}


def _lines_over(ax, grid, x_index, field, line_label):
    """One line per value of the other parameter, `field` against parameter x_index."""
    others = sorted({key[1 - x_index] for key in grid})
    for i, other in enumerate(others):
        points = sorted((key[x_index], getattr(row, field)) for key, row in grid.items()
                        if key[1 - x_index] == other and getattr(row, field) is not None)
        if points:
            ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", markersize=4,
                    color=ADB_COLOURS[i % len(ADB_COLOURS)], label=line_label % other)
    ax.margins(y=0.2)  # head room for a one-row legend, so it need not sit on a line
    ax.legend(fontsize="small", loc="upper center", ncol=min(len(others), 4))
    ax.grid(True, which="both", alpha=0.3)


def plot_pmin_kmin(data):
    """Paper Fig. 11: time and error against p_min (per k_min), time against k_min (per p_min)."""
    models = []
    for model in data.models():
        grid = _adb_grid(data, model, largest_size(data, model))
        if len({k[0] for k in grid}) > 1 or len({k[1] for k in grid}) > 1:
            models.append(model)
    if not models:
        return "no model has more than one p_min or k_min (without budget)"
    fig, axes = plt.subplots(len(models), 3, figsize=(15, 3.9 * len(models)), squeeze=False,
                             layout="constrained")
    for line, model in zip(axes, models):
        triangles = largest_size(data, model)
        grid = _adb_grid(data, model, triangles)
        p_values = sorted({k[0] for k in grid})
        k_values = sorted({k[1] for k in grid})
        title = "%s (%s triangles)" % (model, format(triangles, ","))
        time_label, error_label = "mean time per query (µs)", data.summary_error_label
        panels = ((line[0], 0, "mean_us", "k_min = %d", time_label, "time vs p_min"),
                  (line[1], 0, "error_pct", "k_min = %d", error_label, "error vs p_min"),
                  (line[2], 1, "mean_us", "p_min = %g", time_label, "time vs k_min"))
        for ax, x_index, field, line_label, y_label, what in panels:
            x_values = p_values if x_index == 0 else k_values
            ax.set_title("%s: %s" % (title, what), fontsize="medium")
            if len(x_values) < 2:
                ax.text(0.5, 0.5, "only one %s value" % ("p_min" if x_index == 0 else "k_min"),
                        ha="center", va="center", transform=ax.transAxes)
                continue
            _lines_over(ax, grid, x_index, field, line_label)
            ax.set_xlabel("p_min" if x_index == 0 else "k_min")
            if x_index == 1:
                ax.set_xticks(k_values)
            ax.set_ylabel(y_label)
            if x_index == 0:
                pmin_scale(ax, p_values)
            if field == "error_pct":
                ax.set_ylim(bottom=0)
    fit_suptitle(fig, "ADB parameters: time and error (paper Fig. 11; no time budget)")
    return fig


def _time_budget_bases(data, model, triangles):
    """The (p_min, k_min) pairs of `model` run under at least one ADB time budget."""
    return {(s.p_min, s.k_min) for (m, t, s) in data.summary
            if m == model and t == triangles and s.method == "adb" and s.budget_us is not None}


def base_colours(bases):
    """One palette colour per (p_min, k_min), the paper's default first, shared by all panels."""
    ordered = sorted(bases, key=lambda base: (base != DEFAULT_ADB, base[1], base[0]))
    return {base: ADB_COLOURS[i % len(ADB_COLOURS)] for i, base in enumerate(ordered)}


def base_label(base):
    return "p_min=%g k_min=%d" % base


def plot_error_vs_budget(data):
    """The quality a given time budget buys: error, confidence and actual time per budget."""
    bases_of = {m: _time_budget_bases(data, m, largest_size(data, m)) for m in data.models()}
    models = [m for m in data.models() if bases_of[m]]
    if not models:
        return "no ADB rows with a time budget"
    colours = base_colours(set().union(*bases_of.values()))
    fig, axes = plt.subplots(len(models), 3, figsize=(15, 3.9 * len(models)), squeeze=False,
                             layout="constrained")
    for line, model in zip(axes, models):
        triangles = largest_size(data, model)
        rows = {s: r for (m, t, s), r in data.summary.items()
                if m == model and t == triangles and s.method == "adb"}
        panels = ((line[0], "error_pct", data.summary_error_label, "error"),
                  (line[1], "mean_confidence", "mean confidence", "mean confidence"),
                  (line[2], "mean_us", "mean time per query (µs)", "actual time"))
        budgets_all = [s.budget_us for s in rows if s.budget_us is not None]
        for ax, field, y_label, what in panels:
            for base in sorted(bases_of[model]):
                colour = colours[base]
                points = sorted((s.budget_us, getattr(r, field)) for s, r in rows.items()
                                if (s.p_min, s.k_min) == base and s.budget_us is not None
                                and getattr(r, field) is not None)
                ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", markersize=4,
                        color=colour)
                free = rows.get(Setting("adb", *base))
                if free is not None and getattr(free, field) is not None:
                    # The same setting without budget: what the budget converges to.
                    ax.axhline(getattr(free, field), color=colour, linestyle="--", linewidth=1)
            if field == "mean_us":
                span = [min(budgets_all), max(budgets_all)]
                ax.plot(span, span, color="gray", linestyle=":")
            log_if_wide(ax, budgets_all, axis="x")
            set_value_ticks(ax, budgets_all)
            if field == "mean_us":
                log_if_wide(ax, budgets_all, axis="y")
            if field == "error_pct":
                ax.set_ylim(bottom=0)
            ax.set_xlabel("time budget per query (µs)")
            ax.set_ylabel(y_label)
            ax.set_title("%s (%s triangles): %s" % (model, format(triangles, ","), what),
                         fontsize="medium")
            ax.grid(True, which="both", alpha=0.3)
    # One legend for all panels, beside them: inside, nine settings covered the curves.
    handles = [Line2D([], [], color=colour, marker="o", markersize=4, label=base_label(base))
               for base, colour in colours.items()]
    handles += [Line2D([], [], color="dimgray", linestyle="--", label="the same, no budget"),
                Line2D([], [], color="gray", linestyle=":", label="time = budget")]
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5),
               fontsize="small", frameon=False)
    fit_suptitle(fig, "ADB under a time budget (dashed: the same setting without budget)")
    return fig


def plot_time_vs_triangles(data):
    """Does the cost stay flat as meshes grow? Mean time against triangle count."""
    models = [m for m in data.models() if len(data.triangle_counts(m)) > 1]
    if not models:
        return "every model was run at a single triangle count"
    every = data.settings()
    # Only the peers beside ADB: the baselines' budgets would bury the ADB lines.
    shown = [s for s in every if s.method in PEERS] + featured_adb(every, cap=4)
    colours = colour_map(shown)
    fig, axes = subplot_grid(len(models))
    for ax, model in zip(axes, models):
        for setting in shown:
            points = [(t, summary_value(data, model, t, setting, "mean_us"))
                      for t in data.triangle_counts(model)]
            points = [p for p in points if p[1] is not None]
            if points:
                ax.plot([p[0] for p in points], [p[1] for p in points], marker="o",
                        markersize=4, color=colours[setting], linewidth=line_width(setting))
        ax.set_xscale("log")
        ax.set_yscale("log")
        set_value_ticks(ax, data.triangle_counts(model), "{:,.0f}")
        ax.set_title(model)
        ax.set_xlabel("triangles per object")
        ax.set_ylabel("mean time per query (µs)")
        ax.grid(True, which="both", alpha=0.3)
    fit_suptitle(fig, "Query time vs mesh size (all distances)")
    setting_legend(fig, shown, colours)
    return fig


def plot_cells_histogram(data):
    """Paper Fig. 8: how evenly possible collision cells spread over the 512 cell indices."""
    if data.cells is None:
        return "no cells.csv"
    keys = sorted(k for k, counts in data.cells.items() if sum(counts) > 0)
    if not keys:
        return "cells.csv has no counts"
    fig, axes = subplot_grid(len(keys), width=6.0, height=3.4, columns=min(len(keys), 2))
    for ax, key in zip(axes, keys):
        counts = data.cells[key]
        mean = sum(counts) / CELLS
        ratios = [c / mean for c in counts]
        high, low = max(ratios), min(ratios)
        print("cells %s (%s triangles): max/mean %.2f (%+.0f %%), min/mean %.2f (%+.0f %%)" % (
            key[0], format(key[1], ","), high, 100 * (high - 1), low, 100 * (low - 1)))
        # One stairs artist instead of 512 bars: same picture, a fraction of the drawing time.
        ax.stairs(ratios, [i - 0.5 for i in range(CELLS + 1)], fill=True, color="tab:blue")
        ax.axhline(1.0, color="black", linewidth=1, linestyle="--")
        ax.set_xlim(-0.5, CELLS - 0.5)
        ax.set_xticks(range(0, CELLS + 1, 64))
        ax.set_ylim(0, max(1.5, high * 1.15))
        ax.set_title("%s (%s triangles)" % (key[0], format(key[1], ",")))
        ax.set_xlabel("cell index in the 8×8×8 grid")
        ax.set_ylabel("count / mean count")
        ax.text(0.99, 0.97, "max/mean %.2f   min/mean %.2f" % (high, low), ha="right", va="top",
                transform=ax.transAxes, fontsize="small",
                bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
    fit_suptitle(fig, "Possible collision cells per cell index, all tree nodes "
                 "(paper Fig. 8; 1.0 = uniform)")
    return fig


def plot_speedup(data):
    """Speed-up of each ADB setting against each peer, per model (largest size)."""
    models, peers = [], []
    for model in data.models():
        triangles = largest_size(data, model)
        rows = [r for (m, t, s), r in data.summary.items()
                if m == model and t == triangles and s.method == "adb"]
        found = [p for p in PEERS if any(r.speedup.get(p) for r in rows)]
        if found:
            models.append(model)
            peers += [p for p in found if p not in peers]
    if not models:
        return "no speed-ups (summary has no ADB rows with a peer to compare with)"
    peers = [p for p in PEERS if p in peers]
    fig, axes = subplot_grid(len(models), width=6.4, height=4.4, columns=min(len(models), 2))
    for ax, model in zip(axes, models):
        triangles = largest_size(data, model)
        settings = [s for s in data.settings(model) if s.method == "adb"]
        shown = featured_adb(settings, cap=10)
        width = 0.8 / len(peers)
        for i, peer in enumerate(peers):
            values = [summary_value(data, model, triangles, s, "speedup") or {} for s in shown]
            heights = [v.get(peer) or 0.0 for v in values]
            positions = [j + (i - (len(peers) - 1) / 2) * width for j in range(len(shown))]
            # Bars grow from 1 (no speed-up), so being slower than a peer points down.
            bars = ax.bar(positions, [h - 1.0 if h else 0.0 for h in heights], bottom=1.0,
                          width=width, color=PEER_COLOURS[peer])
            ax.bar_label(bars, labels=["%.2g" % h if h else "" for h in heights],
                         fontsize=6.5, padding=1)
        ax.axhline(1.0, color="gray", linewidth=1)
        ax.set_xticks(range(len(shown)))
        margin = 0.5 + max(0, 3 - len(shown)) / 2  # keep one or two groups from filling the axes
        ax.set_xlim(-margin, len(shown) - 1 + margin)
        ax.set_xticklabels(["p=%g\nk=%d" % (s.p_min, s.k_min) for s in shown], fontsize="small")
        ax.set_yscale("log")  # speed-ups below and above 1 read symmetrically
        ax.set_ylabel("speed-up (peer time / ADB time)")
        ax.set_title("%s (%s triangles)" % (model, format(triangles, ",")))
        ax.grid(True, axis="y", which="both", alpha=0.3)
    # One legend beside the panels: inside, it sat on the tallest (GImpact) bars.
    handles = [Line2D([], [], color=PEER_COLOURS[p], linewidth=6, label="vs " + PEER_LABELS[p])
               for p in peers]
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5),
               fontsize="small", frameon=False)
    fit_suptitle(fig, "Speed-up of ADB (no budget) over the exact methods "
                 "(mean time, all distances)")
    if "gimpact" in peers:
        caption = ("GImpact builds the full contact set (what Bullet's dynamics needs) rather "
                   "than a yes/no answer, so the speed-up against it is not like for like.")
        fig.supxlabel(wrap_to_figure(fig, caption, 9), fontsize=9, style="italic")
    return fig


def _usable(bins):
    return [b for b in bins if b.count and b.confidence is not None and b.right is not None]


def ece_from_bins(bins):
    """Expected calibration error: the count-weighted mean |confidence - fraction right|."""
    used = _usable(bins)
    total = sum(b.count for b in used)
    return sum(b.count * abs(b.confidence - b.right) for b in used) / total if total else None


def _reliability_base(settings):
    """The (p_min, k_min) whose budget curves the reliability panels show.

    Every p_min/k_min times every budget would be dozens of lines, so one setting: the
    paper's default when it was run, else the one with the most budgets.
    """
    counts = defaultdict(int)
    for s in settings:
        if s.method in ("adb", "adb-work"):
            counts[(s.p_min, s.k_min)] += 1
    if not counts:
        return None
    return DEFAULT_ADB if DEFAULT_ADB in counts else max(counts, key=lambda b: (counts[b], b))


def budget_colours(settings):
    """Sequential colours by budget: Blues for time budgets, Oranges for work budgets.

    The two budgets have different units, hence two colour maps; "no budget" is the dark
    end of the time budgets, being their limit. Colours go by rank, as budgets are spread
    over decades.
    """
    time = sorted((s for s in settings if s.method == "adb"),
                  key=lambda s: (s.budget_us is None, s.budget_us or 0.0))
    work = sorted((s for s in settings if s.method == "adb-work"), key=lambda s: s.work)
    colours = {}
    for group, name in ((time, "Blues"), (work, "Oranges")):
        for i, s in enumerate(group):
            colours[s] = colormaps[name](0.4 + 0.55 * i / max(1, len(group) - 1))
    return colours


def budget_label(setting):
    if setting.method == "adb-work":
        return "work budget %d node pairs" % setting.work
    if setting.budget_us is None:
        return "no budget"
    return "time budget %g µs" % setting.budget_us


def reliability_axes(count):
    """Per panel a square-ish diagram with a short count strip under it, sharing x."""
    columns = min(count, 2)
    rows = math.ceil(count / columns)
    fig = plt.figure(figsize=(5.0 * columns, 5.6 * rows), layout="constrained")
    grid = fig.add_gridspec(2 * rows, columns, height_ratios=[4, 1] * rows)
    pairs = []
    for i in range(count):
        row, column = divmod(i, columns)
        main = fig.add_subplot(grid[2 * row, column])
        pairs.append((main, fig.add_subplot(grid[2 * row + 1, column], sharex=main)))
    return fig, pairs


def _reliability_panel(ax, strip, groups, shown, colours, ece):
    """Draw one model's diagram: diagonal, the budget curves thin, the pooled curve bold."""
    ax.plot([0, 1], [0, 1], color="gray", linestyle="--", linewidth=1)
    for setting in shown:
        used = _usable(groups[setting])
        total = sum(b.count for b in used)
        x, y = [b.confidence for b in used], [b.right for b in used]
        style = "--" if setting.method == "adb-work" else "-"
        ax.plot(x, y, color=colours[setting], linestyle=style, linewidth=1.1)
        # Marker area by the bin's share of this setting's queries: a lone query in a bin
        # should not read like a thousand.
        ax.scatter(x, y, s=[4 + 60 * b.count / total for b in used], color=colours[setting],
                   zorder=3)
    pooled = _usable(groups.get(Setting(POOLED), []))
    handles = [Line2D([], [], color="gray", linestyle="--", label="perfect calibration")]
    if pooled:
        label = "ADB, all settings pooled" + ("" if ece is None else " (ECE %.3f)" % ece)
        handles += ax.plot([b.confidence for b in pooled], [b.right for b in pooled],
                           color="black", linewidth=2.6, marker="o", markersize=4, zorder=4,
                           label=label)
        # Counts span decades (most answers are confident), hence a log strip.
        strip.bar([(b.lo + b.hi) / 2 for b in pooled], [b.count for b in pooled],
                  width=[0.9 * (b.hi - b.lo) for b in pooled], color="black")
        strip.set_yscale("log")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.02)
    ax.set_ylabel("fraction of right answers")
    ax.grid(True, alpha=0.3)
    ax.tick_params(labelbottom=False)
    strip.set_xlabel("confidence (the method's own estimate)")
    strip.set_ylabel("queries\n(pooled)")
    strip.grid(True, axis="y", alpha=0.3)
    # Under the strip, not in the diagram: any corner of it may hold points.
    strip.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.55), ncol=2,
                 fontsize="small", frameon=False)


def plot_reliability(data):
    """Is ADB's confidence right? Confidence against the fraction of right answers, binned."""
    if data.reliability is None:
        return "no reliability.csv (written by newer adb-tradeoff runs)"
    sizes = defaultdict(set)
    for model, triangles, _ in data.reliability:
        sizes[model].add(triangles)
    keys = [(model, max(sizes[model])) for model in sorted(sizes)]
    groups_of = {key: {s: bins for (m, t, s), bins in data.reliability.items() if (m, t) == key}
                 for key in keys}
    keys = [key for key in keys if any(_usable(b) for b in groups_of[key].values())]
    if not keys:
        return "reliability.csv has no filled bins"
    base = _reliability_base(s for groups in groups_of.values() for s in groups)
    every = {s for groups in groups_of.values() for s in groups
             if s.method in ("adb", "adb-work") and (s.p_min, s.k_min) == base}
    colours = budget_colours(every)
    fig, pairs = reliability_axes(len(keys))
    for (ax, strip), key in zip(pairs, keys):
        groups = groups_of[key]
        pooled = groups.get(Setting(POOLED), [])
        ece = summary_value(data, key[0], key[1], Setting(POOLED), "ece")
        if ece is None:  # the summary's figure when it has one, so plot and table agree
            ece = ece_from_bins(pooled)
        shown = sorted((s for s in groups if s in colours), key=Setting.sort_key)
        _reliability_panel(ax, strip, groups, shown, colours, ece)
        title = "%s (%s triangles)" % (key[0], format(key[1], ","))
        ax.set_title(title + ("" if ece is None else ": pooled ECE %.3f" % ece))
    ordered = sorted(colours, key=lambda s: (s.method, s.budget_us is None, s.budget_us or 0,
                                             s.work or 0))
    handles = [Line2D([], [], color=colours[s], linestyle="--" if s.method == "adb-work" else "-",
                      marker="o", markersize=4, label=budget_label(s)) for s in ordered]
    if handles:
        fig.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5),
                   fontsize="small", frameon=False,
                   title="ADB %s, by budget" % base_label(base))
    fit_suptitle(fig, "Reliability of ADB's confidence (marker area: the bin's share of "
                 "the setting's queries)")
    return fig


# Pareto figure styles: (colour, line style, marker) of the baselines drawn as curves, and
# (colour, marker, label) of the methods that are single points.
BASELINE_CURVES = {"exact-cut": ("black", ":", "x"), "box-first": ("teal", "-.", "^")}
SINGLE_POINTS = {"root-boxes": ("dimgray", "*", "root boxes"),
                 "exact": (PEER_COLOURS["exact"], "o", "exact"),
                 "fcl": (PEER_COLOURS["fcl"], "X", "FCL"),
                 "gimpact": (PEER_COLOURS["gimpact"], "P", "GImpact")}
ERROR_TICKS = (0, 0.5, 1, 2, 5, 10, 20, 50, 100)


def _curve(ax, rows, colour, style, marker, width=1.2, alpha=1.0):
    """A line through the (mean time, error) of `rows`, in the order given (by budget)."""
    points = [(r.mean_us, r.error_pct) for r in rows
              if r.mean_us is not None and r.error_pct is not None]
    if points:
        ax.plot([p[0] for p in points], [p[1] for p in points], color=colour, linestyle=style,
                marker=marker, markersize=5 if width > 2 else 4, linewidth=width, alpha=alpha)
    return points


def _budget_labels(ax, rows, settings, colour):
    """Name the budget at each point of a curve (only the paper's setting: all would clutter)."""
    for s in settings:
        row = rows[s]
        # Time budgets labelled right of their points, work budgets left: the two curves
        # run close together. The white halo keeps a label readable across other lines.
        timed = s.work is None
        ax.annotate("%g µs" % s.budget_us if timed else "%d pairs" % s.work,
                    (row.mean_us, row.error_pct), xytext=(5 if timed else -5, -2),
                    textcoords="offset points", fontsize=6.5, color=colour, va="top",
                    ha="left" if timed else "right", path_effects=[HALO])


def _pareto_adb(ax, rows, colours):
    """ADB's families: time-budget and work-budget curves per setting, unbudgeted points."""
    for base, colour in colours.items():
        default = base == DEFAULT_ADB
        # The paper's setting bold, the others thin and a little faded behind it.
        width, alpha = (2.6, 1.0) if default else (1.1, 0.75)
        timed = sorted((s for s in rows if s.method == "adb" and s.budget_us is not None
                        and (s.p_min, s.k_min) == base), key=lambda s: s.budget_us)
        worked = sorted((s for s in rows if s.method == "adb-work" and (s.p_min, s.k_min) == base),
                        key=lambda s: s.work)
        _curve(ax, [rows[s] for s in timed], colour, "-", "o", width, alpha)
        _curve(ax, [rows[s] for s in worked], colour, "--", "s", width, alpha)
        if default:
            _budget_labels(ax, rows, timed + worked, colour)
        free = rows.get(Setting("adb", *base))
        if free is not None and free.mean_us is not None and free.error_pct is not None:
            ax.scatter([free.mean_us], [free.error_pct], color=colour, marker="D", zorder=4,
                       s=70 if default else 30, edgecolors="black" if default else "none")


def _pareto_baselines(ax, rows):
    """exact-cut and box-first as curves over their budgets, the rest as labelled points."""
    for method, (colour, style, marker) in BASELINE_CURVES.items():
        budgeted = sorted((s for s in rows if s.method == method),
                          key=lambda s: s.budget_us or 0.0)
        _curve(ax, [rows[s] for s in budgeted], colour, style, marker)
    singles = [(rows[Setting(m)], m) for m in SINGLE_POINTS if Setting(m) in rows]
    singles = sorted((r.mean_us, r.error_pct, m) for r, m in singles
                     if r.mean_us is not None and r.error_pct is not None)
    for i, (x, y, method) in enumerate(singles):
        colour, marker, label = SINGLE_POINTS[method]
        ax.scatter([x], [y], color=colour, marker=marker, s=70, zorder=5)
        # Alternate heights: exact and FCL often sit close together at 0 %.
        ax.annotate(label, (x, y), xytext=(4, 5 + 10 * (i % 2)), textcoords="offset points",
                    fontsize=7.5, color=colour, path_effects=[HALO])


def _error_axis(ax, top):
    # symlog: linear through 0 (the exact methods' 0 % stays visible), logarithmic above
    # 1 %, so 1 and 5 % are told apart as well as 20 and 50 %.
    ax.set_yscale("symlog", linthresh=1.0, linscale=0.6)
    top = min(100.0, max(10.0, 1.5 * top))
    ax.set_ylim(-0.3, top)
    ticks = [t for t in ERROR_TICKS if t <= top]
    ax.set_yticks(ticks)
    ax.set_yticklabels(["%g" % t for t in ticks])
    ax.yaxis.set_minor_formatter(NullFormatter())
    for level in (1, 5):
        ax.axhline(level, color="gray", linestyle=":", linewidth=1)


def _pareto_legend(fig, colours, seen):
    """Colour = ADB setting, line style = budget kind; then the baselines and peers.

    Only what some panel shows: `seen` holds the settings drawn.
    """
    handles = [Line2D([], [], color=c, linewidth=2.6 if b == DEFAULT_ADB else 1.2,
                      label="ADB " + base_label(b)) for b, c in colours.items()]
    methods = {s.method for s in seen}
    timed = {s.budget_us is not None for s in seen if s.method == "adb"}
    families = (("-", "o", "ADB, time budgets", True in timed),
                ("--", "s", "ADB, work budgets", "adb-work" in methods),
                ("none", "D", "ADB, no budget", False in timed))
    handles += [Line2D([], [], color="dimgray", linestyle=style, marker=marker, markersize=4,
                       label=label) for style, marker, label, shown in families if shown]
    handles += [Line2D([], [], color=c, linestyle=style, marker=marker, markersize=5,
                       label="%s, time budgets" % method)
                for method, (c, style, marker) in BASELINE_CURVES.items() if method in methods]
    handles += [Line2D([], [], color=c, linestyle="none", marker=marker, markersize=7,
                       label=label)
                for method, (c, marker, label) in SINGLE_POINTS.items() if method in methods]
    handles.append(Line2D([], [], color="gray", linestyle=":", label="1 % and 5 % error"))
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize="small",
               frameon=False)


def plot_pareto(data):
    """What each method's error costs in time: error rate against mean query time."""
    def panel_rows(model):
        triangles = largest_size(data, model)
        return {s: r for (m, t, s), r in data.summary.items()
                if m == model and t == triangles and s.method != POOLED
                and r.mean_us and r.error_pct is not None}
    rows_of = {m: panel_rows(m) for m in data.models()}
    models = [m for m in data.models() if any(s.method in ("adb", "adb-work") for s in rows_of[m])]
    if not models:
        return "no ADB rows with both a mean time and an error rate"
    colours = base_colours({(s.p_min, s.k_min) for m in models for s in rows_of[m]
                            if s.method in ("adb", "adb-work")})
    # Wide panels: root boxes and GImpact stretch the time axis over four decades or more.
    fig, axes = subplot_grid(len(models), width=7.5, height=5.0, columns=min(len(models), 2))
    for ax, model in zip(axes, models):
        rows = rows_of[model]
        _pareto_adb(ax, rows, colours)
        _pareto_baselines(ax, rows)
        ax.set_xscale("log")  # from a fraction of a µs (root boxes) to GImpact's ms
        _error_axis(ax, max(r.error_pct for r in rows.values()))
        ax.set_xlabel("mean time per query (µs)")
        ax.set_ylabel(data.summary_error_label)
        ax.set_title("%s (%s triangles)" % (model, format(largest_size(data, model), ",")))
        ax.grid(True, which="major", alpha=0.3)
    _pareto_legend(fig, colours, {s for m in models for s in rows_of[m]})
    fit_suptitle(fig, "Error against time: each point a budget or setting "
                 "(lower left is better)")
    return fig


PLOTS = (
    ("time_vs_distance.png", plot_time_vs_distance),
    ("error_vs_distance.png", plot_error_vs_distance),
    ("pmin_kmin.png", plot_pmin_kmin),
    ("error_vs_budget.png", plot_error_vs_budget),
    ("time_vs_triangles.png", plot_time_vs_triangles),
    ("cells_histogram.png", plot_cells_histogram),
    ("speedup.png", plot_speedup),
    ("reliability.png", plot_reliability),
    ("pareto.png", plot_pareto),
)


def write_plots(data):
    load_matplotlib()
    written = []
    for name, make in PLOTS:
        path = os.path.join(data.dir, name)
        try:
            result = make(data)
            if isinstance(result, str):
                print("skip %s: %s" % (name, result))
                continue
            # Constrained layout places everything but figure-level legends (matplotlib
            # 3.6); only figures with one outside the axes need the extra "tight" pass.
            result.savefig(path, dpi=DPI, bbox_inches="tight" if result.legends else None)
            plt.close(result)
            written.append(path)
        except Exception:  # one broken figure must not cost the others of a long run
            print("skip %s: failed while plotting:\n%s" % (name, traceback.format_exc()),
                  file=sys.stderr)
            plt.close("all")
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", nargs="?", help="output directory of adb-tradeoff")
    parser.add_argument("--self-test", action="store_true",
                        help="plot synthetic data in a temporary directory and check the result")
    args = parser.parse_args(argv)
    if args.self_test:
        return self_test()
    if not args.dir:
        parser.error("DIR is required")
    try:
        data = load(args.dir)
    except InputError as error:
        print("plot_tradeoff: %s" % error, file=sys.stderr)
        return 2
    written = write_plots(data)
    print("files written (%d):" % len(written))
    for path in written:
        print("  " + path)
    return 0


# --------------------------------------------------------------------------- self-test

def _write_csv(path, header, rows):
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)


def _cell(value):
    return "" if value is None else value


SYNTHETIC_BUDGETS_US = (10.0, 30.0, 100.0, 300.0)
RELIABILITY_BINS = 10


def _synthetic_settings():
    """Every kind of row the tool writes: peers, baselines, ADB with and without budgets."""
    settings = [Setting(m) for m in PEERS] + [Setting("root-boxes")]
    settings += [Setting("adb", p, k) for p in (0.5, 0.9, 0.99) for k in (1, 5, 10)]
    bases = ((0.99, 10), (0.9, 5))
    settings += [Setting("adb", p, k, b) for p, k in bases for b in SYNTHETIC_BUDGETS_US]
    settings += [Setting("adb-work", p, k, work=w) for p, k in bases for w in (50, 200, 1000)]
    settings += [Setting(m, budget_us=b) for m in BASELINE_CURVES for b in SYNTHETIC_BUDGETS_US]
    return settings


def _csv_method(setting):
    return WORK_PREFIX + str(setting.work) if setting.method == "adb-work" else setting.method


def _synthetic_query(rng, s, truth, overlap, distance, exact_us):
    """(answer, confidence or None, time in µs, node pairs or None) of one made-up query."""
    noise = rng.lognormvariate(0, 0.25)
    peer_cost = {"exact": 1.0, "gimpact": 12.0, "fcl": 0.4}
    if s.method in peer_cost:
        time_us = exact_us * peer_cost[s.method] * noise
        return truth, 1.0, time_us, int(time_us * 8) if s.method == "exact" else None
    if s.method == "root-boxes":
        return overlap, None, 0.05 * noise, 1
    if s.method in BASELINE_CURVES:
        full_us = exact_us * (1.0 if s.method == "exact-cut" else 0.7) * noise
        if full_us <= s.budget_us:
            return truth, 1.0 if s.method == "exact-cut" else None, full_us, int(full_us * 8)
        # Cut short: exact-cut falls back on the root boxes, box-first on the boxes it reached.
        answer = overlap if s.method == "exact-cut" else truth != (rng.random() < 0.3)
        return (answer, 0.5 if s.method == "exact-cut" else None, s.budget_us * 1.05,
                int(s.budget_us * 8))
    near = 0.3 + 2 * math.exp(-((distance - 1.3) / 0.4) ** 2)
    # A per-query error chance spread around the setting's mean, so confidences fill
    # several reliability bins; capped at 0.5, where a yes/no guess is no better than a coin.
    error = min(0.5, near * (0.005 + 0.12 * (1 - s.p_min) + 0.03 / s.k_min)
                * rng.expovariate(1.0))
    # The estimate ignores what a budget costs, so budgeted ADB is overconfident: something
    # for the reliability diagram to show.
    confidence = max(0.0, min(1.0, 1 - error + rng.gauss(0, 0.02)))
    time_us = exact_us * (0.12 + 0.3 * s.k_min / 10) * noise
    if s.budget_us is not None:
        error += 0.25 * math.exp(-s.budget_us / 40)
        time_us = min(time_us, s.budget_us * 1.05)
    if s.work is not None:
        error += 0.25 * math.exp(-s.work / 150)
        time_us = min(time_us, s.work / 8 * 1.05)
    return truth != (rng.random() < error), confidence, time_us, int(time_us * 8)


def synthetic_run(directory, seed=7):
    """Write a plausible small queries, summary, reliability and cells CSV into `directory`."""
    rng = random.Random(seed)
    models = {"teddy": (3192, 12768), "pipes": (20000, 80000)}
    distances = [round(0.4 + 0.2 * i, 2) for i in range(9)]
    settings = _synthetic_settings()
    rows, groups = [], defaultdict(list)
    for model, sizes in models.items():
        for triangles in sizes:
            for distance in distances:
                for rotation in range(30):
                    pose_a = [rng.gauss(0, 1) for _ in range(4)]
                    norm = math.sqrt(sum(v * v for v in pose_a))
                    pose_a = [v / norm for v in pose_a] + [0.0, 0.0, 0.0]
                    pose_b = [1.0, 0.0, 0.0, 0.0, distance, 0.0, 0.0]
                    truth = rng.random() < 1 / (1 + math.exp(-6 * (1.3 - distance)))
                    overlap = distance < 1.8  # stands in for "the root boxes overlap"
                    exact_us = 150 * math.exp(-1.8 * (distance - 0.4)) * (triangles / 3192) ** 0.15
                    for s in settings:
                        answer, confidence, time_us, nodes = _synthetic_query(
                            rng, s, truth, overlap, distance, exact_us)
                        rows.append([model, triangles, _csv_method(s), _cell(s.p_min),
                                     _cell(s.k_min), _cell(s.budget_us), distance, rotation]
                                    + pose_a + pose_b +
                                    [int(answer), "" if confidence is None else "%.4f" % confidence,
                                     int(time_us * 1000), _cell(nodes)])
                        group = (time_us, answer != truth, confidence, overlap, nodes)
                        groups[(model, triangles, s)].append(group)
                        if s.method in ("adb", "adb-work"):
                            groups[(model, triangles, Setting(POOLED))].append(group)
    _write_csv(os.path.join(directory, "queries.csv"), QUERY_COLUMNS, rows)
    summary_columns = list(SUMMARY_COLUMNS)
    summary_columns.insert(summary_columns.index("error_pct") + 1, "ece")
    _write_csv(os.path.join(directory, "summary.csv"), summary_columns,
               _synthetic_summary(groups))
    _write_csv(os.path.join(directory, "reliability.csv"), RELIABILITY_COLUMNS,
               _synthetic_reliability(groups))
    cells = []
    for model in models:
        for triangles in models[model]:
            for index in range(CELLS):
                bias = 1.3 if model == "pipes" and (index // 64) in (3, 4) else 1.0
                cells.append([model, triangles, index, int(rng.gauss(1000, 60) * bias)])
    _write_csv(os.path.join(directory, "cells.csv"), CELL_COLUMNS, cells)


def _has_bins(setting):
    """The settings reliability.csv holds: those whose confidence is an estimate."""
    return setting.method in ("adb", "adb-work", "exact-cut", POOLED)


def _synthetic_bins(group):
    """Ten equal confidence bins over the queries with overlapping root boxes."""
    members = [[] for _ in range(RELIABILITY_BINS)]
    for _, wrong, confidence, overlap, _ in group:
        if overlap and confidence is not None:
            members[min(RELIABILITY_BINS - 1, int(confidence * RELIABILITY_BINS))].append(
                (confidence, not wrong))
    return [Bin(i / RELIABILITY_BINS, (i + 1) / RELIABILITY_BINS, len(m),
                sum(c for c, _ in m) / len(m) if m else None,
                sum(r for _, r in m) / len(m) if m else None)
            for i, m in enumerate(members)]


def _sorted_groups(groups):
    return sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1], kv[0][2].sort_key()))


def _synthetic_reliability(groups):
    rows = []
    for (model, triangles, s), group in _sorted_groups(groups):
        if not _has_bins(s):
            continue
        for index, b in enumerate(_synthetic_bins(group)):
            rows.append([model, triangles, _csv_method(s), _cell(s.p_min), _cell(s.k_min),
                         _cell(s.budget_us), index, "%.1f" % b.lo, "%.1f" % b.hi, b.count,
                         "" if b.confidence is None else "%.4f" % b.confidence,
                         "" if b.right is None else "%.4f" % b.right])
    return rows


def _synthetic_summary(groups):
    means = {key: sum(g[0] for g in group) / len(group) for key, group in groups.items()}
    rows = []
    for (model, triangles, s), group in _sorted_groups(groups):
        times = sorted(g[0] for g in group)
        overlapping = [g for g in group if g[3]]
        error = 100.0 * sum(g[1] for g in overlapping) / len(overlapping)
        confidences = [g[2] for g in group if g[2] is not None]
        nodes = [g[4] for g in group if g[4] is not None]
        ece = ece_from_bins(_synthetic_bins(group)) if _has_bins(s) else None
        speedups = []
        for peer in PEERS:
            # Leave teddy's speed-up cells empty so the reader's fill-in path runs too.
            peer_mean = means.get((model, triangles, Setting(peer)))
            speedups.append("" if model == "teddy" or peer_mean is None
                            else "%.3f" % (peer_mean / means[(model, triangles, s)]))
        rows.append([model, triangles, _csv_method(s), _cell(s.p_min), _cell(s.k_min),
                     _cell(s.budget_us), len(group), len(overlapping),
                     "%.3f" % means[(model, triangles, s)],
                     "%.3f" % times[int(0.95 * (len(times) - 1))],
                     "%.3f" % error, "" if ece is None else "%.4f" % ece,
                     "%.4f" % (sum(confidences) / len(confidences)) if confidences else "",
                     "%.1f" % (sum(nodes) / len(nodes)) if nodes else ""] + speedups)
    return rows


def _run_self(directory):
    result = subprocess.run([sys.executable, os.path.abspath(__file__), directory],
                            capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def _is_png(path):
    if not os.path.exists(path) or os.path.getsize(path) < 1000:
        return False
    with open(path, "rb") as handle:
        return handle.read(8) == b"\x89PNG\r\n\x1a\n"


def _keep_rows(path, keep):
    """Rewrite a CSV file keeping the header and the rows for which keep(row) is true."""
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    _write_csv(path, rows[0], [r for r in rows[1:] if keep(r)])


def _make_old_format(directory):
    """Turn a synthetic run into what adb-tradeoff wrote before the calibration columns:
    only adb and the peers, summary.csv without ece, no reliability.csv."""
    old = ("adb",) + PEERS
    _keep_rows(os.path.join(directory, "queries.csv"), lambda r: r[2] in old)
    path = os.path.join(directory, "summary.csv")
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    drop, method = rows[0].index("ece"), rows[0].index("method")
    _write_csv(path, [c for i, c in enumerate(rows[0]) if i != drop],
               [[c for i, c in enumerate(r) if i != drop] for r in rows[1:] if r[method] in old])
    os.remove(os.path.join(directory, "reliability.csv"))


def _new_rows_read(directory):
    """The new method names, the ece column and reliability.csv come through the readers."""
    with contextlib.redirect_stdout(io.StringIO()):
        data = load(directory)
    key = ("pipes", 80000)
    pooled = data.summary.get(key + (Setting(POOLED),))
    bins = data.reliability.get(key + (Setting("adb-work", 0.99, 10, work=200),), [])
    return (pooled is not None and pooled.ece is not None
            and key + (Setting("exact-cut", budget_us=30.0),) in data.summary
            and key + (Setting("root-boxes"),) in data.summary
            and len(bins) == RELIABILITY_BINS and any(b.count == 0 for b in bins)
            and abs(ece_from_bins(data.reliability[key + (Setting(POOLED),)]) - pooled.ece)
            < 1e-3)


def _arithmetic_ok(root):
    """Four poses at one distance, ADB wrong on one: 25 % error, mean time 2.5 µs."""
    directory = os.path.join(root, "arithmetic")
    os.mkdir(directory)
    pose = [1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0]
    rows = []
    for rotation, (truth, adb) in enumerate(((1, 1), (0, 0), (1, 0), (0, 0))):
        rows.append(["m", 100, "exact", "", "", "", "1.0", rotation] + pose + [truth, 1, 9000, ""])
        rows.append(["m", 100, "adb", 0.99, 10, "", "1.0", rotation] + pose
                    + [adb, 0.9, 1000 * (rotation + 1), 5])
    _write_csv(os.path.join(directory, "queries.csv"), QUERY_COLUMNS, rows)
    data = Dataset(directory)
    data.read_queries()
    acc = data.per_distance[("m", 100, Setting("adb", 0.99, 10))][1.0]
    return (acc.error_pct() == 25.0 and acc.mean_us() == 2.5
            and data.reference_methods == {"exact"})


def self_test():
    failures = []

    def check(condition, what, output=""):
        print("%s: %s" % ("ok  " if condition else "FAIL", what))
        if not condition:
            failures.append(what)
            if output:
                print("    " + output.strip().replace("\n", "\n    "))

    with tempfile.TemporaryDirectory(prefix="plot_tradeoff_") as root:
        full = os.path.join(root, "full")
        os.mkdir(full)
        synthetic_run(full)
        code, output = _run_self(full)
        check(code == 0, "full synthetic run exits 0", output)
        for name, _ in PLOTS:
            check(_is_png(os.path.join(full, name)), "full run wrote %s as a PNG" % name, output)
        check("Traceback" not in output, "full run printed no traceback", output)
        check(_new_rows_read(full), "new methods, ece and reliability bins are read")

        old = os.path.join(root, "old_format")
        os.mkdir(old)
        synthetic_run(old)
        _make_old_format(old)
        code, output = _run_self(old)
        check(code == 0 and "Traceback" not in output, "old-format run exits 0", output)
        check("skip reliability.png: no reliability.csv" in output,
              "old-format run skips the reliability diagram with a note", output)
        for name in ("error_vs_budget.png", "speedup.png", "pareto.png"):
            check(_is_png(os.path.join(old, name)), "old-format run wrote %s" % name, output)

        # A failed tool run: one model, FCL (no exact rows) and one ADB setting, a summary
        # with only its header, no cells, and a last line cut off mid-row.
        partial = os.path.join(root, "partial")
        os.mkdir(partial)
        synthetic_run(partial)
        _write_csv(os.path.join(partial, "summary.csv"), SUMMARY_COLUMNS, [])
        os.remove(os.path.join(partial, "cells.csv"))
        _keep_rows(os.path.join(partial, "queries.csv"),
                   lambda r: r[0] == "pipes" and r[1] == "20000" and (
                       r[2] == "fcl" or (r[2], r[3], r[4], r[5]) == ("adb", "0.99", "10", "")))
        with open(os.path.join(partial, "queries.csv"), "a", encoding="utf-8") as handle:
            handle.write("pipes,20000,adb,0.99,10,,1.2,3,1,0,0")
        code, output = _run_self(partial)
        check(code == 0, "partial run exits 0", output)
        check("Traceback" not in output, "partial run printed no traceback", output)
        for name in ("time_vs_distance.png", "error_vs_distance.png", "speedup.png"):
            check(_is_png(os.path.join(partial, name)), "partial run wrote %s" % name, output)
        check("skip cells_histogram.png" in output, "partial run skips the cell histogram", output)
        check("summary.csv has no rows" in output, "partial run falls back to queries.csv", output)
        check("1 malformed or truncated row" in output, "partial run reports the cut-off row",
              output)

        with contextlib.redirect_stdout(io.StringIO()):  # its notes were checked above
            partial_data = load(partial)
        check(partial_data.reference_methods == {"fcl"},
              "answers are judged against FCL when there are no exact rows")
        check(_arithmetic_ok(root), "error rate and mean time of a hand-made case")

        # Header only: nothing to plot, but no failure either.
        empty = os.path.join(root, "empty")
        os.mkdir(empty)
        _write_csv(os.path.join(empty, "queries.csv"), QUERY_COLUMNS, [])
        code, output = _run_self(empty)
        check(code == 0 and "Traceback" not in output, "header-only queries.csv exits 0", output)

        for file_name, column in (("queries.csv", "time_ns"), ("summary.csv", "error_pct"),
                                  ("cells.csv", "count")):
            broken = os.path.join(root, "broken_" + file_name.split(".")[0])
            os.mkdir(broken)
            synthetic_run(broken)
            path = os.path.join(broken, file_name)
            with open(path, encoding="utf-8") as handle:
                lines = handle.read().split("\n")
            lines[0] = lines[0].replace(column, column + "_renamed")
            with open(path, "w", encoding="utf-8") as handle:
                handle.write("\n".join(lines))
            code, output = _run_self(broken)
            check(code != 0 and column in output and file_name in output,
                  "malformed %s header exits non-zero naming %s" % (file_name, column), output)

        code, output = _run_self(os.path.join(root, "does_not_exist"))
        check(code != 0 and "does_not_exist" in output, "missing DIR exits non-zero", output)
        no_queries = os.path.join(root, "no_queries")
        os.mkdir(no_queries)
        code, output = _run_self(no_queries)
        check(code != 0 and "queries.csv" in output, "missing queries.csv exits non-zero", output)

    print("self-test %s" % ("passed" if not failures else "FAILED (%d)" % len(failures)))
    return 0 if not failures else 1


if __name__ == "__main__":
    ensure_matplotlib()
    sys.exit(main())
