#!/usr/bin/env python3
"""Plots for the ADB-tree accuracy/time trade-off study (`adb-tradeoff`).

Usage:
    plot_tradeoff.py DIR    read DIR/summary.csv (+ distances.csv, cells.csv, reliability.csv),
                            as adb-tradeoff wrote them, and write the PNG figures into DIR

The numbers are the tool's: it judges every answer once (studies/tradeoff/judging.cpp) and
writes what the figures need per distance, per setting and per confidence bin; these files
only draw (plotting/tables.py reads, plotting/figures.py draws). The spec is
docs/benchmark.md (the paper's Figs. 8-11); tests/tradeoff/plot_script_check.py checks it.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from plotting import mpl  # noqa: E402 (after the path above)
from plotting.figures import write_plots  # noqa: E402
from plotting.tables import InputError, load  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", help="output directory of adb-tradeoff")
    args = parser.parse_args(argv)
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


if __name__ == "__main__":
    mpl.ensure_matplotlib()
    sys.exit(main())
