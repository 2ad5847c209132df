"""adb.Scene and adb.World: scenes from files, JSON, dicts and code, stepped like adb-demo,
read back as arrays, drawn, and every bad scene named."""

import csv
import subprocess

import numpy as np
import pytest

import adb
from conftest import BIN, SOURCE

SMALL_SCENE = {
    "description": "two tori dropped on a box",
    "world": {"steps": 40, "budget": {"node_pairs": 3000}},
    "shapes": {
        "floor": {"type": "box", "half_extents": [3, 0.25, 3]},
        "part": {"type": "mesh"},
    },
    "bodies": [
        {"name": "floor", "shape": "floor", "kind": "static", "position": [0, -0.25, 0]},
        # adb.model's torus lies in its xy plane: both are turned flat, so that they are
        # dropped apart (unturned, a stood in the floor with b threaded on it).
        {"name": "a", "shape": "part", "position": [0, 0.6, 0],
         "axis_angle": {"axis": [1, 0, 0], "degrees": 90}},
        {"name": "b", "shape": "part", "position": [0.2, 1.4, 0.1],
         "axis_angle": {"axis": [1, 0, 0], "degrees": 90}},
    ],
    "effects": ["dynamics", "friction"],
}


def small_scene():
    return adb.Scene.from_dict(SMALL_SCENE, meshes={"part": adb.model("torus", 800)})


def test_a_scene_built_in_python_steps_and_reads_back():
    scene = small_scene()
    assert scene.body_names == ["floor", "a", "b"]
    assert scene.budget_pairs == 3000 and scene.budget_us is None
    world = adb.World(scene)
    world.step(40)
    assert world.step_count == 40 and world.time == pytest.approx(40 * scene.time_step)
    poses = world.poses()
    assert poses.shape == (3, 4, 4)
    np.testing.assert_allclose(poses[:, 3], np.tile([0, 0, 0, 1], (3, 1)))
    assert poses[2, 1, 3] < 1.4  # b fell
    stats = world.stats()
    assert len(stats["step"]) == 40 and stats["step"].dtype == np.int64
    assert (stats["node_pairs"] <= 3000 + 3000).all()  # the budget (plus the first pair's roots)
    contacts = world.contacts()
    assert contacts["position"].shape[1] == 3
    assert ((contacts["confidence"] >= 0) & (contacts["confidence"] <= 1)).all()
    summary = world.summary()
    assert summary["steps"] == 40 and summary["bodies"] == 3


def test_stats_are_the_columns_of_steps_csv(tmp_path):
    world = adb.World(small_scene(), out=tmp_path)
    world.step(10)
    rows = list(csv.DictReader(open(tmp_path / "steps.csv")))
    stats = world.stats()
    assert list(stats) == list(rows[0])
    for column, values in stats.items():
        written = np.array([float(r[column]) for r in rows])
        np.testing.assert_allclose(values, written, rtol=1e-5, atol=1e-9, err_msg=column)


def test_the_same_scene_as_adb_demo_gives_the_same_simulation(tmp_path):
    """A node-pair budget makes a run reproducible: World and adb-demo on one scene file write
    the same steps.csv but for the timings."""
    demo = BIN / "adb-demo"
    if not demo.exists():
        pytest.skip("adb-demo is not built (ADB_BUILD_DEMOS=OFF)")
    scene_file = SOURCE / "demos" / "scenes" / "pile.json"
    subprocess.run([str(demo), "--scene", str(scene_file), "--steps", "30", "--budget-pairs",
                    "20000", "--out", str(tmp_path / "demo")], check=True, capture_output=True)
    scene = adb.Scene.load(scene_file)
    scene.steps = 30
    scene.budget_pairs = 20000
    world = adb.World(scene, out=tmp_path / "python")
    world.step(30)
    timing = {"seconds", "frame_us", "contact_us", "parallel_us", "budget_use"}
    demo_rows = list(csv.DictReader(open(tmp_path / "demo" / "steps.csv")))
    python_rows = list(csv.DictReader(open(tmp_path / "python" / "steps.csv")))
    assert len(demo_rows) == len(python_rows) == 30
    for d, p in zip(demo_rows, python_rows):
        assert {k: v for k, v in d.items() if k not in timing} == \
            {k: v for k, v in p.items() if k not in timing}


def test_an_overlap_scene_reports_its_events(tmp_path):
    """The gallery's assembly path: the ring's overlap events, every step's, as adb-demo
    writes them to events.jsonl."""
    import json

    scene = adb.Scene.load(SOURCE / "demos" / "scenes" / "assembly_path.json")
    world = adb.World(scene, out=tmp_path)
    world.step(scene.steps)
    events = world.events()
    written = [json.loads(line) for line in open(tmp_path / "events.jsonl")]
    assert len(events["step"]) == len(written) > 0
    assert list(events["step"]) == [e["step"] for e in written]
    assert list(events["begin"]) == [e["event"] == "begin" for e in written]
    assert ((events["confidence"] >= 0) & (events["confidence"] <= 1)).all()
    assert world.built.startswith("btCollisionWorld")
    for b0, b1 in world.overlapping()["bodies"]:
        assert b0 < b1


def test_render_writes_a_png(tmp_path):
    world = adb.World(small_scene())
    world.step(5)
    world.render(tmp_path / "frame.png", width=320, height=240)
    data = (tmp_path / "frame.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(data[16:20], "big") == 320 and int.from_bytes(data[20:24], "big") == 240


def test_backends_and_threads():
    scene = small_scene()
    scene.steps = 5
    for backend in ("exact", "gimpact"):
        world = adb.World(scene, backend=backend, threads=2)
        world.step(5)
        assert world.backend == backend
    with pytest.raises(adb.SettingsError, match="backend"):
        adb.World(scene, backend="physx")
    with pytest.raises(adb.SettingsError, match="threads"):
        adb.World(scene, threads=-2)


def test_the_pile_made_in_code():
    scene = adb.Scene.pile(bodies=4, triangles=300, floor="plane", steps=20)
    world = adb.World(scene)
    world.step(20)
    assert len(world.body_names) == len(scene.body_names)
    with pytest.raises(adb.SettingsError, match="floor"):
        adb.Scene.pile(floor="sand")


def test_a_pile_of_one_model_sleeps_unless_told_not_to():
    for sleeping in (True, False):
        scene = adb.Scene.pile(bodies=3, triangles=200, model="gears", floor="plane", steps=5,
                               sleeping=sleeping)
        world = adb.World(scene, backend="exact")
        world.step(5)
        summary = world.summary()
        assert summary["asleep_at_end"] == 0  # falling: nobody sleeps yet
        assert summary["all_asleep_from"] == -1
        assert summary["lost_at_end"] == 0
        assert "+sleeping" in summary["effects"] if sleeping else "+sleeping" not in summary["effects"]
    with pytest.raises(adb.SettingsError, match="model"):
        adb.Scene.pile(model="teapot")


def test_a_dict_may_hold_numpy_values():
    scene = dict(SMALL_SCENE, bodies=[dict(b) for b in SMALL_SCENE["bodies"]])
    scene["bodies"][1]["position"] = np.array([0.0, 0.7, 0.0])
    scene["bodies"][1]["mass"] = np.float32(2.0)
    assert adb.Scene.from_dict(scene, meshes={"part": adb.model("torus", 800)}).body_names == \
        ["floor", "a", "b"]
    scene["bodies"][1]["mass"] = object()
    with pytest.raises(adb.SceneError, match="a object is not a value a scene holds"):
        adb.Scene.from_dict(scene, meshes={"part": adb.model("torus", 800)})


def test_bad_scenes_are_named(tmp_path):
    bad = dict(SMALL_SCENE, bodies=[{"name": "a", "shape": "nothing"}])
    with pytest.raises(adb.SceneError, match=r"bodies\[0\]\.shape"):
        adb.Scene.from_dict(bad, meshes={"part": adb.model("torus", 800)})
    with pytest.raises(adb.SceneError, match="shapes.part"):
        adb.Scene.from_dict(SMALL_SCENE)  # no file and no mesh given
    with pytest.raises(adb.MeshError, match=r"meshes\['part'\]: None"):
        adb.Scene.from_dict(SMALL_SCENE, meshes={"part": None})
    with pytest.raises(adb.SceneError, match="line 1"):
        adb.Scene.from_json("{ nope")
    (tmp_path / "s.json").write_text('{"shapes": {}}')
    with pytest.raises(adb.SceneError, match="s.json"):
        adb.Scene.load(tmp_path / "s.json")
    with pytest.raises(adb.SceneError, match="cannot open"):
        adb.Scene.load(tmp_path / "missing.json")
    scene = small_scene()
    with pytest.raises(adb.SettingsError, match="steps"):
        scene.steps = 0
    assert isinstance(adb.SceneError("x"), ValueError)
