"""adb.Mesh, adb.Tree and adb.load_mesh: arrays in and out, files, and every bad input named."""

import numpy as np
import pytest

import adb
from conftest import write_obj

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
TETRA_T = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def test_a_mesh_keeps_its_arrays():
    mesh = adb.Mesh(TETRA_V, TETRA_T, "tetra")
    assert mesh.name == "tetra"
    assert mesh.triangle_count == 4 and mesh.vertex_count == 4
    np.testing.assert_array_equal(mesh.vertices, TETRA_V)
    np.testing.assert_array_equal(mesh.triangles, TETRA_T)
    np.testing.assert_array_equal(mesh.bounds, [[0, 0, 0], [1, 1, 1]])
    assert mesh.report["degenerate_triangles"] == 0


def test_float32_and_unsigned_arrays_are_read():
    mesh = adb.Mesh(TETRA_V.astype(np.float32), TETRA_T.astype(np.uint32))
    np.testing.assert_array_equal(mesh.vertices, TETRA_V)


def test_degenerate_triangles_are_legal_and_counted():
    v = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], dtype=float)
    mesh = adb.Mesh(v, [[0, 1, 2], [0, 1, 3]])
    assert mesh.report["degenerate_triangles"] == 1
    adb.Tree(mesh)  # builds


@pytest.mark.parametrize("vertices, triangles, message", [
    (np.zeros((4, 2)), TETRA_T, "vertices: shape (4, 2), expected (N, 3)"),
    (np.zeros(12), TETRA_T, "vertices: shape (12,), expected (N, 3)"),
    (TETRA_V, TETRA_T[:, :2], "triangles: shape (4, 2), expected (M, 3)"),
    (TETRA_V.astype(complex), TETRA_T, "vertices: dtype complex128, expected real numbers"),
    (TETRA_V, TETRA_T.astype(float), "triangles: dtype float64, expected integers"),
    ("vertices", TETRA_T, "vertices: expected an array, got str"),
    (TETRA_V, [[0, 1, 4]], "triangle 0 references vertex 4, but the mesh has 4 vertices"),
    (TETRA_V, [[0, -1, 2]], "triangle 0 references vertex -1"),
    (np.where(np.arange(12).reshape(4, 3) == 7, np.nan, TETRA_V), TETRA_T,
     "vertex 2 has a non-finite coordinate"),
    (TETRA_V, np.zeros((0, 3), dtype=int), "no triangles"),
])
def test_bad_arrays_are_named(vertices, triangles, message):
    with pytest.raises(adb.MeshError) as error:
        adb.Mesh(vertices, triangles, "part")
    assert message in str(error.value)
    assert str(error.value).startswith("part")
    assert isinstance(error.value, ValueError)


def test_a_tree_takes_the_build_settings(torus):
    mesh = adb.model("torus", 2000)
    coarse = adb.Tree(mesh, grid_resolution=4, max_leaf_triangles=8, counting="exact")
    assert coarse.triangle_count == mesh.triangle_count
    assert coarse.node_count < torus.node_count  # bigger leaves, fewer nodes
    assert coarse.memory_bytes > 0 and coarse.build_seconds >= 0


@pytest.mark.parametrize("settings, name", [
    ({"grid_resolution": 0}, "grid_resolution"),
    ({"grid_resolution": 33}, "grid_resolution"),
    ({"max_leaf_triangles": 16}, "max_leaf_triangles"),
    ({"counting": "fast"}, "counting"),
    ({"area_threshold": 0.0}, "areaThreshold"),
])
def test_bad_build_settings_are_named(settings, name):
    with pytest.raises(adb.SettingsError, match=name):
        adb.Tree(adb.Mesh(TETRA_V, TETRA_T), **settings)


def test_load_mesh_reads_a_file_through_the_isolated_reader(tmp_path):
    mesh = adb.model("knot", 1000)
    path = tmp_path / "knot.obj"
    write_obj(path, mesh.vertices, mesh.triangles)
    loaded = adb.load_mesh(str(path))
    assert loaded.triangle_count == mesh.triangle_count
    assert np.allclose(loaded.bounds, mesh.bounds)
    in_process = adb.load_mesh(path, isolate=False)
    np.testing.assert_array_equal(in_process.bounds, loaded.bounds)


def test_load_mesh_errors_name_the_file(tmp_path):
    with pytest.raises(adb.MeshError, match="nothing.obj"):
        adb.load_mesh(tmp_path / "nothing.obj")
    damaged = tmp_path / "damaged.stl"
    damaged.write_bytes(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n")
    with pytest.raises(adb.MeshError, match="damaged.stl"):
        adb.load_mesh(damaged)
    bad = tmp_path / "nan.obj"
    bad.write_text("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(adb.MeshError, match="nan.obj"):
        adb.load_mesh(bad)


def test_generated_models():
    assert {"torus", "knot", "gears"} <= set(adb.model_names())
    with pytest.raises(adb.MeshError):
        adb.model("teapot")
    with pytest.raises(adb.SettingsError, match="triangles"):
        adb.model("torus", 3)
