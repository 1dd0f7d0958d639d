"""Camera models and calibration files from Python, checked against the pinhole equations and
exact round trips."""
import numpy as np
import pytest

import aperture


def test_pinhole_projects_like_the_pinhole_equations():
    camera = aperture.create_camera_model("pinhole", 640, 480, [500.0, 510.0, 320.5, 240.5])
    p_C = np.array([[0.1, -0.2, 2.0], [0.0, 0.0, 1.0], [0.3, 0.1, -1.0]])
    px, valid = camera.project(p_C)
    np.testing.assert_allclose(px[0], [500.0 * 0.05 + 320.5, 510.0 * -0.1 + 240.5], atol=1e-9)
    np.testing.assert_allclose(px[1], [320.5, 240.5], atol=1e-9)
    assert valid.tolist() == [True, True, False]  # behind the camera


@pytest.mark.parametrize("model,distortion", [("radtan", [-0.28, 0.07, 1e-4, -2e-4]),
                                              ("equidistant", [0.01, -0.005, 0.001, 0.0])])
def test_unproject_inverts_project(model, distortion):
    camera = aperture.create_camera_model(model, 752, 480, [460.0, 460.0, 376.0, 240.0], distortion)
    px = np.array([[10.0, 20.0], [376.0, 240.0], [700.5, 450.25]])
    f_C = camera.unproject(px)
    np.testing.assert_allclose(np.linalg.norm(f_C, axis=1), 1.0, atol=1e-12)
    back, valid = camera.project(f_C * 3.0)
    assert valid.all()
    np.testing.assert_allclose(back, px, atol=1e-6)


def test_calibration_round_trips_through_every_format(tmp_path):
    camera = aperture.create_camera_model("radtan", 752, 480, [458.6, 457.3, 367.2, 248.4],
                                          [-0.283, 0.074, 1.9e-4, 1.8e-5])
    T_BC = np.eye(4)
    T_BC[:3, 3] = [0.05, -0.01, 0.02]
    for fmt in ("opencv", "ros", "kalibr"):
        path = tmp_path / ("cam_%s.yaml" % fmt)
        aperture.save_calibration(camera, str(path), fmt, "cam0", T_BC)
        loaded = aperture.load_calibration(str(path))
        assert loaded.camera.model_name == "radtan"
        assert (loaded.camera.width, loaded.camera.height) == (752, 480)
        np.testing.assert_array_equal(loaded.camera.intrinsics, camera.intrinsics)
        np.testing.assert_array_equal(loaded.camera.distortion, camera.distortion)
        assert loaded.source_path == str(path)


def test_bad_camera_input_names_the_problem():
    with pytest.raises(ValueError, match="fisheye9"):
        aperture.create_camera_model("fisheye9", 640, 480, [500.0, 500.0, 320.0, 240.0])
    with pytest.raises(ValueError, match="no_such_calib.yaml"):
        aperture.load_calibration("no_such_calib.yaml")
