"""adb.CollisionManager: trimesh's CollisionManager calls and meanings, plus the confidence."""

import numpy as np
import pytest

import adb
from conftest import translation


@pytest.fixture(scope="module")
def parts():
    return {"torus": adb.Tree(adb.model("torus", 1500)), "knot": adb.Tree(adb.model("knot", 1500))}


def test_internal_collisions_with_names_and_data(parts):
    manager = adb.CollisionManager(mode="exact")
    manager.add_object("a", parts["torus"])
    manager.add_object("b", parts["torus"], translation(0.5))
    manager.add_object("c", parts["knot"], translation(10))
    assert manager.in_collision_internal() is True
    collides, names = manager.in_collision_internal(return_names=True)
    assert collides and names == {("a", "b")}
    collides, names, data = manager.in_collision_internal(return_names=True, return_data=True)
    assert len(data) == 1 and data[0].names == {"a", "b"}
    contact = data[0]
    assert contact.confidence == 1.0
    assert 0 <= contact.index("a") < 1500 * 2 and contact.index("b") is not None
    assert contact.point.shape == (3,) and contact.depth >= 0
    assert manager.last_confidence == 1.0
    manager.set_transform("b", translation(5))
    assert manager.in_collision_internal() is False
    assert manager.last_confidence == 1.0  # exact: every no is certain


def test_names_are_sorted_tuples_as_trimesh_gives_them(parts):
    manager = adb.CollisionManager()
    manager.add_object("zeta", parts["torus"])
    manager.add_object("alpha", parts["torus"], translation(0.3))
    _, names = manager.in_collision_internal(return_names=True)
    assert names == {("alpha", "zeta")}


def test_single_and_other(parts):
    manager = adb.CollisionManager(mode="exact")
    manager.add_object("ring", parts["torus"])
    mesh = adb.model("knot", 1500)  # a Mesh: its tree is built on the fly
    assert manager.in_collision_single(mesh) is True
    collides, names = manager.in_collision_single(mesh, translation(8), return_names=True)
    assert not collides and names == set()
    other = adb.CollisionManager()
    other.add_object("k", parts["knot"], translation(0.2))
    collides, names = manager.in_collision_other(other, return_names=True)
    assert collides and names == {("ring", "k")}


def test_trimesh_like_objects_are_accepted(parts):
    class Trimeshish:
        def __init__(self, mesh):
            self.vertices = mesh.vertices
            self.faces = mesh.triangles

    manager = adb.CollisionManager(mode="exact")
    manager.add_object("t", Trimeshish(adb.model("torus", 1000)))
    assert manager.in_collision_single(parts["torus"])
    with pytest.raises(adb.MeshError, match="expected an adb.Mesh"):
        manager.add_object("bad", object())


def test_a_budget_gives_a_confidence_below_one(parts):
    manager = adb.CollisionManager(budget_pairs=4)
    manager.add_object("a", parts["knot"])
    manager.add_object("b", parts["knot"], translation(0.4, 0.2))
    collides, data = manager.in_collision_internal(return_data=True)
    assert 0.0 <= manager.last_confidence <= 1.0
    if collides:
        assert data[0].stop == "work budget" and data[0].confidence < 1.0
    else:
        assert manager.last_confidence < 1.0


def test_errors(parts):
    manager = adb.CollisionManager()
    with pytest.raises(ValueError, match="nothing not in collision manager"):
        manager.remove_object("nothing")
    with pytest.raises(ValueError, match="nothing not in collision manager"):
        manager.set_transform("nothing", np.eye(4))
    with pytest.raises(adb.PoseError, match="part: transform: .*orthonormal"):
        manager.add_object("part", parts["torus"], np.diag([2.0, 1, 1, 1]))
    with pytest.raises(adb.SettingsError, match="unknown setting"):
        adb.CollisionManager(pmin=0.5)
    with pytest.raises(adb.SettingsError, match="p_min"):
        adb.CollisionManager(p_min=7)  # named when made, not at the first query
    manager.add_object("x", parts["torus"])
    manager.remove_object("x")
    assert manager.names == []
