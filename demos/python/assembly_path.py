"""An assembly path checked for overlap: a square peg pushed through a ring along two paths,
one through the hole and one that grazes the rim, every pose answered under a node-pair
budget with the confidence of its answer, then checked against exact answers.

    python3 demos/python/assembly_path.py [--samples 400] [--budget-pairs 100] [--out path.png]
"""
import argparse

import matplotlib.pyplot as plt
import numpy as np

import adb

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--samples", type=int, default=400)
parser.add_argument("--budget-pairs", type=int, default=100)
parser.add_argument("--out", default="assembly_path.png")
args = parser.parse_args()


def box(half, n=8):
    """A closed box of half extents `half`, each face split into n x n squares (two
    triangles each), facing out: what a CAD part's tessellation looks like to the tree."""
    grid = np.linspace(-1, 1, n + 1)
    u, v = [a.ravel() for a in np.meshgrid(grid, grid, indexing="ij")]
    cells = np.array([[i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1,
                       i * (n + 1) + j + 1] for i in range(n) for j in range(n)])
    vertices, faces = [], []
    for axis in range(3):
        for sign in (-1, 1):
            face = np.zeros((len(u), 3))
            face[:, axis] = sign
            face[:, (axis + 1) % 3], face[:, (axis + 2) % 3] = u, v * sign  # outward winding
            base = len(vertices) * len(u)
            vertices.append(face)
            faces += [[base + a, base + b, base + c] for a, b, c, d in cells] + \
                     [[base + a, base + c, base + d] for a, b, c, d in cells]
    return adb.Mesh(np.vstack(vertices) * half, np.array(faces), "peg")


ring = adb.Tree(adb.model("torus", 4000))  # around z: hole radius 0.35, tube 0.25
peg = adb.Tree(box([0.15, 0.15, 0.6]))
along = np.linspace(-2.0, 2.0, args.samples)
fig, ax = plt.subplots(figsize=(8, 4))
for name, offset in (("through the hole", 0.0), ("grazing the rim", 0.28)):
    poses = np.tile(np.eye(4), (args.samples, 1, 1))
    poses[:, 0, 3] = offset
    poses[:, 2, 3] = along
    quick = adb.collide_many(ring, np.eye(4), peg, poses, budget_pairs=args.budget_pairs)
    exact = adb.collide_many(ring, np.eye(4), peg, poses, mode="exact")
    wrong = quick["collides"] != exact["collides"]
    unsure = quick["confidence"] < 0.99
    print(f"{name}: {exact['collides'].sum()} of {args.samples} poses overlap; under "
          f"{args.budget_pairs} node pairs a pose, {wrong.sum()} answers wrong, "
          f"{unsure.sum()} below 0.99 confidence (of which {(wrong & unsure).sum()} of the "
          f"wrong ones), {1e6 * quick['seconds'].mean():.1f} us a pose against "
          f"{1e6 * exact['seconds'].mean():.1f} us exact")
    ax.plot(along, np.where(quick["collides"], quick["confidence"], -quick["confidence"]),
            label=f"{name}: confidence, signed by the answer")
    ax.fill_between(along, -1, 1, where=exact["collides"], alpha=0.12,
                    label=f"{name}: exact overlap")
ax.set(xlabel="peg position along the ring's axis", ylabel="+ overlap / - free",
       ylim=(-1.05, 1.05), title="Peg through a ring: answers and their confidence")
ax.legend(fontsize=7, loc="center left")
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(args.out, dpi=110)
print(f"wrote {args.out}")
