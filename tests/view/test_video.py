"""`plx check --simulate --video`: GIF and MP4 with the expected number of frames, showing motion."""

from __future__ import annotations

import numpy as np
import pytest

from tests.conftest import run_plx

PIL = pytest.importorskip("PIL.Image", reason="the video extra (Pillow) is not installed")


def _gif_frames(path) -> list[np.ndarray]:
    from PIL import Image, ImageSequence

    with Image.open(path) as im:
        return [np.asarray(f.convert("RGB")) for f in ImageSequence.Iterator(im)]


def _mp4_frames(path) -> list[np.ndarray]:
    av = pytest.importorskip("av", reason="the video extra (PyAV) is not installed")
    with av.open(str(path)) as c:
        return [f.to_ndarray(format="rgb24") for f in c.decode(video=0)]


def _video(tmp_path, name: str, *extra: str):
    out = tmp_path / name
    model = "examples/boxtruck/boxtruck.openplx"  # drives off at its motors' constant speed
    r = run_plx("check", "--simulate", "--video", str(out), "--duration", "1.2", "--fps", "10", *extra, model)
    if "cannot create a headless" in r.stderr:
        pytest.skip(f"offscreen rendering unavailable: {r.stderr.strip()}")
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    return out


@pytest.mark.parametrize("name,read", [("run.gif", _gif_frames), ("run.mp4", _mp4_frames)])
def test_video_has_one_frame_per_tick_and_shows_motion(tmp_path, name, read):
    frames = read(_video(tmp_path, name))
    assert len(frames) == 12  # 1.2 s at 10 frames per second
    assert frames[0].shape == (480, 640, 3)
    assert len(np.unique(frames[0].reshape(-1, 3), axis=0)) > 8  # a scene, not a blank frame
    moved = [float(np.abs(a.astype(int) - b.astype(int)).mean()) for a, b in zip(frames, frames[1:])]
    assert max(moved) > 0.5  # the truck lands and its wheels turn: consecutive frames differ


def test_gif_frame_duration_follows_fps(tmp_path):
    from PIL import Image

    out = _video(tmp_path, "slow.gif")
    with Image.open(out) as im:
        assert im.info["duration"] == 100  # 10 frames per second


@pytest.mark.parametrize("target,message", [
    ("run.avi", "--video writes .gif or .mp4"),
    ("missing-folder/run.gif", "no folder"),
])
def test_bad_video_targets_are_refused_before_simulating(tmp_path, target, message):
    r = run_plx("check", "--video", str(tmp_path / target), "examples/boxtruck/boxtruck.openplx")
    assert r.returncode == 2 and message in r.stderr and "Traceback" not in r.stderr
    assert list(tmp_path.iterdir()) == []


def test_fps_out_of_range_is_a_usage_error(tmp_path):
    r = run_plx("check", "--video", str(tmp_path / "a.gif"), "--fps", "0", "examples/boxtruck/boxtruck.openplx")
    assert r.returncode == 2 and "--fps" in r.stderr


def test_a_model_that_cannot_simulate_writes_no_video(tmp_path):
    out = tmp_path / "x.gif"
    r = run_plx("check", "--video", str(out), "examples/lint_errors/unknown_type.openplx")
    assert r.returncode != 0 and not out.exists()
    assert "cannot write" in r.stderr or "nothing to" in r.stderr
    assert [p.name for p in tmp_path.iterdir()] == []  # no half-written temporary file either


def test_a_fixed_camera_keeps_the_ground_still_and_the_follow_camera_does_not(tmp_path):
    """Issue 40.6: with the following camera a driving truck looked parked (only the grid moved);
    `--video-camera fixed` keeps the camera where it framed the scene at the start."""
    fixed = _gif_frames(_video(tmp_path, "fixed.gif", "--video-camera", "fixed"))
    follow = _gif_frames(_video(tmp_path, "follow.gif"))
    corner = lambda f: f[:120, :160].astype(int)  # noqa: E731 - ground and sky far from the truck
    still = float(np.abs(corner(fixed[-1]) - corner(fixed[0])).mean())
    moving = float(np.abs(corner(follow[-1]) - corner(follow[0])).mean())
    assert still < 0.5 < moving, (still, moving)
    # the truck itself moves in the fixed view: the whole picture changes
    assert float(np.abs(fixed[-1].astype(int) - fixed[0].astype(int)).mean()) > 0.5
