#!/usr/bin/python3
"""Budget sweep of adb-demo's 50-body pile (issue 11, item 2): what a per-step budget costs
in penetration, lost bodies and settling, against exact contacts, GImpact and a convex
decomposition.

For each scene (all in the btBoxShape bin, --floor box):
  * exact contacts (no budget), seed 1: the need (mean needed_node_pairs over steps
    100..end) and exact mode's pair time (mean frame_us over the same steps);
  * adb with node-pair budgets of 1/2, 1/4, 1/8 of the need and time budgets of 1/2, 1/4,
    1/8 of that time, seed 1;
  * seeds 2..4: exact, and 1/4 of that seed's own need;
  * GImpact (its first --gimpact-steps steps: it is slow on big meshes) and the convex
    decomposition (--backend convex), seed 1.
Every run probes body-body penetration from the geometry every --probe-every steps.

Writes, in --out: runs/NAME/ (each run's steps.csv, stdout, command), runs.csv (every run),
quarter_seeds.csv (1/4 budget against exact, per seed), sweep.md (the tables),
penetration.png and time.png. Progress goes to stderr. Runs already in --out with the same
command are reused (--rerun repeats them).

    /usr/bin/python3 studies/budget_sweep/budget_sweep.py --out out/budget-sweep
"""

import argparse
import os
import sys
import time

import plots
import tables
from runs import SETTLED_FROM, RunSpec, run

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FRACTIONS = (1 / 2, 1 / 4, 1 / 8)
QUARTER = 1 / 4


def scenes(meshes):
    box = ["--bodies", "50", "--floor", "box"]
    made = {"generated": box + ["--triangles", "3000"]}
    for name in ("fandisk", "homer", "spot"):
        made[name] = box + ["--mesh", os.path.join(meshes, name + ".obj")]
    return made


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--demo", default=os.path.join(REPO, "build", "bin", "adb-demo"))
    p.add_argument("--meshes", default=os.path.join(os.path.dirname(REPO), "shared", "meshes"))
    p.add_argument("--out", default=os.path.join(REPO, "out", "budget-sweep"))
    p.add_argument("--scenes", nargs="+", default=["generated", "fandisk", "homer", "spot"])
    p.add_argument("--steps", type=int, default=600, help="steps of adb, exact and convex runs")
    p.add_argument("--gimpact-steps", type=int, default=120,
                   help="steps of the GImpact runs (compared over these first steps)")
    p.add_argument("--probe-every", type=int, default=20)
    p.add_argument("--seeds", type=int, default=4, help="seeds of the 1/4 budget and exact")
    p.add_argument("--rerun", action="store_true", help="repeat runs already in --out")
    a = p.parse_args()
    if a.steps <= SETTLED_FROM:
        # The need and exact mode's time are measured over the settled steps only.
        sys.exit("budget_sweep: --steps must exceed %d (the need is measured from step %d on)"
                 % (SETTLED_FROM, SETTLED_FROM))
    if not os.access(a.demo, os.X_OK):
        sys.exit("budget_sweep: no adb-demo at %s (build first, or --demo)" % a.demo)
    known = scenes(a.meshes)
    for s in a.scenes:
        if s not in known:
            sys.exit("budget_sweep: unknown scene %s (known: %s)" % (s, ", ".join(known)))
    return a


class Progress:
    def __init__(self, total):
        self.total, self.done, self.t0 = total, 0, time.monotonic()

    def report(self, summary):
        self.done += 1
        s = summary.spec
        what = s.kind if s.fraction is None else "%s 1/%d" % (s.kind, round(1 / s.fraction))
        print("[%2d/%d] %-9s %-12s seed %d: %6.1f s%s, lost %d, probed max %.4f  "
              "(elapsed %.1f min)"
              % (self.done, self.total, s.scene, what, s.seed, summary.wall_seconds,
                 " (reused)" if summary.reused else "", summary.lost(), summary.probed_max(),
                 (time.monotonic() - self.t0) / 60), file=sys.stderr, flush=True)


def main():
    a = parse()
    os.makedirs(a.out, exist_ok=True)
    made = scenes(a.meshes)
    per_scene = 1 + 2 * len(FRACTIONS) + 2 * (a.seeds - 1) + 2
    progress = Progress(per_scene * len(a.scenes))
    started = time.monotonic()
    results = []

    def go(spec):
        summary = run(spec, a.demo, a.out, reuse=not a.rerun)
        progress.report(summary)
        results.append(summary)
        return summary

    for scene in a.scenes:
        args = made[scene]

        def spec(kind, seed, backend="adb", steps=a.steps, fraction=None, budget=None):
            return RunSpec(scene, args, backend, kind, seed, steps, a.probe_every, fraction,
                           budget)

        exact = go(spec("exact", 1))
        need, exact_us = exact.settled_need(), exact.settled_frame_us()
        for f in FRACTIONS:
            go(spec("pairs", 1, fraction=f, budget=round(f * need)))
        for f in FRACTIONS:
            go(spec("time", 1, fraction=f, budget=f * exact_us))
        for seed in range(2, a.seeds + 1):
            seed_need = go(spec("exact", seed)).settled_need()
            go(spec("pairs", seed, fraction=QUARTER, budget=round(QUARTER * seed_need)))
        go(spec("gimpact", 1, backend="gimpact", steps=a.gimpact_steps))
        go(spec("convex", 1, backend="convex"))

    elapsed = (time.monotonic() - started) / 60
    tables.write_all(results, a, elapsed)
    plots.write_all(results, a)
    print("budget_sweep: %d runs, %.1f min (the runs' own time, reused ones included: %.1f "
          "min); tables in %s/sweep.md" % (len(results), elapsed,
                                           sum(r.wall_seconds for r in results) / 60, a.out),
          file=sys.stderr)


if __name__ == "__main__":
    main()
