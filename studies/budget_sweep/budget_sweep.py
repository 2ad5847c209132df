#!/usr/bin/python3
"""Budget sweep (issue 44): what a per-step budget of 1/4, 1/8 and 1/16 of what exact contacts
need costs a pile, on the scenes of docs/bullet-results.md.

For each scene: exact contacts (adb's exact backend, no budget), whose need N is the mean
`from_scratch_node_pairs` over steps 100 to 400 (docs/bullet-results.md's definition), then adb
under `--budget-pairs` N/4, N/8 and N/16, and with --gimpact GImpact (slow on big piles). Every run is 1,200 steps (--steps), probes body-body penetration
from the geometry every --probe-every steps, and lets Bullet put bodies to sleep.

Writes, in --out: runs/NAME/ (each run's steps.csv, summary.json, stdout, command), runs.csv
(every figure), results.md (the table: lost, all asleep from, energy, resting penetration,
step time, budget use, targets missed) and results.png. Progress goes to stderr. Runs
already in --out with the same command are reused (--rerun repeats them).

    /usr/bin/python3 studies/budget_sweep/budget_sweep.py --out out/budget-sweep
"""

import argparse
import os
import sys
import time

import plots
import tables
from runs import RunSpec, run

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FRACTIONS = (1 / 4, 1 / 8, 1 / 16)


def scenes(meshes, repo):
    """The piles of docs/bullet-results.md ("How to reproduce" lists them) and the robot room."""
    made = {}
    for floor in ("plane", "box", "mesh"):
        for model in ("gears", "knot", "pipes"):
            made["%s-%s" % (floor, model)] = ["--model", model, "--triangles", "3000",
                                              "--bodies", "50", "--floor", floor]
    for name in ("bunny.obj", "teddy.obj", "fandisk.obj", "diff_arm.stl", "quadrotor_base.obj"):
        made["box-" + name.split(".")[0]] = ["--mesh", os.path.join(meshes, name),
                                            "--bodies", "50", "--floor", "box"]
    made["gallery"] = ["--scene", os.path.join(repo, "demos", "scenes", "pile.json")]
    made["slivers"] = ["--model", "slivers", "--triangles", "2000", "--bodies", "30",
                       "--floor", "box"]
    made["robot-room"] = ["--scene", os.path.join(repo, "demos", "scenes", "robot_room.json")]
    return made


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--demo", default=os.path.join(REPO, "build", "bin", "adb-demo"))
    p.add_argument("--meshes", default=os.path.join(os.path.dirname(REPO), "shared", "meshes"))
    p.add_argument("--out", default=os.path.join(REPO, "out", "budget-sweep"))
    p.add_argument("--scenes", nargs="+", help="scene keys (default: all)")
    p.add_argument("--steps", type=int, default=1200)
    p.add_argument("--probe-every", type=int, default=60)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--gimpact", action="store_true", help="also GImpact (its sleep time)")
    p.add_argument("--rerun", action="store_true", help="repeat runs already in --out")
    a = p.parse_args()
    if not os.access(a.demo, os.X_OK):
        sys.exit("budget_sweep: no adb-demo at %s (build first, or --demo)" % a.demo)
    known = scenes(a.meshes, REPO)
    a.scenes = a.scenes or list(known)
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
        what = s.kind if s.fraction is None else "1/%d" % round(1 / s.fraction)
        asleep = summary.all_asleep_from()
        print("[%2d/%d] %-14s %-8s %6.1f s%s, lost %d, asleep from %s  (elapsed %.1f min)"
              % (self.done, self.total, s.scene, what, summary.wall_seconds,
                 " (reused)" if summary.reused else "", summary.lost(),
                 asleep if asleep else "-", (time.monotonic() - self.t0) / 60),
              file=sys.stderr, flush=True)


def main():
    a = parse()
    os.makedirs(a.out, exist_ok=True)
    made = scenes(a.meshes, REPO)
    per_scene = 1 + len(FRACTIONS) + (1 if a.gimpact else 0)
    progress = Progress(per_scene * len(a.scenes))
    started = time.monotonic()
    results = []
    for scene in a.scenes:
        def go(backend, kind, fraction=None, budget=None):
            spec = RunSpec(scene, made[scene], backend, kind, a.seed, a.steps, a.probe_every,
                           fraction, budget)
            summary = run(spec, a.demo, a.out, reuse=not a.rerun)
            progress.report(summary)
            results.append(summary)
            return summary

        need = go("exact", "exact").settled_need()
        if a.gimpact:
            go("gimpact", "gimpact")
        for f in FRACTIONS:
            go("adb", "fraction", f, max(1, round(f * need)))
    elapsed = (time.monotonic() - started) / 60
    command = "/usr/bin/python3 studies/budget_sweep/budget_sweep.py " + " ".join(
        arg for arg in sys.argv[1:] if arg != "--rerun")
    tables.write_all(results, a, elapsed, command)
    plots.write_all(results, a)
    print("budget_sweep: %d runs, %.1f min; table in %s/results.md" % (
        len(results), elapsed, a.out), file=sys.stderr)


if __name__ == "__main__":
    main()
