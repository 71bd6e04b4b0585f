"""Stand-ins for the AGX runtime's display calls, which MuJoCo's viewer has no use for.

The tutorial's controller sets up the camera, shadows and lights (``application().getCameraData()``,
``getSceneDecorator().setEnableShadows(True)``, ``agx.Vec3``, ``agxOSG.SceneDecorator.LIGHT0``)
before it loads the scene.  ``plx view`` draws with MuJoCo's own camera and lights, so these calls
are accepted and ignored rather than removed from the script: a controller written for AGX runs
with only its imports changed.  Every method of :class:`Ignored` returns the same object, so a
chain such as ``getLightSource(LIGHT0).setPosition(...)`` is ignored as a whole.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any


class Ignored:
    """Accepts any method call and any attribute assignment, and does nothing with them."""

    def __init__(self, what: str) -> None:
        object.__setattr__(self, "_what", what)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):  # copy, pickle and friends must not see a method that is not there
            raise AttributeError(name)

        def ignored(*_args: Any, **_kwargs: Any) -> "Ignored":
            return self

        return ignored

    def __repr__(self) -> str:
        return f"<{self._what}: ignored by plx view>"


class CameraData(SimpleNamespace):
    """``application().getCameraData()``: fields a script may set; ``applyCameraData`` ignores them."""

    def __init__(self) -> None:
        super().__init__(eye=None, center=None, up=None, nearClippingPlane=None, farClippingPlane=None)


class Vec3(tuple):
    """``agx.Vec3(x, y, z)`` as a plain tuple of floats (used only for camera and light set-up)."""

    def __new__(cls, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> "Vec3":
        return super().__new__(cls, (float(x), float(y), float(z)))


class Vec4(tuple):
    """``agx.Vec4(x, y, z, w)`` as a plain tuple of floats."""

    def __new__(cls, x: float = 0.0, y: float = 0.0, z: float = 0.0, w: float = 0.0) -> "Vec4":
        return super().__new__(cls, (float(x), float(y), float(z), float(w)))


class SceneDecorator:
    """``agxOSG.SceneDecorator``'s constants, so that the script's arguments evaluate."""

    NO_SHADOWS, SHADOWMAP, SOFT_SHADOWMAP, LIGHT_SPACE_PERSPECTIVE_SHADOWMAP = 0, 1, 2, 3
    LIGHT0, LIGHT1, LIGHT2 = 0, 1, 2


agx = SimpleNamespace(Vec3=Vec3, Vec4=Vec4)
agxOSG = SimpleNamespace(SceneDecorator=SceneDecorator)  # noqa: N816 - the runtime's module name
