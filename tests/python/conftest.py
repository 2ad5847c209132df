"""Shared fixtures of the Python suite. ctest runs it with PYTHONPATH at the built package
(build/python), ADB_BUILD_BIN at the built programs and ADB_SOURCE_DIR at the checkout."""

import os
import pathlib

import numpy as np
import pytest

import adb

SOURCE = pathlib.Path(os.environ.get("ADB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
BIN = pathlib.Path(os.environ.get("ADB_BUILD_BIN", SOURCE / "build" / "bin"))


def translation(x=0.0, y=0.0, z=0.0):
    pose = np.eye(4)
    pose[:3, 3] = (x, y, z)
    return pose


def random_rotations(rng, k):
    """k uniformly random rotation matrices (from normalised Gaussian quaternions)."""
    q = rng.normal(size=(k, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], 1)


def random_poses(rng, k, spread):
    """k random poses: random rotations, translations uniform in [-spread, spread]^3."""
    poses = np.tile(np.eye(4), (k, 1, 1))
    poses[:, :3, :3] = random_rotations(rng, k)
    poses[:, :3, 3] = rng.uniform(-spread, spread, size=(k, 3))
    return poses


@pytest.fixture(scope="session")
def torus():
    return adb.Tree(adb.model("torus", 2000))


@pytest.fixture(scope="session")
def knot():
    return adb.Tree(adb.model("knot", 3000))


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        for v in vertices:
            f.write(f"v {v[0]!r} {v[1]!r} {v[2]!r}\n")
        for t in triangles:
            f.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
