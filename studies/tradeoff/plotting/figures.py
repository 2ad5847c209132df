"""The figures: the paper's Figs. 8-11 and the budget, scaling, speed-up, reliability and
error-against-time plots. Each takes the Dataset and returns a matplotlib Figure, or a string
saying why it was skipped; they draw what adb-tradeoff computed and compute no rates."""

import math
import os
import sys
import traceback
from collections import defaultdict

from . import mpl
from .style import (colour_map, featured_adb, fit_suptitle, largest_size, line_width,
                    log_if_wide, per_distance_lines, pmin_scale, set_value_ticks,
                    setting_legend, subplot_grid, summary_value, triangle_legend,
                    wrap_to_figure)
from .tables import (ADB_COLOURS, CELLS, DEFAULT_ADB, DPI, PEER_COLOURS, PEER_LABELS, PEERS,
                     POOLED, Dataset, Setting)

# --------------------------------------------------------------------------- figures

def plot_time_vs_distance(data):
    """Paper Fig. 9: mean time per query against the distance of the two copies."""
    models = data.models()
    if not data.per_distance:
        return "no rows in distances.csv (or none: written by newer adb-tradeoff runs)"
    every = data.settings()
    # Only the peers beside ADB: the baselines' budgets would bury the ADB lines.
    shown = [s for s in every if s.method in PEERS] + featured_adb(every, cap=4)
    colours = colour_map(shown)
    fig, axes = subplot_grid(len(models))
    for ax, model in zip(axes, models):
        values = []
        for setting in shown:
            values += per_distance_lines(data, model, setting, lambda p: p.mean_us, ax,
                                         colours[setting])
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
    # distances.csv's error_pct: judged by adb-tradeoff as summary.csv's is (the run's
    # reference, among the queries whose root boxes overlap), per distance.
    if not data.per_distance:
        return "no rows in distances.csv (or none: written by newer adb-tradeoff runs)"
    if data.reference_label() == "no reference":
        return "no exact or fcl rows: no answer was judged"
    every = [s for s in data.settings() if s.method == "adb"]
    shown = featured_adb(every, cap=4)  # error curves are noisy: more lines stop being readable
    if not shown:
        return "no ADB rows without a time budget"
    colours = colour_map(shown)
    models = [m for m in data.models() if any(s.method == "adb" for s in data.settings(m))]
    fig, axes = subplot_grid(len(models))
    for ax, model in zip(axes, models):
        for setting in shown:
            per_distance_lines(data, model, setting, lambda p: p.error_pct, ax, colours[setting])
        ax.set_title(model)
        ax.set_xlabel("distance of box centres (units of half the largest box edge)")
        ax.set_ylabel("wrong answers, % of queries with\noverlapping root boxes at this distance")
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
    fig, axes = mpl.plt.subplots(len(models), 3, figsize=(15, 3.9 * len(models)), squeeze=False,
                             layout="constrained")
    for line, model in zip(axes, models):
        triangles = largest_size(data, model)
        grid = _adb_grid(data, model, triangles)
        p_values = sorted({k[0] for k in grid})
        k_values = sorted({k[1] for k in grid})
        title = "%s (%s triangles)" % (model, format(triangles, ","))
        time_label, error_label = "mean time per query (µs)", Dataset.ERROR_LABEL
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
    fig, axes = mpl.plt.subplots(len(models), 3, figsize=(15, 3.9 * len(models)), squeeze=False,
                             layout="constrained")
    for line, model in zip(axes, models):
        triangles = largest_size(data, model)
        rows = {s: r for (m, t, s), r in data.summary.items()
                if m == model and t == triangles and s.method == "adb"}
        panels = ((line[0], "error_pct", Dataset.ERROR_LABEL, "error"),
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
    handles = [mpl.Line2D([], [], color=colour, marker="o", markersize=4, label=base_label(base))
               for base, colour in colours.items()]
    handles += [mpl.Line2D([], [], color="dimgray", linestyle="--", label="the same, no budget"),
                mpl.Line2D([], [], color="gray", linestyle=":", label="time = budget")]
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
    handles = [mpl.Line2D([], [], color=PEER_COLOURS[p], linewidth=6, label="vs " + PEER_LABELS[p])
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
            colours[s] = mpl.colormaps[name](0.4 + 0.55 * i / max(1, len(group) - 1))
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
    fig = mpl.plt.figure(figsize=(5.0 * columns, 5.6 * rows), layout="constrained")
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
    handles = [mpl.Line2D([], [], color="gray", linestyle="--", label="perfect calibration")]
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
        ece = summary_value(data, key[0], key[1], Setting(POOLED), "ece")  # the table's
        shown = sorted((s for s in groups if s in colours), key=Setting.sort_key)
        _reliability_panel(ax, strip, groups, shown, colours, ece)
        title = "%s (%s triangles)" % (key[0], format(key[1], ","))
        ax.set_title(title + ("" if ece is None else ": pooled ECE %.3f" % ece))
    ordered = sorted(colours, key=lambda s: (s.method, s.budget_us is None, s.budget_us or 0,
                                             s.work or 0))
    handles = [mpl.Line2D([], [], color=colours[s], linestyle="--" if s.method == "adb-work" else "-",
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
                    ha="left" if timed else "right", path_effects=[mpl.HALO])


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
                    fontsize=7.5, color=colour, path_effects=[mpl.HALO])


def _error_axis(ax, top):
    # symlog: linear through 0 (the exact methods' 0 % stays visible), logarithmic above
    # 1 %, so 1 and 5 % are told apart as well as 20 and 50 %.
    ax.set_yscale("symlog", linthresh=1.0, linscale=0.6)
    top = min(100.0, max(10.0, 1.5 * top))
    ax.set_ylim(-0.3, top)
    ticks = [t for t in ERROR_TICKS if t <= top]
    ax.set_yticks(ticks)
    ax.set_yticklabels(["%g" % t for t in ticks])
    ax.yaxis.set_minor_formatter(mpl.NullFormatter())
    for level in (1, 5):
        ax.axhline(level, color="gray", linestyle=":", linewidth=1)


def _pareto_legend(fig, colours, seen):
    """Colour = ADB setting, line style = budget kind; then the baselines and peers.

    Only what some panel shows: `seen` holds the settings drawn.
    """
    handles = [mpl.Line2D([], [], color=c, linewidth=2.6 if b == DEFAULT_ADB else 1.2,
                      label="ADB " + base_label(b)) for b, c in colours.items()]
    methods = {s.method for s in seen}
    timed = {s.budget_us is not None for s in seen if s.method == "adb"}
    families = (("-", "o", "ADB, time budgets", True in timed),
                ("--", "s", "ADB, work budgets", "adb-work" in methods),
                ("none", "D", "ADB, no budget", False in timed))
    handles += [mpl.Line2D([], [], color="dimgray", linestyle=style, marker=marker, markersize=4,
                       label=label) for style, marker, label, shown in families if shown]
    handles += [mpl.Line2D([], [], color=c, linestyle=style, marker=marker, markersize=5,
                       label="%s, time budgets" % method)
                for method, (c, style, marker) in BASELINE_CURVES.items() if method in methods]
    handles += [mpl.Line2D([], [], color=c, linestyle="none", marker=marker, markersize=7,
                       label=label)
                for method, (c, marker, label) in SINGLE_POINTS.items() if method in methods]
    handles.append(mpl.Line2D([], [], color="gray", linestyle=":", label="1 % and 5 % error"))
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
        ax.set_ylabel(Dataset.ERROR_LABEL)
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
    mpl.load_matplotlib()
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
            mpl.plt.close(result)
            written.append(path)
        except Exception:  # one broken figure must not cost the others of a long run
            print("skip %s: failed while plotting:\n%s" % (name, traceback.format_exc()),
                  file=sys.stderr)
            mpl.plt.close("all")
    return written
