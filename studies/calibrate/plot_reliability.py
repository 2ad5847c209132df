#!/usr/bin/env python3
"""Reliability diagrams of the collision estimate, one panel per budget (`adb-calibrate`).

Usage:
    plot_reliability.py DIR    read DIR/reliability.csv as adb-calibrate wrote it and write
                               DIR/reliability.png

Each panel: the answers' confidence (binned) against the share of them that was right, for the
fit set and the check set pooled (thick) and for each checked case (thin). A calibrated
estimate lies on the diagonal; below it, the answers were surer than right. The numbers are the
tool's (it bins and judges); this file only draws.
"""

import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tradeoff"))

from plotting import mpl  # noqa: E402 (after the path above)


def load(path):
    rows = {}
    order = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if r["budget"] not in order:
                order.append(r["budget"])
            rows.setdefault(r["budget"], {}).setdefault((r["set"], r["case"]), []).append(r)
    return order, rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", help="output directory of adb-calibrate")
    args = parser.parse_args(argv)
    order, rows = load(os.path.join(args.dir, "reliability.csv"))
    mpl.ensure_matplotlib()
    mpl.load_matplotlib()
    plt = mpl.plt
    columns = 3
    lines = (len(order) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(4.2 * columns, 4.2 * lines), squeeze=False)
    for k, budget in enumerate(order):
        ax = axes[k // columns][k % columns]
        ax.plot([0.5, 1.0], [0.5, 1.0], color="0.6", lw=1, ls="--")
        pooled = []
        for (set_, case), bins in sorted(rows[budget].items()):
            x = [float(b["mean_confidence"]) for b in bins]
            y = [float(b["fraction_right"]) for b in bins]
            if case.startswith("all "):
                colour = "tab:blue" if set_ == "fit" else "tab:red"
                ece = float(bins[0]["ece"])
                pooled.append((x, y, colour, "%s (ECE %.3f)" % (case, ece)))
            elif set_ == "check":
                ax.plot(x, y, color="tab:red", lw=0.8, alpha=0.35, marker=".", ms=3)
        for x, y, colour, label in pooled:
            ax.plot(x, y, color=colour, lw=2.2, marker="o", ms=4, label=label)
        ax.set_title("budget: %s" % budget)
        ax.set_xlim(0.5, 1.0)
        ax.set_ylim(0.0, 1.02)
        ax.set_xlabel("confidence of the answer")
        ax.set_ylabel("share of answers right")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right", fontsize=8)
    for k in range(len(order), lines * columns):
        axes[k // columns][k % columns].axis("off")
    fig.suptitle("adb-calibrate: reliability at QuerySettings' defaults "
                 "(thin: each checked case)")
    fig.tight_layout()
    out = os.path.join(args.dir, "reliability.png")
    fig.savefig(out, dpi=90)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
