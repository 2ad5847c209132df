"""matplotlib, imported only when there is something to plot (the import takes most of a
second, and bad input should be reported without that wait), headless (Agg)."""

import importlib.util
import os
import sys

SYSTEM_PYTHON = "/usr/bin/python3"

# Bound by load_matplotlib(); the figures use them as mpl.plt and so on.
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
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, os.path.abspath(sys.argv[0])] + sys.argv[1:])
    sys.exit("plot_tradeoff: matplotlib is not installed for %s "
             "(Debian: apt-get install python3-matplotlib)" % sys.executable)


def load_matplotlib():
    """Import matplotlib with the headless Agg backend into this module's names."""
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
