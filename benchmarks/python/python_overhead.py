"""What the Python module costs over the C++ it calls, both measured in one run (issue 28's
targets; docs/python.md has the figures):

1. collide_many over ~10,000 poses against the same queries in adb-tradeoff's C++ loop: the
   tool's per-query CSV gives the poses and each query's time (--repeats 1), cold
   (--no-warmup, as a batch meets them) and warm (after an untimed run of the same query,
   the study's procedure); Python answers the same poses in one call. Three rounds, the
   fastest of each kept; also the queries' own time inside the call, which separates what
   the binding adds from the machine's noise.
2. A scene stepped by adb.World against adb-demo's steps on the same scene under a node-pair
   budget (the same work in both): Python's wall clock around world.step(n) per step against
   the mean of adb-demo's own step times (steps.csv `seconds`), best of 5 alternating runs
   each; Python's own step times too, which separate the loop's cost from run-to-run noise.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python/python_overhead.py [--bin build/bin]
"""
import argparse
import csv
import pathlib
import subprocess
import tempfile
import time

import numpy as np

import adb

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--bin", default="build/bin", help="where adb-tradeoff and adb-demo are")
parser.add_argument("--model", default="knot:5000")
parser.add_argument("--rotations", type=int, default=600, help="per distance (17 distances)")
parser.add_argument("--scene", default=str(pathlib.Path(__file__).parents[2] / "demos" /
                                          "scenes" / "pile.json"))
parser.add_argument("--steps", type=int, default=200)
parser.add_argument("--budget-pairs", type=int, default=20000)
args = parser.parse_args()
tool_dir = pathlib.Path(args.bin)


def poses(rows, side):
    """The CSV's poses, made as the tool made them (Pose::fromQuaternion)."""
    return adb.poses_from_quaternions(
        [[float(r[f"{side}_q{c}"]) for c in "wxyz"] for r in rows],
        [[float(r[f"{side}_t{c}"]) for c in "xyz"] for r in rows])


def best_of(n, run):
    best = float("inf")
    for _ in range(n):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    # 1. Batched queries: three rounds, each the tool then Python, the fastest of each kept.
    name, triangles = args.model.split(":")
    tree = adb.Tree(adb.model(name, int(triangles)))
    methods = (("exact", {"mode": "exact"}), ("adb", {"p_min": 0.99, "k_min": 10}))
    cpp, cold, wall, inner, same = {}, {}, {}, {}, {}
    tool = [str(tool_dir / "adb-tradeoff"), "--model", args.model, "--distances", "0.4:2.0:0.1",
            "--rotations", str(args.rotations), "--methods", "exact,adb", "--p-min", "0.99",
            "--k-min", "10", "--budget-us", "none", "--repeats", "1", "--no-plots"]

    def run_tool(out, flags):
        subprocess.run(tool + ["--out", str(out)] + flags, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return list(csv.DictReader(open(out / "queries.csv")))

    def of(rows, method):
        return [r for r in rows if r["method"] == method and r["budget_us"] == ""]

    def seconds(rows):
        return sum(float(r["time_ns"]) for r in rows) * 1e-9

    for round_ in range(3):
        print(f"round {round_ + 1}: adb-tradeoff {args.model}, 17 distances x "
              f"{args.rotations} rotations, warm and cold, then Python", flush=True)
        warm_rows = run_tool(tmp / "warm", [])
        cold_rows = run_tool(tmp / "cold", ["--no-warmup"])
        for method, settings in methods:
            chosen = of(warm_rows, method)
            cpp[method] = min(cpp.get(method, 1e9), seconds(chosen))
            cold[method] = min(cold.get(method, 1e9), seconds(of(cold_rows, method)))
            pa, pb = poses(chosen, "a"), poses(chosen, "b")
            start = time.perf_counter()
            answers = adb.collide_many(tree, pa, tree, pb, **settings)
            wall[method] = min(wall.get(method, 1e9), time.perf_counter() - start)
            inner[method] = min(inner.get(method, 1e9), answers["seconds"].sum())
            same[method] = np.array_equal(answers["collides"],
                                          [r["collides"] == "1" for r in chosen])
    for method, _ in methods:
        print(f"collide_many, {method:>5}, {len(chosen)} poses: Python {wall[method] * 1e3:.1f} "
              f"ms; the C++ loop cold (--no-warmup) {cold[method] * 1e3:.1f} ms: "
              f"{wall[method] / cold[method]:.3f}x (target <= 1.2x); warm (each query after an "
              f"untimed run of itself) {cpp[method] * 1e3:.1f} ms: "
              f"{wall[method] / cpp[method]:.3f}x; the queries' own time in the call "
              f"{inner[method] * 1e3:.1f} ms: the binding adds "
              f"{100 * (wall[method] / inner[method] - 1):.1f} %; same answers: {same[method]}")

    # 2. Scene steps.
    scene = adb.Scene.load(args.scene)
    scene.steps = args.steps
    scene.budget_pairs = args.budget_pairs
    demo_means, python_steps, python_own = [], [], []
    for run in range(5):
        out = tmp / f"demo{run}"
        subprocess.run([str(tool_dir / "adb-demo"), "--scene", args.scene, "--steps",
                        str(args.steps), "--budget-pairs", str(args.budget_pairs), "--out",
                        str(out)], check=True, stdout=subprocess.DEVNULL)
        demo_means.append(np.mean([float(r["seconds"]) for r in
                                   csv.DictReader(open(out / "steps.csv"))]))
        world = adb.World(scene)
        start = time.perf_counter()
        world.step(args.steps)
        python_steps.append((time.perf_counter() - start) / args.steps)
        python_own.append(world.stats()["seconds"].mean())
    demo, python, own = min(demo_means), min(python_steps), min(python_own)
    print(f"scene step, {pathlib.Path(args.scene).name}, {args.steps} steps at "
          f"{args.budget_pairs} node pairs: Python {python * 1e3:.3f} ms (wall clock of "
          f"world.step), adb-demo {demo * 1e3:.3f} ms (its steps' own time): "
          f"{python / demo:.3f}x (target <= 1.05x); Python's steps' own time {own * 1e3:.3f} "
          f"ms: the loop adds {100 * (python / own - 1):.1f} %")
