"""`plx check --simulate --video FILE.gif|FILE.mp4`: an offscreen recording of the simulation.

The camera follows the dynamic bodies (its look-at point moves with their centre, its distance is
the one that framed them at the start), or with `--video-camera fixed` stays where it framed them at
the start, so that motion shows against the ground. Cylinders of moving bodies carry a cross on
their faces, so that a turning wheel looks turning.  Frames are taken at ``fps`` per simulated second, the
first at t = 0, so a run of D seconds gives round(D * fps) frames.

Encoders (the ``video`` extra, see docs/view.md): Pillow writes GIF (MIT-CMU licence, about 7 MB);
PyAV writes MP4 with H.264 (BSD-3-Clause around FFmpeg libraries that it ships, about 100 MB
installed).  Both are imported only here, when a video is asked for, so `plx lint` and `plx fmt`
never load them.
"""

from __future__ import annotations

import math
import os
import tempfile
from typing import Any

import numpy as np

from plxtools.check.mujoco.kinematic import Stepper
from plxtools.check.mujoco.render import _gl_context, frame_camera
from plxtools.check.mujoco.results import VISUAL_GROUP

COLLISION_BEHIND_VISUALS = 3  # geom group of collision geometry on bodies that have visuals
VIDEO_SUFFIXES = (".gif", ".mp4")


class VideoError(RuntimeError):
    """The video cannot be written (no encoder installed, no GL, a bad path): a one-line reason."""


def show_visuals(model: Any) -> None:
    """Draw a body's visuals in place of its collision geometry, as the AGX viewer does.

    Collision geoms of bodies that carry a visual move to group 3 (hidden by default; the view's
    G key swaps groups 2 and 3).  Geom groups only filter drawing and ray casts: contacts are
    set by contype/conaffinity, so the physics does not change."""
    with_visual = {int(model.geom_bodyid[g]) for g in range(model.ngeom) if model.geom_group[g] == VISUAL_GROUP}
    for g in range(model.ngeom):
        if model.geom_group[g] == 0 and int(model.geom_bodyid[g]) in with_visual:
            model.geom_group[g] = COLLISION_BEHIND_VISUALS


def check_target(path: str) -> None:
    """Refuse a path the encoders cannot write before any simulation runs."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in VIDEO_SUFFIXES:
        raise VideoError(f"--video writes .gif or .mp4, not {suffix or 'a file without a suffix'} ({path})")
    encoder_module(suffix)
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise VideoError(f"cannot write {path}: no folder {folder}")


def check_fps(fps: float) -> None:
    if not (math.isfinite(fps) and 0 < fps <= 100):
        raise VideoError(f"--fps must be a number of frames per second in (0, 100]; got {fps:g}")


def encoder_module(suffix: str) -> Any:
    try:
        if suffix == ".gif":
            from PIL import Image

            return Image
        import av

        return av
    except ImportError:
        lib = "Pillow" if suffix == ".gif" else "PyAV"
        raise VideoError(f"writing {suffix} needs {lib}: pip install 'plxtools[video]'") from None


CAMERAS = ("follow", "fixed")  # --video-camera


def record(compiled: Any, path: str, duration: float, fps: float = 25.0, width: int = 640,
           height: int = 480, camera: str = "follow") -> dict[str, Any]:
    """Simulate ``compiled`` from its initial state for ``duration`` s and write the video; the camera
    follows the bodies, or stays where it framed them at the start (``camera="fixed"``)."""
    import mujoco

    check_target(path)
    check_fps(fps)
    width, height = width // 2 * 2, height // 2 * 2  # H.264's 4:2:0 needs even sides
    model = compiled.model
    show_visuals(model)
    model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), width)
    model.vis.global_.offheight = max(int(model.vis.global_.offheight), height)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("initial").id)
    mujoco.mj_forward(model, data)
    stepper = Stepper(mujoco, compiled, model, data)  # the step plx check --simulate takes
    n = max(1, int(round(duration * fps)))
    dt = float(model.opt.timestep)
    frames: list[np.ndarray] = []
    try:
        ctx = _gl_context(width, height)
    except Exception as exc:  # RenderUnavailable: the message says which libraries are missing
        raise VideoError(str(exc)) from None
    con = None
    samples = int(model.vis.quality.offsamples)
    try:
        # no multisampling: with software OpenGL (llvmpipe, a headless machine's) it doubled the
        # CPU of every frame, for edges a GIF's palette blurs anyway
        model.vis.quality.offsamples = 0
        con = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, con)
        scn = mujoco.MjvScene(model, maxgeom=max(1000, 4 * model.ngeom + 200))
        opt = mujoco.MjvOption()
        cam = frame_camera(model, data)
        start = np.array(cam.lookat)
        offset = start - _centre(model, data)
        floor = floor_height(model, data)
        rect = mujoco.MjrRect(0, 0, width, height)
        done = 0
        for k in range(n):
            target = int(round(k / fps / dt))
            while done < target:
                stepper.step(done)
                done += 1
            if camera != "fixed":
                cam.lookat[:] = _centre(model, data) + offset
            mujoco.mjv_updateScene(model, data, opt, None, cam, mujoco.mjtCatBit.mjCAT_ALL, scn)
            floor_grid(scn, floor, cam.lookat)
            wheel_marks(scn, model, data)
            mujoco.mjr_render(rect, scn, con)
            rgb = np.empty((height, width, 3), dtype=np.uint8)
            mujoco.mjr_readPixels(rgb, None, rect, con)
            frames.append(np.flipud(rgb))
    finally:
        model.vis.quality.offsamples = samples
        if con is not None:
            con.free()
        ctx.free()
    _encode(frames, path, fps)
    return {"path": path, "frames": n, "fps": fps, "width": width, "height": height,
            "seconds": float(data.time)}


def floor_height(model: Any, data: Any) -> float | None:
    """The top of the highest static box or plane under the scene (None: there is no floor)."""
    import mujoco

    tops = []
    for g in range(model.ngeom):
        if model.body_weldid[model.geom_bodyid[g]] != 0 or model.geom_group[g] not in (0, COLLISION_BEHIND_VISUALS):
            continue
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
            tops.append(float(data.geom_xpos[g][2]))
        elif model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX and min(model.geom_size[g][:2]) > 2.0:
            tops.append(float(data.geom_xpos[g][2] + abs(data.geom_xmat[g].reshape(3, 3)[2]) @ model.geom_size[g]))
    return max(tops) if tops else None


def floor_grid(scn: Any, floor: float | None, centre: Any, extent: int = 12, rgba=(0.25, 0.28, 0.25, 1.0)) -> None:
    """Draw 1 m grid lines on the floor around ``centre``: with a camera that follows the bodies,
    the grid is what shows that they move."""
    import mujoco

    if floor is None:
        return
    cx, cy = round(float(centre[0])), round(float(centre[1]))
    z = floor + 0.003
    for i in range(-extent, extent + 1):
        for a, b in (((cx + i, cy - extent), (cx + i, cy + extent)), ((cx - extent, cy + i), (cx + extent, cy + i))):
            if scn.ngeom >= scn.maxgeom:
                return
            g = scn.geoms[scn.ngeom]
            mujoco.mjv_initGeom(g, mujoco.mjtGeom.mjGEOM_LINE, np.zeros(3), np.zeros(3), np.zeros(9),
                                np.array(rgba, dtype=np.float32))
            mujoco.mjv_connector(g, mujoco.mjtGeom.mjGEOM_LINE, 2.0, np.array([a[0], a[1], z]), np.array([b[0], b[1], z]))
            scn.ngeom += 1


def wheel_marks(scn: Any, model: Any, data: Any, rgba=(0.95, 0.95, 0.9, 1.0)) -> None:
    """A cross on both faces of every cylinder of a moving body: a plain cylinder turning about its
    axis looks still, and a driving truck looked parked (issue 40.6)."""
    import mujoco

    cyl = mujoco.mjtGeom.mjGEOM_CYLINDER
    colour = np.array(rgba, dtype=np.float32)
    for g in range(model.ngeom):
        if model.geom_type[g] != cyl or model.body_weldid[model.geom_bodyid[g]] == 0 \
                or model.geom_rgba[g][3] == 0 or model.geom_group[g] > 5:
            continue
        radius, half = float(model.geom_size[g][0]), float(model.geom_size[g][1])
        rot = data.geom_xmat[g].reshape(3, 3)
        axis = rot[:, 2]
        for side in (1.0, -1.0):
            centre = data.geom_xpos[g] + axis * side * (half + 0.002)
            for turn in (0, 1):  # two bars across the face, at right angles
                if scn.ngeom >= scn.maxgeom:
                    return
                size = np.array([radius * 0.85, radius * 0.09, 0.002]) if turn == 0 else \
                    np.array([radius * 0.09, radius * 0.85, 0.002])
                mujoco.mjv_initGeom(scn.geoms[scn.ngeom], mujoco.mjtGeom.mjGEOM_BOX, size, centre,
                                    rot.reshape(-1), colour)
                scn.ngeom += 1


def _centre(model: Any, data: Any) -> np.ndarray:
    """Mean position of the dynamic bodies (the world origin when none moves)."""
    ids = [b for b in range(1, model.nbody) if model.body_weldid[b] != 0]
    return np.mean(data.xpos[ids], axis=0) if ids else np.zeros(3)


def _encode(frames: list[np.ndarray], path: str, fps: float) -> None:
    """Write to a temporary file beside ``path`` and rename: never a half-written video."""
    suffix = os.path.splitext(path)[1].lower()
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=suffix, prefix=".plx-video-", dir=folder)
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # as an ordinary new file, not mkstemp's 0600
    try:
        if suffix == ".gif":
            _gif(frames, tmp, fps)
        else:
            _mp4(frames, tmp, fps)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _gif(frames: list[np.ndarray], path: str, fps: float) -> None:
    Image = encoder_module(".gif")
    # one palette for the whole clip (taken from the first frame) keeps colours steady
    first = Image.fromarray(frames[0]).quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    images = [first] + [Image.fromarray(f).quantize(palette=first, dither=Image.Dither.NONE) for f in frames[1:]]
    images[0].save(path, save_all=True, append_images=images[1:], duration=round(1000 / fps), loop=0,
                   optimize=False, disposal=1)


def _mp4(frames: list[np.ndarray], path: str, fps: float) -> None:
    from fractions import Fraction

    av = encoder_module(".mp4")
    h, w = frames[0].shape[:2]
    with av.open(path, mode="w", format="mp4") as container:
        stream = container.add_stream("libx264", rate=Fraction(fps).limit_denominator(1000))
        stream.width, stream.height, stream.pix_fmt = w, h, "yuv420p"
        stream.options = {"crf": "23", "preset": "veryfast"}
        for f in frames:
            for packet in stream.encode(av.VideoFrame.from_ndarray(f, format="rgb24")):
                container.mux(packet)
        for packet in stream.encode():
            container.mux(packet)
