"""Rendered datasets with ground truth for the binding tests, written by the `aperture` binary that
ctest names in APERTURE_BINARY (python/CMakeLists.txt) with `aperture render`."""
import os
import subprocess

import numpy as np
import pytest


def _aperture_binary():
    binary = os.environ.get("APERTURE_BINARY")
    if not binary or not os.path.exists(binary):
        pytest.fail("set APERTURE_BINARY to the built aperture executable (ctest does: "
                    "`ctest -R python`), got %r" % binary)
    return binary


def render(scenario, out, *args):
    subprocess.run([_aperture_binary(), "render", scenario, "--out", str(out), *args],
                   check=True, capture_output=True)
    return out


def quaternion_to_matrix(qx, qy, qz, qw):
    x, y, z, w = np.array([qx, qy, qz, qw]) / np.linalg.norm([qx, qy, qz, qw])
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def pose(tx, ty, tz, qx, qy, qz, qw):
    T = np.eye(4)
    T[:3, :3] = quaternion_to_matrix(qx, qy, qz, qw)
    T[:3, 3] = [tx, ty, tz]
    return T


def camera_poses(dataset):
    """T_WC per frame from groundtruth.txt (TUM: t tx ty tz qx qy qz qw)."""
    rows = np.loadtxt(dataset / "groundtruth.txt", ndmin=2)
    return [pose(*row[1:]) for row in rows]


def object_poses(dataset, name):
    """T_WO per frame of the object `name` from objects.csv."""
    poses = []
    with open(dataset / "objects.csv") as f:
        next(f)
        for line in f:
            cells = line.strip().split(",")
            if cells[1] == name:
                poses.append(pose(*map(float, cells[2:])))
    return poses


@pytest.fixture(scope="session")
def gap_dataset(tmp_path_factory):
    """Three frames of the `gap` scenario (180 deg fisheye) approaching the gap from ~5 m."""
    return render("gap", tmp_path_factory.mktemp("gap"), "--frames", "3")


@pytest.fixture(scope="session")
def led_dataset(tmp_path_factory):
    """Three frames of the `led` scenario: the ground camera under the LED target."""
    return render("led", tmp_path_factory.mktemp("led"), "--frames", "3", "--trajectory", "hover")
