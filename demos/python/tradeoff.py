"""What accuracy costs in time, on one mesh: exact answers against ADB's quality targets and
budgets, over random poses of two copies (docs/benchmark.md's procedure), plotted.

    python3 demos/python/tradeoff.py [MESH_FILE] [--poses 4000] [--out tradeoff.png]
"""
import argparse

import matplotlib.pyplot as plt
import numpy as np

import adb

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("mesh", nargs="?", help="a mesh file (default: the generated knot)")
parser.add_argument("--poses", type=int, default=4000)
parser.add_argument("--out", default="tradeoff.png")
args = parser.parse_args()

mesh = adb.load_mesh(args.mesh) if args.mesh else adb.model("knot", 5000)
tree = adb.Tree(mesh)
# Two copies at random turns, their centres 0.4 to 2 benchmark units apart (docs/benchmark.md).
distances = np.random.default_rng(1).uniform(0.4, 2.0, args.poses)
poses_a, poses_b = adb.benchmark_poses(mesh, distances)

exact = adb.collide_many(tree, poses_a, tree, poses_b, mode="exact")
methods = {"exact": {"mode": "exact"}}
methods.update({f"p_min {p}": {"p_min": p, "k_min": 10} for p in (0.5, 0.9, 0.99)})
methods.update({f"{b} us": {"budget_us": b} for b in (5, 20, 80)})
methods.update({f"{n} node pairs": {"budget_pairs": n} for n in (50, 200, 800)})
fig, ax = plt.subplots(figsize=(7, 4.5))
for name, settings in methods.items():
    r = adb.collide_many(tree, poses_a, tree, poses_b, **settings)
    error = 100 * np.mean(r["collides"] != exact["collides"])
    micros = 1e6 * r["seconds"].mean()
    print(f"{name:>16}: {micros:8.1f} us a query, {error:5.2f} % wrong, "
          f"mean confidence {r['confidence'].mean():.3f}")
    ax.scatter(micros, error, label=name)
ax.set(xscale="log", xlabel="mean time per query (us)", ylabel="wrong answers (%)",
       title=f"{mesh.name}: {mesh.triangle_count} triangles, {args.poses} poses")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(args.out, dpi=110)
print(f"wrote {args.out}")
