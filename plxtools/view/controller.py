"""Running a controller script against the view, under the runtime's names.

The tutorial's script loads the scene with ``application().loadOpenPlxFile(path, root())`` inside
a ``buildScene()`` function and binds keys with ``KeyboardCallback.bind``.  ``plx view FILE
--controller script.py`` executes the script (not as ``__main__``, so its ``init_app`` block does
not run), then calls its ``buildScene()`` (or ``build_scene()``) after every load and reload;
``application().loadOpenPlxFile`` returns the view's current simulation (a
:class:`plxtools.check.api.Simulation`, which has ``scene()`` and ``getInputSignalQueue()``).
"""

from __future__ import annotations

import os
import runpy
import traceback
from typing import Any

from plxtools.view.display_stubs import CameraData, Ignored


class ControllerError(Exception):
    """The controller script failed; the message holds its own traceback (the user's code)."""


class _Application:
    """``application()``: what a controller script asks for the scene the view shows."""

    def __init__(self) -> None:
        self.simulation: Any = None

    def loadOpenPlxFile(self, path: str, root: Any = None) -> Any:  # noqa: N802 - the runtime's spelling
        sim = self.simulation
        if sim is None:
            raise RuntimeError("loadOpenPlxFile: no scene is loaded (run the script with plx view FILE --controller)")
        if os.path.realpath(path) != os.path.realpath(sim.path):
            raise RuntimeError(f"loadOpenPlxFile({path!r}): this view shows {sim.path}; "
                               f"run plx view {path} --controller ... to drive that file")
        return sim

    load_openplx_file = loadOpenPlxFile

    def getSimulation(self) -> Any:  # noqa: N802
        return self.simulation

    # camera, shadows and lights: MuJoCo's viewer has its own; see plxtools.view.display_stubs
    def getCameraData(self) -> CameraData:  # noqa: N802
        return CameraData()

    def applyCameraData(self, camera_data: Any) -> None:  # noqa: N802
        """Ignored: the view keeps MuJoCo's camera (and the user's, across reloads)."""

    def getSceneDecorator(self) -> Ignored:  # noqa: N802
        return Ignored("SceneDecorator")


_APP = _Application()


def application() -> _Application:
    return _APP


def root() -> None:
    """The runtime's scene-graph root; the view has none to give (loadOpenPlxFile ignores it)."""
    return None


def init_app(*args: Any, **kwargs: Any) -> None:
    """The runtime's entry point; under ``plx view --controller`` the view is the application."""
    raise RuntimeError("run this script with: plx view MODEL.openplx --controller SCRIPT.py")


def run_controller(script: str, simulation: Any) -> None:
    """Execute ``script`` and call its buildScene() with ``simulation`` as the loaded scene."""
    _APP.simulation = simulation
    try:
        ns = runpy.run_path(script, run_name="__plx_controller__")
        build = ns.get("buildScene") or ns.get("build_scene")
        if build is None:
            raise ControllerError(f"{script}: defines no buildScene() (or build_scene()) to call after loading")
        build()
    except ControllerError:
        raise
    except BaseException as exc:  # the user's code: show its own frames, not the view's
        if isinstance(exc, KeyboardInterrupt):
            raise
        tb = traceback.TracebackException.from_exception(exc)
        frames = [f for f in tb.stack if os.path.realpath(f.filename) == os.path.realpath(script)]
        tb.stack = traceback.StackSummary.from_list(frames or list(tb.stack)[-1:])
        raise ControllerError(f"{script}: {''.join(tb.format()).rstrip()}") from None
