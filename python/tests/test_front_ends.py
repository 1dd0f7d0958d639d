"""The gap detector, the LED tracker and aperture.run on images the simulator rendered, against
the renderer's ground truth."""
import numpy as np
import pytest

import aperture
from conftest import camera_poses, object_poses


def test_gap_detector_finds_the_rendered_gap_in_a_numpy_image(gap_dataset):
    calibration = aperture.load_calibration(str(gap_dataset / "calib.yaml"))
    detector = aperture.GapDetector(calibration.camera)
    image = aperture.read_image(str(gap_dataset / "images" / "000000.png"))
    assert image.dtype == np.uint8 and image.shape == (480, 752)
    detection = detector.detect(image)
    assert detection.detected, detection.status
    T_CG_true = np.linalg.inv(camera_poses(gap_dataset)[0]) @ object_poses(gap_dataset, "gap")[0]
    distance_m = np.linalg.norm(T_CG_true[:3, 3])
    # gap_detector_render_test: median position error < 0.04 % of the distance; one frame gets 1 %.
    assert np.linalg.norm(detection.T_CG[:3, 3] - T_CG_true[:3, 3]) < 0.01 * distance_m
    # The plane normal z_G agrees up to the pattern's symmetry (gap_detector.h).
    assert abs(detection.T_CG[:3, 2] @ T_CG_true[:3, 2]) > np.cos(np.radians(2.0))
    assert detection.corners_px.shape == (8, 2)


def test_gap_detector_rejects_a_float_image(gap_dataset):
    calibration = aperture.load_calibration(str(gap_dataset / "calib.yaml"))
    detector = aperture.GapDetector(calibration.camera)
    with pytest.raises(ValueError, match="uint8"):
        detector.detect(np.zeros((480, 752), dtype=np.float32))
    with pytest.raises(ValueError, match="752"):
        detector.detect(np.zeros((240, 376), dtype=np.uint8))


def test_led_tracker_finds_the_target_pose(led_dataset):
    calibration = aperture.load_calibration(str(led_dataset / "calib.yaml"))
    tracker = aperture.LedTracker(aperture.LedConfiguration.default(), calibration.camera)
    image = aperture.read_image(str(led_dataset / "images" / "000000.png"))
    result = tracker.track(image, 0.0)
    assert result.has_pose, result.status
    # The scenario's LEDs are the default configuration in the body frame: T = B.
    T_CT_true = np.linalg.inv(camera_poses(led_dataset)[0]) @ object_poses(led_dataset, "led_target")[0]
    assert np.linalg.norm(result.T_CT[:3, 3] - T_CT_true[:3, 3]) < 0.01  # ~2 m away
    assert len(result.detections_px) >= 4


def test_run_gives_the_gap_pose_of_every_frame(gap_dataset):
    result = aperture.run(str(gap_dataset), frontends=["gap"], calib=str(gap_dataset / "calib.yaml"))
    assert result["frames"] == 3
    np.testing.assert_allclose(np.diff(result["t_s"]), 1.0 / 50.0, rtol=1e-9)
    gap = result["poses"]["gap"]
    assert gap["T"].shape == (3, 4, 4)
    T_WG = object_poses(gap_dataset, "gap")[0]
    for T_WC, T_GC in zip(camera_poses(gap_dataset), gap["T"]):  # stream "gap" is T_GC
        p_GC_true = (np.linalg.inv(T_WG) @ T_WC)[:3, 3]
        assert np.linalg.norm(T_GC[:3, 3] - p_GC_true) < 0.01 * np.linalg.norm(p_GC_true)
    assert set(result["metrics"]) >= {"gap.detected"}


def test_run_names_an_unknown_front_end_and_a_missing_source(gap_dataset):
    with pytest.raises(ValueError, match="no_such_front_end"):
        aperture.run(str(gap_dataset), frontends=["no_such_front_end"])
    with pytest.raises(RuntimeError, match="missing_folder"):
        aperture.run("missing_folder", frontends=["image_quality"])
