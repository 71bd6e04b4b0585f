"""The real viewer window under Xvfb (PLX_VIEW_TESTS=1, as .ci/run sets; needs xvfb, xdotool and
imagemagick): it shows the scene, a saved edit reloads it, a broken edit keeps it on screen with a
message, and holding Up through a controller drives the truck forward until the key is released."""

from __future__ import annotations

import json
import os
import time

import numpy as np
import pytest

from tests.view.xvfb_session import ViewInXvfb, missing_tools

REQUIRED = os.environ.get("PLX_VIEW_TESTS") == "1"
if not REQUIRED:
    pytest.skip("the window tests run with PLX_VIEW_TESTS=1 (as .ci/run sets)", allow_module_level=True)
if missing_tools():
    pytest.fail(f"PLX_VIEW_TESTS=1 but {', '.join(missing_tools())} not installed "
                "(apt-get install xvfb xdotool imagemagick)", pytrace=False)

# a controller in the runtime's style that also writes the chassis state when L is pressed
LOGGING_CONTROLLER = '''
import json
import os
from plxtools.check.api import RealInputSignal
from plxtools.view import KeyboardCallback, agxSDK, application, root

class Driver:
    def __init__(self, result):
        scene = result.scene()
        self.result = result
        self.queue = result.getInputSignalQueue()
        self.left = scene.getObject("box_truck.front_left_drive_motor.target_angular_velocity_input")
        self.right = scene.getObject("box_truck.front_right_drive_motor.target_angular_velocity_input")

    def on_up(self, key):
        speed = 3.0 if key.down else 0.0
        self.queue.send(RealInputSignal.create(speed, self.left))
        self.queue.send(RealInputSignal.create(-speed, self.right))

    def on_log(self, key):
        if key.down:
            b = self.result.body("box_truck.chassis")
            with open("states.jsonl", "a") as fh:
                fh.write(json.dumps({"t": self.result.time, "x": b.position[0], "vx": b.linear_velocity[0]}) + "\\n")

def buildScene():
    result = application().loadOpenPlxFile(os.path.abspath("truck.openplx"), root())
    d = Driver(result)
    KeyboardCallback.bind(name="forward", key=agxSDK.GuiEventListener.KEY_Up, callback=d.on_up)
    KeyboardCallback.bind(name="log", key=agxSDK.GuiEventListener.KEY_L, callback=d.on_log)
'''


def _until(v: ViewInXvfb, path, ok, seconds: float = 30.0) -> np.ndarray:
    """Screenshots until ``ok(picture)`` (a loaded machine draws late); the last one either way."""
    end = time.monotonic() + seconds
    while True:
        img = v.screenshot(path)
        if ok(img) or time.monotonic() > end:
            return img
        time.sleep(0.3)


def _scene_pixels(img: np.ndarray) -> int:
    """Distinct colours: a drawn scene has hundreds (shading), a blank or menu-only window a few."""
    return len(np.unique(img.reshape(-1, 3), axis=0))


def test_window_shows_the_scene_and_reloads_a_saved_edit(truck, tmp_path):
    with ViewInXvfb([truck.name], truck.parent) as v:
        v.wait_for("loaded Scene")
        # (a loaded machine may take seconds between the load and the first drawn frame)
        first = _until(v, tmp_path / "first.png", lambda img: _scene_pixels(img) > 200)
        assert _scene_pixels(first) > 200, "the window looks blank"
        time.sleep(1.0)
        first = v.screenshot(tmp_path / "first.png")
        text = truck.read_text()
        truck.write_text(text.replace("position.z: 1.1", "position.z: 3.0"))
        t0 = time.monotonic()
        v.wait_for("loaded Scene", count=2, seconds=10)
        reload_s = time.monotonic() - t0
        time.sleep(0.5)
        after = v.screenshot(tmp_path / "after.png")
        assert np.abs(after.astype(int) - first.astype(int)).mean() > 0.5, "the reloaded scene looks the same"
        # a broken edit: a message, the last good scene stays on screen, the window stays open
        truck.write_text(text.replace("radius: 0.26", "radius: "))
        v.wait_for("cannot load", seconds=10)
        time.sleep(0.5)
        broken = v.screenshot(tmp_path / "broken.png")
        assert _scene_pixels(broken) > 200 and v.proc.poll() is None
        assert "still showing the last good scene" in v.stderr()
    print(f"reload on screen after {reload_s:.2f} s")


def test_holding_up_drives_the_truck_and_releasing_stops_it(truck, tmp_path):
    (truck.parent / "drive.py").write_text(LOGGING_CONTROLLER)
    with ViewInXvfb([truck.name, "--controller", "drive.py"], truck.parent) as v:
        v.wait_for("loaded Scene")
        _until(v, tmp_path / "shown.png", lambda img: _scene_pixels(img) > 200)
        time.sleep(2.0)  # land
        v.xdotool("key", "l")
        v.xdotool("keydown", "Up")
        time.sleep(3.0)
        v.xdotool("keyup", "Up")
        time.sleep(0.2)
        v.xdotool("key", "l")
        time.sleep(2.0)
        v.xdotool("key", "l")
        time.sleep(0.5)
        v.xdotool("key", "l")
        time.sleep(0.5)
    states = [json.loads(line) for line in (truck.parent / "states.jsonl").read_text().splitlines()]
    assert len(states) == 4, states
    start, released, later, last = states
    assert released["t"] > start["t"] and released["x"] < start["x"] - 0.2, states  # forward is -x
    assert abs(later["vx"]) < 0.05 and abs(last["x"] - later["x"]) < 0.02, states  # stopped


def test_reset_view_frames_the_model_and_panels_sit_on_the_right(truck, tmp_path):
    """Issue 40.6: Ctrl+A (MuJoCo's reset view) framed the 100 m ground, the truck a few pixels; now
    it is the opening camera. Our status and signal panels are drawn on the right, where MuJoCo's F1
    help and F2 info (on the left) do not cover them. Paused: the pictures compare like for like."""
    with ViewInXvfb([truck.name, "--paused"], truck.parent) as v:
        v.wait_for("loaded Scene")
        _until(v, tmp_path / "opening.png", lambda img: _scene_pixels(img) > 200)
        time.sleep(1.5)
        opening = v.screenshot(tmp_path / "opening.png")
        for _ in range(12):  # zoom with the wheel
            v.xdotool("click", "5")
            time.sleep(0.05)
        time.sleep(1.0)
        zoomed = v.screenshot(tmp_path / "zoomed.png")
        v.xdotool("key", "ctrl+a")
        time.sleep(1.5)
        reset = v.screenshot(tmp_path / "reset.png")
        v.xdotool("key", "F1")
        helped = _until(v, tmp_path / "help.png", lambda img: _help_shown(img, reset))
    diff = lambda a, b: np.abs(a.astype(int) - b.astype(int)).mean()  # noqa: E731
    assert diff(zoomed, opening) > 2 * diff(reset, opening), (diff(zoomed, opening), diff(reset, opening))
    # the panels are right of the help's box, top to bottom: F1 changes nothing there
    from plxtools.view.window import HELP_PX

    h, w, _ = opening.shape
    right = lambda img: img[:, HELP_PX + 5:]  # noqa: E731
    assert np.abs(right(helped).astype(int) - right(reset).astype(int)).max() == 0
    assert _help_shown(helped, reset)


def _help_shown(img: np.ndarray, before: np.ndarray) -> bool:
    from plxtools.view.window import HELP_PX

    return float(np.abs(img[:, : HELP_PX - 20].astype(int) - before[:, : HELP_PX - 20].astype(int)).mean()) > 5


def test_a_scene_that_would_fall_out_of_view_opens_paused_on_the_chassis(tmp_path):
    """Issue 40.6: the tutorial's step 3 (a chassis, no ground) showed a black window: it had fallen out
    of view before the first frame. It now opens paused on the chassis and says why; E plays."""
    import shutil
    from pathlib import Path

    src = Path(__file__).resolve().parents[2] / "examples" / "tutorial" / "step03-chassis" / "boxtruck.openplx"
    shutil.copy(src, tmp_path / "boxtruck.openplx")
    with ViewInXvfb(["boxtruck.openplx"], tmp_path) as v:
        v.wait_for("paused: it leaves the view")
        # the chassis fills the middle (reddish, shaded); falling, it leaves the background
        centre = lambda img: img[img.shape[0] // 4: 3 * img.shape[0] // 4, img.shape[1] // 4: 3 * img.shape[1] // 4]  # noqa: E731
        red = lambda img: int((centre(img)[..., 0].astype(int) > centre(img)[..., 1].astype(int) + 40).sum())  # noqa: E731
        big = lambda img: red(img) > 0.1 * centre(img).shape[0] * centre(img).shape[1]  # noqa: E731
        waiting = _until(v, tmp_path / "waiting.png", big)
        time.sleep(1.0)
        still = v.screenshot(tmp_path / "still.png")
        v.xdotool("key", "e")
        played = _until(v, tmp_path / "played.png", lambda img: red(img) < red(waiting) / 10)
    assert big(waiting) and red(still) == red(waiting), (red(waiting), red(still))  # it waits
    assert red(played) < red(waiting) / 10, (red(played), red(waiting))
