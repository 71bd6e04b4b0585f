"""Offscreen PNG rendering of a compiled scene (EGL, or OSMesa when selected).

Rendering does not rely on ``MUJOCO_GL`` (which mujoco reads once, at its first import): it builds
an EGL/OSMesa context directly with ``mujoco.egl`` / ``mujoco.osmesa`` and drives the classic
``MjrContext`` renderer.  The only process-wide settings it touches are ``PYOPENGL_PLATFORM``
(when unset and PyOpenGL is not imported yet) and ``MESA_SHADER_CACHE_DISABLE``.
"""

from __future__ import annotations

import math
import os
import struct
import sys
import zlib
from typing import Any

import numpy as np

from plxtools.check.mujoco.compile import VISUAL_GROUP, CompiledScene
from plxtools.fileio import write_output


class RenderUnavailable(RuntimeError):
    """Offscreen OpenGL rendering cannot work in this process / on this machine."""


def write_png(path: str, rgb: np.ndarray) -> None:
    """Write an (H, W, 3) uint8 array as an 8-bit RGB PNG using only zlib."""
    img = np.ascontiguousarray(rgb, dtype=np.uint8)
    h, w = img.shape[:2]
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))

    def chunk(tag: bytes, payload: bytes) -> bytes:
        return (
            struct.pack(">I", len(payload))
            + tag
            + payload
            + struct.pack(">I", zlib.crc32(tag + payload) & 0xFFFFFFFF)
        )

    write_output(path, b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                 + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def _platform_name() -> str:
    p = os.environ.get("PYOPENGL_PLATFORM", "").strip().lower()
    if p:
        return p
    gl = os.environ.get("MUJOCO_GL", "").strip().lower()
    return gl if gl in ("egl", "osmesa") else "egl"


def _gl_context(width: int, height: int) -> Any:
    os.environ.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    platform = _platform_name()
    if platform not in ("egl", "osmesa"):
        raise RenderUnavailable(
            f"PYOPENGL_PLATFORM={platform!r}: only headless 'egl' or 'osmesa' rendering is supported"
        )
    if "OpenGL" in sys.modules:
        try:
            import OpenGL.platform as glp

            current = type(glp.PLATFORM).__name__.lower()
        except Exception as err:  # pragma: no cover - depends on the GL stack
            raise RenderUnavailable(
                f"PyOpenGL is already imported and its platform cannot be determined: {err}"
            ) from err
        if platform not in current:
            raise RenderUnavailable(
                f"PyOpenGL was already imported with platform {current!r}; headless {platform} rendering needs "
                f"PYOPENGL_PLATFORM={platform} (or MUJOCO_GL={platform}) set before anything imports OpenGL"
            )
    else:
        os.environ.setdefault("PYOPENGL_PLATFORM", platform)
    try:
        if platform == "egl":
            from mujoco.egl import GLContext
        else:
            from mujoco.osmesa import GLContext
        ctx = GLContext(width, height)
        ctx.make_current()
        return ctx
    except Exception as err:
        hint = (
            "EGL needs libEGL + Mesa (libegl1, libegl-mesa0, libgl1-mesa-dri, libgbm1)"
            if platform == "egl"
            else "OSMesa needs libosmesa6"
        )
        raise RenderUnavailable(
            f"cannot create a headless {platform} OpenGL context ({type(err).__name__}: {err}); {hint}"
        ) from err


def frame_camera(model: Any, data: Any) -> Any:
    """A free camera looking at the dynamic bodies (all bodies when none is dynamic)."""
    import mujoco

    pts, radii = [], []
    for g in range(model.ngeom):
        dynamic = model.body_weldid[model.geom_bodyid[g]] != 0
        if dynamic and model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE:
            pts.append(data.geom_xpos[g].copy())
            radii.append(float(model.geom_rbound[g]))
    if not pts:
        for g in range(model.ngeom):
            if model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE:
                pts.append(data.geom_xpos[g].copy())
                radii.append(float(model.geom_rbound[g]))
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    if not pts:
        cam.lookat[:] = [0, 0, 0]
        cam.distance = 5.0
    else:
        p = np.array(pts)
        lo = np.min(p - np.array(radii)[:, None], axis=0)
        hi = np.max(p + np.array(radii)[:, None], axis=0)
        center = (lo + hi) / 2
        radius = max(float(np.linalg.norm(hi - lo)) / 2, 0.05)
        fovy = math.radians(float(model.vis.global_.fovy))
        cam.lookat[:] = center
        cam.distance = 0.95 * radius / math.tan(fovy / 2)
    cam.azimuth = 135.0
    cam.elevation = -25.0
    return cam


def render_compiled(
    compiled: CompiledScene, path: str, width: int = 640, height: int = 480, at_time: float = 0.0
) -> dict[str, Any]:
    if not compiled.ok:
        raise ValueError("scene did not compile; see compiled.notes")
    import mujoco

    model = compiled.model
    model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), width)
    model.vis.global_.offheight = max(int(model.vis.global_.offheight), height)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("initial").id)
    if at_time > 0:
        mujoco.mj_step(model, data, nstep=max(1, int(round(at_time / model.opt.timestep))))
    mujoco.mj_forward(model, data)
    ctx = _gl_context(width, height)
    con = None
    try:
        con = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, con)
        scn = mujoco.MjvScene(model, maxgeom=max(1000, 4 * model.ngeom))
        opt = mujoco.MjvOption()
        opt.geomgroup[VISUAL_GROUP] = 1
        cam = frame_camera(model, data)
        mujoco.mjv_updateScene(model, data, opt, None, cam, mujoco.mjtCatBit.mjCAT_ALL, scn)
        rect = mujoco.MjrRect(0, 0, width, height)
        mujoco.mjr_render(rect, scn, con)
        rgb = np.empty((height, width, 3), dtype=np.uint8)
        mujoco.mjr_readPixels(rgb, None, rect, con)
    finally:
        if con is not None:
            con.free()
        ctx.free()
    rgb = np.flipud(rgb)
    write_png(path, rgb)
    return {
        "path": path,
        "width": width,
        "height": height,
        "time": float(data.time),
        "camera": {
            "lookat": [float(v) for v in cam.lookat],
            "distance": float(cam.distance),
            "azimuth": 135.0,
            "elevation": -25.0,
        },
        "distinct_colours": int(len(np.unique(rgb.reshape(-1, 3), axis=0))),
    }
