"""The examples of demos/python run, small, and make what they say they make."""

import os
import subprocess
import sys

import pytest

from conftest import SOURCE

EXAMPLES = SOURCE / "demos" / "python"


def run(script, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)], env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout


def is_png(path):
    return path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_tradeoff(tmp_path):
    out = run("tradeoff.py", "--poses", "300", "--out", tmp_path / "t.png")
    assert "exact:" in out and "p_min 0.99:" in out and "% wrong" in out
    assert is_png(tmp_path / "t.png")


def test_tradeoff_on_a_mesh_file(tmp_path):
    from conftest import write_obj
    import adb

    mesh = adb.model("gears", 2000)
    write_obj(tmp_path / "gears.obj", mesh.vertices, mesh.triangles)
    out = run("tradeoff.py", tmp_path / "gears.obj", "--poses", "200", "--out", tmp_path / "g.png")
    assert "gears" in out or "exact:" in out


def test_assembly_path(tmp_path):
    out = run("assembly_path.py", "--samples", "120", "--out", tmp_path / "p.png")
    assert "through the hole: 0 of 120 poses overlap" in out
    assert "grazing the rim:" in out
    assert is_png(tmp_path / "p.png")


def test_pile(tmp_path):
    out = run("pile.py", "--bodies", "6", "--steps", "40", "--out", tmp_path)
    assert "exact:" in out and "budget:" in out
    for name in ("exact.png", "budget.png", "step_times.png"):
        assert is_png(tmp_path / name)


def test_the_readme_snippet_runs():
    """The README's Python snippet, run as written from the checkout, so it never goes stale."""
    text = (SOURCE / "README.md").read_text()
    snippet = text.split("```python\n", 1)[1].split("```", 1)[0]
    cwd = os.getcwd()
    os.chdir(SOURCE)
    try:
        names = {}
        exec(compile(snippet, "README.md", "exec"), names)
    finally:
        os.chdir(cwd)
    assert names["r"].collides and names["r"].confidence > 0.5
    assert names["many"]["collides"].shape == (1000,)
    assert names["world"].step_count == 30
