"""What the figures share: which settings get a line, colours, legends and axes."""

import math
import textwrap

from . import mpl
from .tables import ADB_COLOURS, DEFAULT_ADB, PEER_COLOURS, TRIANGLE_STYLES, Setting


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
    fig, axes = mpl.plt.subplots(rows, columns, figsize=(width * columns, height * rows),
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
        ax.xaxis.set_minor_formatter(mpl.NullFormatter())  # log axes would add 2x10^1-style labels


def triangle_legend(ax, counts):
    styles = [TRIANGLE_STYLES[i % len(TRIANGLE_STYLES)] for i in range(len(counts))]
    handles = [mpl.Line2D([], [], color="dimgray", linestyle=style, marker=marker, markersize=4,
                      label="%s triangles" % format(t, ","))
               for (style, marker), t in zip(styles, counts)]
    ax.legend(handles=handles, fontsize="small", loc="best", framealpha=0.8)


def setting_legend(fig, settings, colours, title=None):
    handles = [mpl.Line2D([], [], color=colours[s], linewidth=line_width(s) + 0.4, label=s.label())
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
    """Plot one line per triangle count of `value(point)` against distance; return the y
    values."""
    plotted = []
    for rank, triangles in enumerate(data.triangle_counts(model)):
        series = data.per_distance.get((model, triangles, setting))
        if not series:
            continue
        points = [(d, value(point)) for d, point in sorted(series.items())]
        points = [(d, v) for d, v in points if v is not None]
        if not points:
            continue
        style, marker = TRIANGLE_STYLES[rank % len(TRIANGLE_STYLES)]
        ax.plot([p[0] for p in points], [p[1] for p in points], color=colour, linestyle=style,
                marker=marker, markersize=3.5, linewidth=line_width(setting))
        plotted += [p[1] for p in points]
    return plotted
