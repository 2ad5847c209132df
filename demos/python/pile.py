"""A pile stepped under a budget: concave bodies dropped into a bin, first with exact contacts
to learn what they need, then under a fraction of it, with a picture of each and their step
times plotted.

    python3 demos/python/pile.py [--bodies 30] [--steps 300] [--fraction 0.25] [--out DIR]
"""
import argparse
import pathlib

import matplotlib.pyplot as plt
import numpy as np

import adb

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--bodies", type=int, default=30)
parser.add_argument("--steps", type=int, default=300)
parser.add_argument("--fraction", type=float, default=0.25, help="of exact contacts' node pairs")
parser.add_argument("--threads", type=int, default=1)
parser.add_argument("--out", default="pile")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

scene = adb.Scene.pile(bodies=args.bodies, triangles=1500, floor="box", steps=args.steps)
runs = {}
for name in ("exact", "budget"):
    if name == "budget":  # a node-pair budget: the same run on any machine and thread count
        scene.budget_pairs = max(1, int(args.fraction * runs["exact"]["node_pairs"].mean()))
    world = adb.World(scene, backend="exact" if name == "exact" else "adb", threads=args.threads)
    world.step(args.steps)
    world.render(out / f"{name}.png")
    runs[name] = stats = world.stats()
    print(f"{name:>6}: {1e3 * stats['seconds'].mean():.2f} ms a step, "
          f"{stats['node_pairs'].mean():,.0f} node pairs, {stats['at_rest'][-1]} of "
          f"{args.bodies} at rest, deepest contact {stats['penetration'].max():.4f}, "
          f"{stats['lost'].max()} lost, worst confidence {stats['worst_confidence'].min():.3f}"
          + (f" (budget {scene.budget_pairs:,} node pairs)" if name == "budget" else ""))

fig, ax = plt.subplots(figsize=(7, 4))
for name, stats in runs.items():
    ax.plot(stats["step"], 1e3 * stats["seconds"], label=name, lw=1)
ax.set(xlabel="step", ylabel="step time (ms)", title=f"{args.bodies} bodies in a bin")
ax.legend()
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out / "step_times.png", dpi=110)
print(f"wrote {out}/exact.png, {out}/budget.png and {out}/step_times.png")
