"""The window: MuJoCo's own interactive viewer (``mujoco.viewer.launch_passive``) over a ViewSession.

MuJoCo's viewer owns the camera, mouse, pause of drawing, contact and joint display and body
perturbation; this loop steps the simulation in real time, feeds keys to the session, polls the
watched files and swaps the new model into the open window on reload (keeping the camera).

MuJoCo calls the key callback on presses only, on its render thread: the callback queues the key
and remembers the GLFW window, and this loop polls ``glfw.get_key`` for the held keys to send
their releases (a held Up drives, releasing it stops).
"""

from __future__ import annotations

import queue
import sys
import threading
import time
from typing import Any

from plxtools.view.session import ViewSession

POLL_S = 0.1  # how often the watched files are looked at (a stat of each: cheap)
FRAME_S = 1 / 60
OVERLAY = True
# MuJoCo's passive viewer loses a pending overlay text when it loads a model, and set_texts() then
# waits for ever: a swap starts only this long after the last set_texts()
QUIET_BEFORE_SWAP_S = 0.5
MAX_SIGNAL_LINES = 12  # and at most half the window's height: the scene stays visible
MAX_OVERLAY_CHARS = 440  # MuJoCo's overlay drops what is past about 500 characters
# MuJoCo's overlay at font scale 100, measured on screenshots: a character is about 7 px wide, a line
# 23 px high; its F1 help box reaches 335 px from the left edge (F2's info box less far)
CHAR_PX, LINE_PX, HELP_PX = 7, 23, 345


def run(session: ViewSession, *, wait_for_fix: bool = True) -> int:
    """Open the window on the session's model; returns when the window is closed."""
    import glfw
    import mujoco
    import mujoco.viewer

    from plxtools.check.mujoco.video import show_visuals
    from plxtools.check.mujoco.render import frame_camera

    session.load()
    while session.sim is None:  # nothing to show yet: say why and wait for a fix, never a blank window
        if not wait_for_fix:
            return 1
        print(f"plx view: waiting for a change to {session.path} (Ctrl+C quits)", file=sys.stderr)
        try:
            while session.poll() is None:
                time.sleep(POLL_S)
        except KeyboardInterrupt:
            return 1

    # GLFW reports errors through the Python glfw package's callback, which needs the GIL; MuJoCo's
    # set_texts() holds the GIL while it waits for the render thread: a GLFW error then (Xvfb has
    # a few) would hang both threads. The viewer works without the report.
    glfw.set_error_callback(None)
    keys: "queue.Queue[int]" = queue.Queue()
    window: dict[str, Any] = {}

    def on_key(code: int) -> None:  # MuJoCo's render thread
        window.setdefault("glfw", glfw.get_current_context())
        keys.put(code)

    def _open(sim: Any) -> Any:
        show_visuals(sim.model)
        frame_statistic(sim.model, sim.data)
        return mujoco.viewer.launch_passive(sim.model, sim.data, key_callback=on_key,
                                            show_left_ui=False, show_right_ui=False)  # Tab / Shift+Tab show them

    sim = session.sim
    handle = _open(sim)
    shown = session.generation
    with handle.lock():
        _set_camera(handle.cam, frame_camera(sim.model, sim.data))  # = Ctrl+A (frame_statistic)
    handle.sync()
    last = time.perf_counter()
    drawn = not OVERLAY  # the clock starts at the first drawn frame: nothing falls out of view unseen
    next_poll = last + POLL_S
    shown_texts: tuple[str, str] = ("", "")
    swapping: threading.Thread | None = None
    texts_at = 0.0
    kept: Any = None
    try:
        while handle.is_running():
            with handle.lock():
                while not keys.empty():
                    session.key(keys.get(), True)
                win = window.get("glfw")
                if win is not None:
                    for code in list(session.held):
                        if glfw.get_key(win, code) == glfw.RELEASE:
                            session.key(code, False)
            now = time.perf_counter()
            if now >= next_poll:
                session.poll()
                next_poll = now + POLL_S
            if swapping is not None:
                if swapping.is_alive():  # the render thread takes the new model: keep syncing meanwhile
                    handle.sync()
                    time.sleep(FRAME_S)
                    continue
                with handle.lock():
                    _set_camera(handle.cam, kept)
                swapping, last = None, time.perf_counter()
            if session.generation != shown and session.sim is not None and \
                    time.perf_counter() - texts_at < QUIET_BEFORE_SWAP_S:
                handle.sync()  # no new overlay text until the viewer has taken the last one
                time.sleep(FRAME_S)
                continue
            if session.generation != shown and session.sim is not None:
                kept = mujoco.MjvCamera()
                _set_camera(kept, handle.cam)
                show_visuals(session.sim.model)
                frame_statistic(session.sim.model, session.sim.data)
                # the viewer's load() returns once its render thread has taken the model, which in
                # passive mode needs this loop's sync() calls: so it runs on a helper thread
                swapping = threading.Thread(target=handle._get_sim().load, daemon=True,
                                            args=(session.sim.model, session.sim.data, session.path))
                swapping.start()
                shown = session.generation
                continue
            with handle.lock():
                now = time.perf_counter()
                session.advance(now - last if drawn else 0.0)  # (nothing before the first frame)
                last = now
                _decorate(handle, session)
                status, signals = _panel_texts(handle, session)
            handle.sync()
            # outside our lock (set_texts waits for the render thread to take the previous text)
            texts = ("\n".join(status), "\n".join(signals))
            if texts != shown_texts and OVERLAY:
                # on the right: MuJoCo draws its F1 help top left and its F2 info bottom left
                handle.set_texts([(mujoco.mjtFontScale.mjFONTSCALE_100, mujoco.mjtGridPos.mjGRID_TOPRIGHT, texts[0], ""),
                                  (mujoco.mjtFontScale.mjFONTSCALE_100, mujoco.mjtGridPos.mjGRID_BOTTOMRIGHT, texts[1],
                                   "")])
                shown_texts, texts_at = texts, time.perf_counter()
                # set_texts returns once the render thread took the text, to draw it: the first
                # frame is on its way, and the clock starts now
                last, drawn = (last, drawn) if drawn else (texts_at, True)
            spare = FRAME_S - (time.perf_counter() - now)
            if spare > 0:
                time.sleep(spare)
    except KeyboardInterrupt:
        pass
    finally:
        handle.close()
    return 0


def _decorate(handle: Any, session: ViewSession) -> None:
    """Visuals or collision geometry (G), a 1 m grid on the floor around where the camera looks, and
    crosses on the wheels."""
    from plxtools.check.mujoco.results import VISUAL_GROUP
    from plxtools.check.mujoco.video import COLLISION_BEHIND_VISUALS, floor_grid, floor_height, wheel_marks

    handle.opt.geomgroup[VISUAL_GROUP] = 0 if session.show_collision else 1
    handle.opt.geomgroup[COLLISION_BEHIND_VISUALS] = 1 if session.show_collision else 0
    if handle.user_scn is not None:
        handle.user_scn.ngeom = 0
        floor_grid(handle.user_scn, floor_height(session.sim.model, session.sim.data), handle.cam.lookat)
        wheel_marks(handle.user_scn, session.sim.model, session.sim.data)


def frame_statistic(model: Any, data: Any) -> None:
    """Make MuJoCo's "reset view" (Ctrl+A: a free camera from `stat.center`, 1.5 `stat.extent` away,
    at `vis.global` azimuth and elevation) the opening camera, which frames the bodies, where it
    framed the model's whole extent (the 100 m ground: the truck a few pixels). The far clipping
    plane stays where it was (it is a multiple of the extent)."""
    from plxtools.check.mujoco.render import frame_camera

    cam = frame_camera(model, data)
    far = float(model.vis.map.zfar) * float(model.stat.extent)
    extent = max(float(cam.distance) / 1.5, 1e-3)
    model.stat.center[:] = cam.lookat
    model.stat.extent = extent
    model.vis.global_.azimuth = float(cam.azimuth)
    model.vis.global_.elevation = float(cam.elevation)
    model.vis.map.zfar = max(far, 50.0 * extent) / extent


def _panel_texts(handle: Any, session: ViewSession) -> tuple[list[str], list[str]]:
    """The status panel's lines (top right) and the signal panel's (bottom right), fitted to the window."""
    cols, rows = _panel_room(handle)
    status = [_cut(line, cols) for line in session.status(cols)]
    if len(status) > rows - 2:  # a long error: its last lines go, the clock line stays
        status = status[: max(1, rows - 4)] + ["  ...", status[-1]]
    most = max(1, min(MAX_SIGNAL_LINES, rows // 2, rows - len(status) - 1))
    return status, _fit(session.signals(cols), most)


def _panel_room(handle: Any) -> tuple[int, int]:
    """Characters per line and lines the right-hand panels have: they stay right of MuJoCo's F1 help
    (the widest thing MuJoCo draws on the left) and the status (top) and signal (bottom) panels
    share the height, so that no two overlap (issue 40.6)."""
    vp = getattr(handle, "viewport", None)
    width, height = (int(vp.width), int(vp.height)) if vp is not None and vp.width > 0 else (1200, 900)
    return max(24, (width - HELP_PX - 2 * CHAR_PX) // CHAR_PX), max(3, height // LINE_PX - 1)


def _cut(line: str, cols: int) -> str:
    return line if len(line) <= cols else line[: cols - 3] + "..."


def _fit(lines: list[str], most: int = MAX_SIGNAL_LINES) -> list[str]:
    """As many lines as MuJoCo's overlay shows whole (it cuts long text) and the window has room for,
    then how many are left out."""
    out: list[str] = []
    used = 0
    for i, line in enumerate(lines):
        if len(out) >= most - 1 and i < len(lines) - 1 or used + len(line) + 1 > MAX_OVERLAY_CHARS:
            out.append(f"... {len(lines) - i} more")
            break
        out.append(line)
        used += len(line) + 1
    return out


def _set_camera(dst: Any, src: Any) -> None:
    dst.lookat[:] = src.lookat
    dst.distance = src.distance
    dst.azimuth = src.azimuth
    dst.elevation = src.elevation
