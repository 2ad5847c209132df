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


def random_poses(rng, k, spread):
    """k random poses: uniformly random rotations (normalised Gaussian quaternions),
    translations uniform in [-spread, spread]^3."""
    return adb.poses_from_quaternions(rng.normal(size=(k, 4)),
                                      rng.uniform(-spread, spread, size=(k, 3)))


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
