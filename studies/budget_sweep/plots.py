"""The budget sweep's picture: per scene, what each fraction of the need costs against exact
contacts, in resting penetration and in the step at which the pile falls asleep
(results.png)."""

import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

from tables import PENETRATION_FACTOR, rows_of  # noqa: E402

COLOURS = {"exact": "black", "gimpact": "tab:grey", "1/4": "tab:blue", "1/8": "tab:orange",
           "1/16": "tab:red"}


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def write_all(results, args):
    table = rows_of(results)
    scenes = []
    for t in table:
        if t["scene"] not in scenes:
            scenes.append(t["scene"])
    fig, (pen, sleep) = plt.subplots(1, 2, figsize=(13, 0.45 * len(scenes) + 2), sharey=True)
    steps = max(r.spec.steps for r in results)
    highest = 1.0
    for index, (budget, colour) in enumerate(COLOURS.items()):
        ys, pens, sleeps, awake = [], [], [], []
        for t in table:
            if t["budget"] != budget:
                continue
            y = scenes.index(t["scene"])
            ratio = _number(t["penetration_vs_exact"])
            if budget != "exact" and not math.isnan(ratio):
                ys.append(y)
                pens.append(ratio)
                highest = max(highest, ratio)
            asleep = t["all_asleep_from"]
            # Awake runs side by side past the run's end, one column per budget: stacked,
            # the crosses of two budgets hid each other.
            (sleeps if asleep else awake).append((asleep or steps * (1.03 + 0.025 * index), y))
        if ys:
            pen.scatter(pens, ys, color=colour, label=budget, s=28)
        if sleeps:
            sleep.scatter([s for s, _ in sleeps], [y for _, y in sleeps], color=colour,
                          label=budget, s=28)
        if awake:
            sleep.scatter([s for s, _ in awake], [y for _, y in awake], color=colour, marker="x",
                          s=36)
    pen.axvline(PENETRATION_FACTOR, color="tab:red", lw=0.8, ls="--")
    pen.set_xscale("log")
    pen.set_xlabel("resting penetration / exact contacts' (target <= %g)" % PENETRATION_FACTOR)
    pen.set_yticks(range(len(scenes)))
    pen.set_yticklabels(scenes)
    pen.invert_yaxis()
    pen.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    pen.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    pen.set_xticks([t for t in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000)
                    if t <= highest * 1.5])
    sleep.axvline(steps, color="grey", lw=0.8)
    sleep.set_xlabel("all asleep from step (x: awake after %d steps)" % steps)
    sleep.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    for ax in (pen, sleep):
        ax.grid(True, axis="x", alpha=0.3)
    fig.suptitle("Piles under a budget of 1/4, 1/8 and 1/16 of exact contacts' need")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "results.png"), dpi=110)
    plt.close(fig)
