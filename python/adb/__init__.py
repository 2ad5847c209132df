"""adb: collision queries between concave triangle meshes under a time or work budget, with
the probability that each answer is right (ADB-trees), and Bullet scenes simulated with them.

The compiled part is adb._adb; this package adds CollisionManager, which follows trimesh's
collision manager call by call. docs/python.md sets the API next to python-fcl's and
trimesh's.
"""

from __future__ import annotations

from typing import Any, Dict, Iterable, List, Optional, Set, Tuple, Union

import numpy as np

from ._adb import (
    Mesh,
    MeshError,
    PoseError,
    Result,
    Scene,
    SceneError,
    SettingsError,
    Tree,
    World,
    benchmark_poses,
    check_pose,
    collide,
    collide_many,
    load_mesh,
    model,
    model_names,
    poses_from_quaternions,
)

__all__ = [
    "CollisionManager",
    "Contact",
    "Mesh",
    "MeshError",
    "PoseError",
    "Result",
    "Scene",
    "SceneError",
    "SettingsError",
    "Tree",
    "World",
    "benchmark_poses",
    "check_pose",
    "collide",
    "collide_many",
    "load_mesh",
    "model",
    "model_names",
    "poses_from_quaternions",
]

_IDENTITY = np.eye(4)
# A one-triangle tree, for checking a CollisionManager's settings when it is made.
_POINT_TREE = Tree(Mesh(np.eye(3), np.array([[0, 1, 2]]), "settings check"))

MeshLike = Union[Mesh, Tree, Any]


def _tree_of(mesh: MeshLike, name: str) -> Tree:
    """A Tree for an adb.Tree, an adb.Mesh, or any object with `vertices` and `faces` arrays
    (a trimesh.Trimesh)."""
    if isinstance(mesh, Tree):
        return mesh
    if isinstance(mesh, Mesh):
        return Tree(mesh)
    vertices = getattr(mesh, "vertices", None)
    faces = getattr(mesh, "faces", None)
    if vertices is None or faces is None:
        raise MeshError(
            f"{name}: expected an adb.Mesh, an adb.Tree or an object with 'vertices' and "
            f"'faces' arrays, got {type(mesh).__name__}"
        )
    return Tree(Mesh(np.asarray(vertices), np.asarray(faces), name))


class Contact:
    """One colliding pair of a CollisionManager query, as trimesh's ContactData: the two
    names, a contact point and depth where an intersecting triangle pair was found, the
    triangle of each object (index(name)), and what adb adds: the confidence of the answer.
    """

    def __init__(self, names: Tuple[str, str], result: Result):
        self.names: Set[str] = set(names)
        self.confidence: float = result.confidence
        self.stop: str = result.stop
        self._index: Dict[str, int] = {}
        self.point: Optional[np.ndarray] = None
        self.normal: Optional[np.ndarray] = None
        self.depth: Optional[float] = None
        triangles = result.witnesses
        if len(triangles) and triangles[0][0] >= 0:
            self._index = {names[0]: int(triangles[0][0]), names[1]: int(triangles[0][1])}
            contacts = result.contacts()
            self.point = contacts["points"][0]
            self.normal = contacts["normals"][0]
            self.depth = float(contacts["depths"][0])

    def index(self, name: str) -> Optional[int]:
        """The triangle of object `name` in the contact (None for a pair accepted on
        probability, which names no triangle)."""
        return self._index.get(name)

    def __repr__(self) -> str:
        return f"<adb.Contact {sorted(self.names)} confidence={self.confidence:.4f}>"


class CollisionManager:
    """trimesh.collision.CollisionManager's calls over adb's queries: add objects with a pose,
    move them, ask whether anything collides. Every pair is one adb.collide under the
    settings given here (mode, p_min, k_min, budget_us, budget_pairs), and every answer has a
    confidence: `last_confidence` after each call, `Contact.confidence` per pair.

    The confidence of a whole answer: for "collision", the highest confidence among the pairs
    that said yes (one right yes suffices); for "no collision", the product of every tested
    pair's confidence (each no must be right, taken as independent). Pairs whose bounding
    boxes are apart are certain and count as 1.
    """

    def __init__(self, **settings: Any):
        self._settings = dict(settings)
        collide_keys = {"mode", "p_min", "k_min", "budget_us", "budget_pairs",
                        "stop_at_first_hit", "max_witnesses", "contact_margin"}
        unknown = set(settings) - collide_keys
        if unknown:
            raise SettingsError(f"unknown setting(s) {sorted(unknown)}; known: "
                                f"{sorted(collide_keys)}")
        # The settings checked now, not at the first query: an empty batch runs no query.
        collide_many(_POINT_TREE, _IDENTITY, _POINT_TREE, np.zeros((0, 4, 4)), **settings)
        self._objects: Dict[str, Tuple[Tree, np.ndarray]] = {}
        #: The probability that the last call's answer is right.
        self.last_confidence: float = 1.0

    # --- objects ------------------------------------------------------------------------
    def add_object(self, name: str, mesh: MeshLike, transform: Optional[Any] = None) -> None:
        """Adds (or replaces) object `name`: an adb.Mesh, an adb.Tree (shared, not copied) or
        a trimesh-like mesh, at `transform` (4x4; identity when None)."""
        pose = _IDENTITY if transform is None else self._checked_pose(transform, name)
        self._objects[name] = (_tree_of(mesh, name), pose)

    def remove_object(self, name: str) -> None:
        """Removes object `name`; ValueError if there is none (as trimesh)."""
        if name not in self._objects:
            raise ValueError(f"{name} not in collision manager!")
        del self._objects[name]

    def set_transform(self, name: str, transform: Any) -> None:
        """Moves object `name` to `transform` (4x4); ValueError if there is none."""
        if name not in self._objects:
            raise ValueError(f"{name} not in collision manager!")
        self._objects[name] = (self._objects[name][0], self._checked_pose(transform, name))

    @property
    def names(self) -> List[str]:
        return list(self._objects)

    # --- queries ------------------------------------------------------------------------
    def in_collision_single(self, mesh: MeshLike, transform: Optional[Any] = None,
                            return_names: bool = False, return_data: bool = False):
        """Whether `mesh` at `transform` collides with any object of the manager. With
        return_names also the set of names it collides with, with return_data the list of
        Contact objects, as trimesh returns them."""
        tree = _tree_of(mesh, "mesh")
        pose = _IDENTITY if transform is None else self._checked_pose(transform, "mesh")
        pairs = [((name, "__external"), obj_tree, obj_pose, tree, pose)
                 for name, (obj_tree, obj_pose) in self._objects.items()]
        hits = self._run(pairs)
        names = {names[0] for names, _ in hits}
        return self._answer(hits, names, return_names, return_data)

    def in_collision_internal(self, return_names: bool = False, return_data: bool = False):
        """Whether any two objects of the manager collide. return_names: the set of colliding
        (name, name) tuples, each sorted; return_data: the Contact list."""
        items = list(self._objects.items())
        pairs = []
        for i in range(len(items)):
            for j in range(i + 1, len(items)):
                (na, (ta, pa)), (nb, (tb, pb)) = items[i], items[j]
                key = tuple(sorted((na, nb)))
                first, second = ((ta, pa), (tb, pb)) if key[0] == na else ((tb, pb), (ta, pa))
                pairs.append((key, first[0], first[1], second[0], second[1]))
        hits = self._run(pairs)
        return self._answer(hits, {names for names, _ in hits}, return_names, return_data)

    def in_collision_other(self, other_manager: "CollisionManager", return_names: bool = False,
                           return_data: bool = False):
        """Whether any object of this manager collides with any of `other_manager`'s.
        return_names: the set of (this name, other name) tuples."""
        pairs = [((na, nb), ta, pa, tb, pb)
                 for na, (ta, pa) in self._objects.items()
                 for nb, (tb, pb) in other_manager._objects.items()]
        hits = self._run(pairs)
        return self._answer(hits, {names for names, _ in hits}, return_names, return_data)

    # --- inside -------------------------------------------------------------------------
    @staticmethod
    def _checked_pose(transform: Any, name: str) -> np.ndarray:
        return check_pose(transform, f"{name}: transform")

    def _run(self, pairs) -> List[Tuple[Tuple[str, str], Result]]:
        hits: List[Tuple[Tuple[str, str], Result]] = []
        no_confidence = 1.0
        for names, tree_a, pose_a, tree_b, pose_b in pairs:
            result = collide(tree_a, pose_a, tree_b, pose_b, **self._settings)
            if result.collides:
                hits.append((names, result))
            else:
                no_confidence *= result.confidence
        self.last_confidence = (max(r.confidence for _, r in hits) if hits
                                else no_confidence)
        return hits

    @staticmethod
    def _answer(hits, names, return_names: bool, return_data: bool):
        collides = bool(hits)
        if not (return_names or return_data):
            return collides
        out: List[Any] = [collides]
        if return_names:
            out.append(names)
        if return_data:
            out.append([Contact(n, r) for n, r in hits])
        return tuple(out)
