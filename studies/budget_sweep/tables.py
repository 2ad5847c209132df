"""The budget sweep's tables: runs.csv and quarter_seeds.csv (every figure), and sweep.md
(the same as markdown, per scene, plus the issue's targets at a quarter of the need)."""

import csv
import math
import os
import sys
import time

from runs import LAST_SECOND, SETTLED_FROM

# The targets at 1/4 of the need: no body lost, probed max penetration at most this
# many times exact's, the pile settling. "Settles" is judged here as: mean kinetic energy
# over the last second at most this many times exact's on the same seed (the same factor as
# for penetration; the end of a single step is one body's bounce).
PENETRATION_FACTOR = 2.0
SETTLING_FACTOR = 2.0


def _label(r):
    s = r.spec
    if s.kind == "exact":
        return "exact (no budget)"
    if s.kind in ("pairs", "time"):
        return "%s 1/%d" % ("node pairs" if s.kind == "pairs" else "time", round(1 / s.fraction))
    if s.kind == "gimpact":
        return "GImpact (%d steps)" % s.steps
    return "convex (HACD)"


def _budget_text(r):
    s = r.spec
    if s.kind == "pairs":
        return "%d node pairs" % s.budget
    if s.kind == "time":
        return "%.2f ms" % (s.budget / 1e3)
    return "-"


def _ratio(x, y):
    return x / y if y > 0 else float("nan")


def _f(x, digits=4):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else "%.*f" % (digits, x)


def _row(r, first):
    s = r.spec
    return {
        "scene": s.scene, "kind": s.kind, "backend": s.backend, "seed": s.seed,
        "fraction": "" if s.fraction is None else "%.4f" % s.fraction,
        "budget": "" if s.budget is None else "%.0f" % s.budget, "steps": s.steps,
        "wall_s": "%.1f" % r.wall_seconds, "load_before": "%.2f" % r.load_before,
        "load_after": "%.2f" % r.load_after,
        "ms_step": "%.3f" % r.ms_per_step(), "ms_step_first": "%.3f" % r.ms_per_step(first),
        "pair_ms_step": "%.3f" % r.frame_ms(),
        "settled_frame_us": "%.0f" % r.settled_frame_us(),
        "settled_need": "%.0f" % r.settled_need(),
        "settled_node_pairs": "%.0f" % r.settled_node_pairs(),
        "cut_share": "%.4f" % r.cut_share(), "lost": r.lost(),
        "first_lost_step": r.first_lost_step() or "",
        "probed_max": "%.5f" % r.probed_max(), "probed_mean": "%.5f" % r.probed_mean(),
        "probed_mean_end": "%.5f" % r.probed_mean_end(),
        "probed_max_first": "%.5f" % r.probed_max(first),
        "probed_mean_first": "%.5f" % r.probed_mean(first),
        "at_rest_end": r.at_rest_end(), "kinetic_end": "%.4f" % r.kinetic_end(),
        "at_rest_last_s": "%.1f" % r.at_rest_last_second(),
        "kinetic_last_s": "%.4f" % r.kinetic_last_second(),
        "prep_s": "" if r.prep_seconds is None else "%.2f" % r.prep_seconds,
        "hulls": "" if r.hulls is None else r.hulls,
        "hull_volume_ratio": r.hull_volume_ratio or "",
    }


def _write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def _find(results, scene, kind, seed=1, fraction=None):
    for r in results:
        s = r.spec
        if s.scene == scene and s.kind == kind and s.seed == seed and (
                fraction is None or (s.fraction and abs(s.fraction - fraction) < 1e-9)):
            return r
    return None


def quarter_rows(results, seeds):
    """The 1/4 node-pair budget against exact contacts on the same seed."""
    rows = []
    for scene in dict.fromkeys(r.spec.scene for r in results):
        for seed in range(1, seeds + 1):
            e = _find(results, scene, "exact", seed)
            q = _find(results, scene, "pairs", seed, 0.25)
            if not (e and q):
                continue
            max_ratio = _ratio(q.probed_max(), e.probed_max())
            settle_ratio = _ratio(q.kinetic_last_second(), e.kinetic_last_second())
            rows.append({
                "scene": scene, "seed": seed, "need": "%.0f" % e.settled_need(),
                "budget": "%.0f" % q.spec.budget,
                "lost_exact": e.lost(), "lost_quarter": q.lost(),
                "first_lost_step": q.first_lost_step() or "",
                "probed_max_exact": "%.5f" % e.probed_max(),
                "probed_max_quarter": "%.5f" % q.probed_max(),
                "probed_max_ratio": "%.2f" % max_ratio,
                "probed_mean_exact": "%.5f" % e.probed_mean(),
                "probed_mean_quarter": "%.5f" % q.probed_mean(),
                "probed_mean_ratio": "%.2f" % _ratio(q.probed_mean(), e.probed_mean()),
                "probed_mean_end_exact": "%.5f" % e.probed_mean_end(),
                "probed_mean_end_quarter": "%.5f" % q.probed_mean_end(),
                "at_rest_end_exact": e.at_rest_end(), "at_rest_end_quarter": q.at_rest_end(),
                "kinetic_last_s_exact": "%.4f" % e.kinetic_last_second(),
                "kinetic_last_s_quarter": "%.4f" % q.kinetic_last_second(),
                "kinetic_ratio": "%.2f" % settle_ratio,
                "no_body_lost": q.lost() == 0,
                "max_within_2x": max_ratio <= PENETRATION_FACTOR,
                "settles": settle_ratio <= SETTLING_FACTOR,
                "rests_apart": _ratio(q.probed_mean_end(), e.probed_mean_end())
                <= PENETRATION_FACTOR,
            })
    return rows


def _md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out)


def _yes(b):
    return "yes" if b else "**no**"


def write_all(results, a, elapsed_min):
    first = a.gimpact_steps
    _write_csv(os.path.join(a.out, "runs.csv"), [_row(r, first) for r in results])
    quarter = quarter_rows(results, a.seeds)
    if quarter:
        _write_csv(os.path.join(a.out, "quarter_seeds.csv"), quarter)

    md = ["# Budget sweep", "",
          "```sh", "/usr/bin/python3 " + " ".join(sys.argv), "```", "",
          "%s; %d runs, %.1f min of runs (this invocation: %.1f min); load average %.2f to "
          "%.2f during the runs; %d steps of 1/60 s (GImpact %d), body-body penetration "
          "probed from the geometry every %d steps."
          % (time.strftime("%Y-%m-%d"), len(results), sum(r.wall_seconds for r in results) / 60,
             elapsed_min, min(r.load_before for r in results),
             max(r.load_after for r in results), a.steps, a.gimpact_steps, a.probe_every), ""]

    for scene in dict.fromkeys(r.spec.scene for r in results):
        mine = [r for r in results if r.spec.scene == scene]
        exact = _find(results, scene, "exact", 1)
        md += ["## %s" % scene, "",
               "Need (exact contacts, mean node pairs per step over steps %d..end): %.0f; exact "
               "mode's adb pair time over the same steps: %.2f ms. Seed 1."
               % (SETTLED_FROM, exact.settled_need(), exact.settled_frame_us() / 1e3), ""]
        rows = []
        for r in mine:
            if r.spec.seed != 1:
                continue
            adb = r.spec.backend == "adb"
            rows.append([
                _label(r), _budget_text(r), "%.1f" % r.ms_per_step(),
                "%.1f" % r.frame_ms() if adb else "-",
                "%.0f %%" % (100 * r.cut_share()) if adb else "-",
                "%d%s" % (r.lost(), " (step %d)" % r.first_lost_step() if r.lost() else ""),
                _f(r.probed_max()), _f(_ratio(r.probed_max(), exact.probed_max()), 2),
                _f(r.probed_mean()), _f(_ratio(r.probed_mean(), exact.probed_mean()), 2),
                _f(r.probed_mean_end()), "%d/50" % r.at_rest_end(),
                _f(r.kinetic_last_second(), 3)])
        md += [_md_table(["run", "budget per step", "ms/step", "adb pairs ms/step", "pairs cut",
                          "lost (first)", "probed max", "x exact", "probed mean", "x exact",
                          "probed mean (end)", "at rest (end)", "KE last 1 s"], rows), ""]
        rows = []
        for r in mine:
            if r.spec.seed == 1 and (r.spec.kind in ("exact", "gimpact", "convex")
                                     or abs((r.spec.fraction or 0) - 0.25) < 1e-9):
                rows.append([_label(r), "%.1f" % r.ms_per_step(first), _f(r.probed_max(first)),
                             _f(r.probed_mean(first))])
        md += ["Over the first %d steps (what GImpact ran):" % first, "",
               _md_table(["run", "ms/step", "probed max", "probed mean"], rows), ""]
        convex = _find(results, scene, "convex", 1)
        if convex and convex.hulls is not None:
            md += ["Convex decomposition: %d hulls, prepared in %.1f s; hulls' volume over the "
                   "mesh's: %s." % (convex.hulls, convex.prep_seconds, convex.hull_volume_ratio),
                   ""]

    if quarter:
        md += ["## A quarter of the need, 4 seeds, against exact contacts", "",
               "Targets: no body lost; probed max penetration <= %gx exact's; settles = mean "
               "kinetic energy over the last %d steps <= %gx exact's (same seed). Added here: "
               "rests apart = the last probe's mean penetration <= %gx exact's (a pile frozen "
               "into itself has no kinetic energy either)."
               % (PENETRATION_FACTOR, LAST_SECOND, SETTLING_FACTOR, PENETRATION_FACTOR), ""]
        rows = [[q["scene"], q["seed"], q["budget"], "%s / %s" % (q["lost_exact"],
                 q["lost_quarter"]), "%s / %s" % (q["probed_max_exact"], q["probed_max_quarter"]),
                 q["probed_max_ratio"], "%s / %s" % (q["probed_mean_exact"],
                 q["probed_mean_quarter"]), q["probed_mean_ratio"],
                 "%s / %s" % (q["probed_mean_end_exact"], q["probed_mean_end_quarter"]),
                 "%s / %s" % (q["at_rest_end_exact"], q["at_rest_end_quarter"]),
                 "%s / %s" % (q["kinetic_last_s_exact"], q["kinetic_last_s_quarter"]),
                 _yes(q["no_body_lost"]), _yes(q["max_within_2x"]), _yes(q["settles"]),
                 _yes(q["rests_apart"])]
                for q in quarter]
        md += [_md_table(["scene", "seed", "budget", "lost exact / 1/4", "probed max exact / 1/4",
                          "ratio", "probed mean exact / 1/4", "ratio",
                          "probed mean at the end exact / 1/4", "at rest exact / 1/4",
                          "KE last 1 s exact / 1/4", "none lost", "max <= 2x", "settles",
                          "rests apart"], rows),
               ""]
    with open(os.path.join(a.out, "sweep.md"), "w") as f:
        f.write("\n".join(md))
