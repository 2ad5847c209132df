"""The budget sweep's plots, one panel per scene: probed penetration against the budget
(penetration.png) and time per step against the budget (time.png), GImpact and the convex
decomposition as horizontal reference lines. Runs with Debian's matplotlib (/usr/bin/python3).
"""

import math
import os

import matplotlib

matplotlib.use("Agg")  # headless
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, NullFormatter  # noqa: E402

SERIES = {"pairs": ("node-pair budget", "tab:blue", "o"),
          "time": ("time budget", "tab:orange", "s")}
PEERS = {"gimpact": ("GImpact", "tab:red"), "convex": ("convex (HACD)", "tab:green")}
XTICKS = [1 / 8, 1 / 4, 1 / 2, 1]
XLABELS = ["1/8", "1/4", "1/2", "exact"]


def _series(mine, kind):
    """Seed-1 points of one budget kind, from the smallest budget up to exact (x = 1)."""
    pts = sorted((r.spec.fraction, r) for r in mine if r.spec.kind == kind and r.spec.seed == 1)
    exact = [r for r in mine if r.spec.kind == "exact" and r.spec.seed == 1]
    return [p[0] for p in pts] + [1.0], [p[1] for p in pts] + exact


def _panels(results):
    """One panel per scene, in the runs' order: the figure and (axis, scene, its runs)."""
    scenes = list(dict.fromkeys(r.spec.scene for r in results))
    cols = 2 if len(scenes) > 1 else 1
    rows = math.ceil(len(scenes) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.6 * rows), squeeze=False)
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    return fig, [(ax, scene, [r for r in results if r.spec.scene == scene])
                 for ax, scene in zip(axes.flat, scenes)]


def _axes(ax, scene, ylabel):
    ax.set_xscale("log", base=2)
    ax.set_xticks(XTICKS)
    ax.set_xticklabels(XLABELS)
    ax.set_xlim(1 / 10, 1.25)
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: "%g" % v))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_title(scene)
    ax.set_xlabel("budget (fraction of the need / of exact time)")
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)


def _mark_lost(ax, xs, ys, rs):
    """Runs that lost bodies: ringed in red with the count. A lost body no longer presses
    on the others or costs contacts, so such a run's penetration and time are not
    comparable."""
    for x, y, r in zip(xs, ys, rs):
        if r.lost():
            ax.scatter([x], [y], s=140, facecolors="none", edgecolors="red", linewidths=1.3,
                       zorder=4, label="run lost bodies (count)")
            ax.annotate("%d" % r.lost(), (x, y), textcoords="offset points", xytext=(6, 5),
                        color="red", fontsize=8)


def _peer_lines(ax, mine, value, styles):
    for kind, (name, colour) in PEERS.items():
        peer = [r for r in mine if r.spec.kind == kind and r.spec.seed == 1]
        if not peer:
            continue
        r = peer[0]
        steps = " (%d steps)" % r.spec.steps if kind == "gimpact" else ""
        for what, style in styles:
            ax.axhline(value(r, what), color=colour, linestyle=style, linewidth=1.2,
                       label="%s%s, %s" % (name, steps, what))


def _save(fig, path, title):
    handles, labels = [], []
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.suptitle(title, fontsize=11)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    rows = math.ceil(len(labels) / 3)
    fig.tight_layout(rect=(0, 0.01 + 0.2 * rows / fig.get_figheight(), 1, 0.96))
    # tight: a figure of one scene is narrower than the three-column legend under it.
    fig.savefig(path, dpi=90, bbox_inches="tight")
    plt.close(fig)


def _budget_lines(ax, mine, value, first, second, ringed, second_label=None):
    """Per budget kind (SERIES), a solid line of value(r, first) and a hollow one of
    value(r, second[0]) in style second[1], in the order the legend lists them; the runs that
    lost bodies ringed on the `ringed` line."""
    what, style = second
    for kind, (name, colour, marker) in SERIES.items():
        xs, rs = _series(mine, kind)
        ys = {first: [value(r, first) for r in rs], what: [value(r, what) for r in rs]}
        ax.plot(xs, ys[first], color=colour, marker=marker, label="%s, %s" % (name, first))
        if ringed == first:
            _mark_lost(ax, xs, ys[first], rs)
        ax.plot(xs, ys[what], color=colour, marker=marker, linestyle=style,
                markerfacecolor="none", label="%s, %s" % (name, second_label or what))
        if ringed == what:
            _mark_lost(ax, xs, ys[what], rs)


def penetration(results, path, steps):
    fig, panels = _panels(results)

    def value(r, what):
        return r.probed_max() if what == "max" else r.probed_mean()

    for ax, scene, mine in panels:
        _budget_lines(ax, mine, value, "max", ("mean", "--"), ringed="mean")
        others = [r for r in mine if r.spec.seed != 1]
        for what, marker in (("max", "x"), ("mean", "+")):
            ax.scatter([r.spec.fraction or 1.0 for r in others], [value(r, what) for r in others],
                       color="0.35", marker=marker, s=22, zorder=3,
                       label="seeds 2-4 (1/4 and exact), %s" % what)
        _peer_lines(ax, mine, value, (("max", "-"), ("mean", "--")))
        _axes(ax, scene, "body-body penetration (probed)")
    _save(fig, path, "Probed body-body penetration over %d steps (max over the run; mean: "
                     "each body's deepest, over bodies and probes)" % steps)


def step_time(results, path, steps):
    fig, panels = _panels(results)

    def value(r, what):
        return r.ms_per_step() if what == "whole step" else r.frame_ms()

    for ax, scene, mine in panels:
        _budget_lines(ax, mine, value, "whole step", ("adb pairs", ":"), ringed="whole step",
                      second_label="adb pairs only")
        _peer_lines(ax, mine, value, (("whole step", "-"),))
        _axes(ax, scene, "ms per step (mean)")
    _save(fig, path, "Time per step, mean over %d steps (GImpact: its first steps only)" % steps)


def write_all(results, a):
    penetration(results, os.path.join(a.out, "penetration.png"), a.steps)
    step_time(results, os.path.join(a.out, "time.png"), a.steps)
