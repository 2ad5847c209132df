"""adb.collide and adb.collide_many: known answers, the C++ tool's answers on the same poses,
thread counts, budgets, the GIL, and bad arguments named."""

import csv
import subprocess
import threading
import time

import numpy as np
import pytest

import adb
from conftest import BIN, random_poses, translation

I4 = np.eye(4)


def test_known_answers(torus):
    # The torus (about 2 units across, tube radius about 0.3) against a copy: the same pose
    # intersects everywhere, a shift of 5 is far apart, one along the axis through the hole
    # by less than the tube's diameter still touches.
    assert adb.collide(torus, I4, torus, I4, mode="exact").collides
    far = adb.collide(torus, I4, torus, translation(5), mode="exact")
    assert not far.collides and far.confidence == 1.0 and far.stop == "completed"
    assert far.node_pairs == 1  # the roots' boxes are apart
    adb_far = adb.collide(torus, I4, torus, translation(5))
    assert not adb_far.collides and adb_far.confidence == 1.0


def test_witnesses_name_mesh_triangles_that_intersect(torus):
    mesh = adb.model("torus", 2000)
    r = adb.collide(torus, I4, torus, translation(0.5), mode="exact", stop_at_first_hit=False,
                    max_witnesses=16)
    assert r.collides and r.confidence == 1.0
    assert r.witnesses.shape == (16, 2)
    assert (r.witnesses >= 0).all() and (r.witnesses < mesh.triangle_count).all()
    contacts = r.contacts()
    assert contacts["points"].shape == (16, 3)
    assert np.isfinite(contacts["points"]).all() and (contacts["depths"] >= 0).all()
    # Each point lies near both witness triangles: within the triangles' own size.
    v, t = mesh.vertices, mesh.triangles
    for (ta, tb), p in zip(r.witnesses, contacts["points"]):
        a = v[t[ta]]
        b = v[t[tb]] + [0.5, 0, 0]
        size = max(np.ptp(a, axis=0).max(), np.ptp(b, axis=0).max())
        assert np.linalg.norm(p - b.mean(axis=0)) <= 2 * size
        assert np.linalg.norm(p - a.mean(axis=0)) <= 2 * size


def test_three_by_four_poses_equal_four_by_four(torus):
    p = translation(0.8, 0.1)
    assert adb.collide(torus, I4[:3], torus, p[:3], mode="exact").node_pairs == \
        adb.collide(torus, I4, torus, p, mode="exact").node_pairs


def csv_poses(rows, side):
    """The CSV's poses, made by the C++ code that made the tool's (Pose::fromQuaternion)."""
    quaternions = [[float(r[f"{side}_q{c}"]) for c in "wxyz"] for r in rows]
    translations = [[float(r[f"{side}_t{c}"]) for c in "xyz"] for r in rows]
    return adb.poses_from_quaternions(quaternions, translations)


def test_answers_equal_the_cpp_tools_on_the_same_poses(tmp_path, knot):
    """adb-tradeoff's per-query CSV (docs/benchmark.md) holds every pose and answer: the same
    poses from Python give the same exact answers, and the same ADB answers and confidences
    (no time budget: the traversal is deterministic)."""
    tool = BIN / "adb-tradeoff"
    if not tool.exists():
        pytest.skip("adb-tradeoff is not built (ADB_BUILD_DEMOS=OFF)")
    subprocess.run([str(tool), "--model", "knot:3000", "--distances", "0.4:2.0:0.2",
                    "--rotations", "25", "--methods", "exact,adb", "--p-min", "0.99",
                    "--k-min", "10", "--budget-us", "none", "--repeats", "1", "--no-plots",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    rows = list(csv.DictReader(open(tmp_path / "queries.csv")))
    exact = [r for r in rows if r["method"] == "exact"]
    budgetless = [r for r in rows if r["method"] == "adb" and r["budget_us"] == ""]
    assert len(exact) == 9 * 25 and len(budgetless) == len(exact)
    poses_a, poses_b = csv_poses(exact, "a"), csv_poses(exact, "b")
    many = adb.collide_many(knot, poses_a, knot, poses_b, mode="exact")
    expected = np.array([r["collides"] == "1" for r in exact])
    assert 0 < expected.sum() < len(expected)  # both answers occur
    np.testing.assert_array_equal(many["collides"], expected)
    for k in range(0, len(exact), 20):  # one by one too
        assert adb.collide(knot, poses_a[k], knot, poses_b[k], mode="exact").collides == \
            expected[k]
    adb_many = adb.collide_many(knot, poses_a, knot, poses_b, p_min=0.99, k_min=10)
    np.testing.assert_array_equal(adb_many["collides"],
                                  [r["collides"] == "1" for r in budgetless])
    np.testing.assert_allclose(adb_many["confidence"],
                               [float(r["confidence"]) for r in budgetless], rtol=1e-8)
    np.testing.assert_array_equal(adb_many["node_pairs"],
                                  [int(r["node_pairs"]) for r in budgetless])


def test_collide_many_equals_collide_at_any_thread_count(torus):
    rng = np.random.default_rng(7)
    poses = random_poses(rng, 300, 1.5)
    one = adb.collide_many(torus, I4, torus, poses, p_min=0.9, k_min=5, budget_pairs=400)
    two = adb.collide_many(torus, I4, torus, poses, p_min=0.9, k_min=5, budget_pairs=400,
                           threads=2)
    every = adb.collide_many(torus, I4, torus, poses, p_min=0.9, k_min=5, budget_pairs=400,
                             threads=0)
    for key in ("collides", "confidence", "node_pairs", "stop", "witness"):
        np.testing.assert_array_equal(one[key], two[key])
        np.testing.assert_array_equal(one[key], every[key])
    for k in range(0, 300, 37):
        r = adb.collide(torus, I4, torus, poses[k], p_min=0.9, k_min=5, budget_pairs=400)
        assert (r.collides, r.confidence, r.node_pairs, r.stop) == \
            (one["collides"][k], one["confidence"][k], one["node_pairs"][k], one["stop"][k])
    assert (one["node_pairs"] <= 400).all()
    assert ((one["confidence"] >= 0) & (one["confidence"] <= 1)).all()
    assert set(one["stop"]) <= {"completed", "quality reached", "exact hit", "work budget"}


def test_a_time_budget_cuts_queries_and_says_so(knot):
    rng = np.random.default_rng(3)
    poses = random_poses(rng, 200, 0.6)
    cut = adb.collide_many(knot, I4, knot, poses, mode="exact", budget_us=0)
    assert (cut["stop"] == "time budget").any()
    assert (cut["confidence"] <= 1).all() and (cut["confidence"] >= 0).all()


def test_the_gil_is_released_while_collide_many_runs(knot):
    rng = np.random.default_rng(5)
    poses = random_poses(rng, 1000, 0.8)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.perf_counter()
    adb.collide_many(knot, I4, knot, poses, mode="exact", stop_at_first_hit=False)
    elapsed = time.perf_counter() - start
    done.set()
    ticker.join()
    during = [t for t in ticks if start < t < start + elapsed]
    # Held GIL: no tick during the call, one gap as long as the call. Released: ticks all
    # through it. Not a tick rate: with both cores busy on the query (a loaded 2-core machine)
    # the ticker gets the CPU only now and then, but it does get it.
    assert elapsed > 0.05
    assert len(during) >= 10
    edges = [start] + during + [start + elapsed]
    longest_gap = max(b - a for a, b in zip(edges, edges[1:]))
    assert longest_gap < 0.5 * elapsed


@pytest.mark.parametrize("kwargs, message", [
    ({"mode": "fast"}, "mode: 'fast', expected 'adb' or 'exact'"),
    ({"p_min": 1.5}, "p_min"),
    ({"p_min": float("nan")}, "p_min"),
    ({"k_min": 0}, "k_min"),
    ({"budget_us": -1.0}, "budget_us"),
    ({"budget_pairs": -5}, "budget_pairs"),
    ({"contact_margin": -0.1}, "contact_margin"),
    ({"max_witnesses": -1}, "max_witnesses"),
])
def test_bad_settings_are_named(torus, kwargs, message):
    with pytest.raises(adb.SettingsError) as error:
        adb.collide(torus, I4, torus, I4, **kwargs)
    assert message in str(error.value)
    with pytest.raises(adb.SettingsError):
        adb.collide_many(torus, I4, torus, I4[None], **kwargs)


def not_orthonormal():
    pose = np.eye(4)
    pose[0, 0] = 1.01
    return pose


@pytest.mark.parametrize("pose, message", [
    (np.eye(3), "pose_b: shape (3, 3), expected (4, 4) or (3, 4)"),
    (np.eye(4)[None], "pose_b: shape (1, 4, 4), expected (4, 4) or (3, 4)"),
    (np.eye(4).astype(complex), "pose_b: dtype complex128; a pose needs real numbers"),
    (np.full((4, 4), np.nan), "pose_b: entry [0, 0] is nan"),
    (translation(np.inf), "pose_b: entry [0, 3] is inf"),
    (np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [1, 0, 0, 1]]),
     "pose_b: the last row of a 4x4 pose must be [0, 0, 0, 1]"),
    (not_orthonormal(), "pose_b: has a rotation that is not orthonormal"),
    ("identity", "pose_b: expected an array, got str"),
    (None, "pose_b: expected an array, got NoneType"),
])
def test_bad_poses_are_named(torus, pose, message):
    with pytest.raises(adb.PoseError) as error:
        adb.collide(torus, I4, torus, pose)
    assert message in str(error.value)
    assert isinstance(error.value, ValueError)


def test_bad_batches_are_named_by_index(torus):
    poses = np.tile(np.eye(4), (30, 1, 1))
    poses[17, 1, 3] = np.nan
    with pytest.raises(adb.PoseError, match=r"poses_b\[17\]: entry \[1, 3\] is nan"):
        adb.collide_many(torus, I4, torus, poses)
    with pytest.raises(adb.PoseError, match="poses_a holds 3 poses and poses_b 30"):
        adb.collide_many(torus, np.tile(I4, (3, 1, 1)), torus, np.tile(I4, (30, 1, 1)))
    with pytest.raises(adb.PoseError, match=r"poses_a: shape \(2, 2, 4, 4\)"):
        adb.collide_many(torus, np.zeros((2, 2, 4, 4)), torus, I4)
    with pytest.raises(adb.SettingsError, match="threads"):
        adb.collide_many(torus, I4, torus, I4, threads=-1)


def test_batches_broadcast_a_single_pose_on_either_side(torus):
    empty = adb.collide_many(torus, I4, torus, np.zeros((0, 4, 4)))
    assert all(len(v) == 0 for v in empty.values())
    assert len(adb.collide_many(torus, np.zeros((0, 3, 4)), torus, I4)["collides"]) == 0
    one = adb.collide_many(torus, I4, torus, translation(5))
    assert list(one["collides"]) == [False]
    moved = np.tile(translation(5), (3, 1, 1))
    assert list(adb.collide_many(torus, moved, torus, I4, mode="exact")["collides"]) == \
        [False] * 3


def test_no_tree_is_a_type_error_not_a_crash(torus):
    # pybind11 would pass None as an empty shared pointer: the trees are declared not-None.
    with pytest.raises(TypeError):
        adb.collide(None, I4, torus, I4)
    with pytest.raises(TypeError):
        adb.collide_many(torus, I4, None, I4)


def test_pose_helpers():
    half_turn = adb.poses_from_quaternions([[0, 0, 0, 2]], [[1, 2, 3]])[0]  # normalised
    np.testing.assert_allclose(half_turn[:3, :3], np.diag([-1.0, -1, 1]), atol=1e-15)
    np.testing.assert_array_equal(half_turn[:3, 3], [1, 2, 3])
    with pytest.raises(adb.PoseError, match=r"quaternions\[0\]: not a rotation"):
        adb.poses_from_quaternions([[0, 0, 0, 0]], [[0, 0, 0]])
    with pytest.raises(adb.PoseError, match="expected \\(K, 4\\) and \\(K, 3\\)"):
        adb.poses_from_quaternions([[1, 0, 0, 0]], [[0, 0]])
    mesh = adb.model("knot", 1000)
    a, b = adb.benchmark_poses(mesh, [0.5, 1.5], seed=4)
    again, _ = adb.benchmark_poses(mesh, [0.5, 1.5], seed=4)
    np.testing.assert_array_equal(a, again)
    unit = np.ptp(mesh.bounds, axis=0).max() / 2
    centre = np.append(mesh.bounds.mean(axis=0), 1)
    gaps = (b @ centre)[:, :3] - (a @ centre)[:, :3]  # the box centres, posed
    np.testing.assert_allclose(gaps, [[0.5 * unit, 0, 0], [1.5 * unit, 0, 0]], atol=1e-12)


def test_check_pose_returns_the_checked_matrix():
    np.testing.assert_array_equal(adb.check_pose(translation(1, 2, 3)[:3]), translation(1, 2, 3))
    with pytest.raises(adb.PoseError, match="gripper: has a rotation that is not orthonormal"):
        adb.check_pose(not_orthonormal(), "gripper")
