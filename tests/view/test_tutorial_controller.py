"""The tutorial's step-11 controller, read from the shared seed at run time, drives plx view.

The script is not copied into the repository: the test cuts it out of the tutorial text, replaces
only its import lines with plx's (the table in docs/view.md), writes it beside a copy of
examples/tutorial/step11-controls/boxtruck.openplx (so the file name it loads is unchanged), and
runs it through ViewSession's --controller machinery without a window.
"""

from __future__ import annotations

import difflib
import shutil
from pathlib import Path

import pytest

from plxtools.view.keys import GuiEventListener as K
from plxtools.view.keys import KeyboardCallback
from plxtools.view.session import ViewSession

REPO = Path(__file__).resolve().parents[2]
TUTORIAL = REPO.parent / "shared" / "seed" / "boxtruck-tutorial.txt"
STEP11 = REPO / "examples" / "tutorial" / "step11-controls"

# the AGX runtime's import lines and plx's, as documented in docs/view.md
PLX_IMPORTS = {
    "from agxPythonModules.utils.environment import init_app, application, root":
        "from plxtools.view import init_app, application, root",
    "from agxPythonModules.utils.callbacks import KeyboardCallback": "from plxtools.view import KeyboardCallback",
    "import openplx": "from plxtools.view import openplx",
    "from openplx.Physics.Signals import RealInputSignal": "from plxtools.check.api import RealInputSignal",
    "import agx": "from plxtools.view import agx",
    "import agxOSG": "from plxtools.view import agxOSG",
    "import agxSDK": "from plxtools.view import agxSDK",
}
LEFT = "boxTruck.front_left_drive_motor.target_angular_velocity_input"
RIGHT = "boxTruck.front_right_drive_motor.target_angular_velocity_input"


def _tutorial_script() -> str:
    if not TUTORIAL.is_file():
        pytest.skip(f"the BoxTruck tutorial text is not at {TUTORIAL} (the shared folder beside the checkout)")
    text = TUTORIAL.read_text(encoding="utf-8")
    start = text.find('"""\nController script')
    end = text.find('if __name__ == "__main__":', max(start, 0))
    assert start >= 0 and end > start, f"{TUTORIAL}: no step-11 controller script found"
    return text[start:end]


def _ported(script: str) -> tuple[str, list[tuple[str, str]]]:
    """The script with its import lines replaced; fails on an import plx has no equivalent for."""
    out, changed = [], []
    for line in script.splitlines():
        stripped = line.strip()
        if stripped.startswith(("import ", "from ")) and stripped != "import os":
            assert stripped in PLX_IMPORTS, f"an import the port does not know: {stripped!r}"
            out.append(PLX_IMPORTS[stripped])
            changed.append((stripped, PLX_IMPORTS[stripped]))
        else:
            out.append(line)
    return "\n".join(out) + "\n", changed


@pytest.fixture
def tutorial_controller(tmp_path) -> tuple[Path, Path, list[tuple[str, str]]]:
    source, changed = _ported(_tutorial_script())
    shutil.copy(STEP11.parent / "plx.toml", tmp_path / "plx.toml")  # the tutorial's names (boxTruck) lint clean
    step = tmp_path / "step11"
    step.mkdir()
    model = step / "boxtruck.openplx"
    shutil.copy(STEP11 / "boxtruck.openplx", model)
    script = step / "boxtruck.py"
    script.write_text(source, encoding="utf-8")
    return model, script, changed


def _targets(s: ViewSession) -> tuple[float, float]:
    """The two motors' target speeds as the view's signal panel shows them (after one step applies them)."""
    s.sim.step(0.01)
    # issue 40.6: an input shows what was sent to it (`in  ….path <- 3`), the root's name elided
    sent = dict(line[3:].strip().split(" <- ") for line in s.signals() if line.startswith("in ") and " <- " in line)
    values = {full: float(v) for shown, v in sent.items() for full in (LEFT, RIGHT) if full.endswith(shown.lstrip("…"))}
    return values[LEFT], values[RIGHT]


def test_only_the_import_lines_change(tutorial_controller):
    _model, script, changed = tutorial_controller
    original = _tutorial_script().splitlines()
    diff = [d for d in difflib.ndiff(original, script.read_text().splitlines()) if d[:2] in ("- ", "+ ")]
    assert len(changed) == len(PLX_IMPORTS)  # every runtime import is there, each replaced once
    assert sorted(d[2:] for d in diff if d.startswith("- ")) == sorted(a for a, _ in changed)
    assert sorted(d[2:] for d in diff if d.startswith("+ ")) == sorted(b for _, b in changed)


def test_the_tutorial_controller_drives_the_truck_forward_and_stops_it(tutorial_controller):
    model, script, _ = tutorial_controller
    lines: list[str] = []
    s = ViewSession(str(model), say=lines.append, controller=str(script))
    r = s.load()
    assert r.ok, (s.error, r.details)
    assert sorted(KeyboardCallback.bindings()) == [("backward", K.KEY_Down), ("forward", K.KEY_Up)]
    s.sim.step(1.0)  # land
    start = s.sim.body("boxTruck.chassis").position
    assert s.key(K.KEY_Up, True) == "bound"
    assert _targets(s) == pytest.approx((3.0, -3.0))  # the tutorial's amplitude, mirrored for the right hub
    s.sim.step(2.0)
    moved = s.sim.body("boxTruck.chassis").position
    forward = moved[0] - start[0]
    assert forward < -1.0, f"the chassis moved {forward:+.3f} m along x in 2 s of Up (forward is -x: the front hubs)"
    assert abs(moved[1] - start[1]) < 0.1  # straight: both wheels drive the same way
    s.key(K.KEY_Up, False)
    assert _targets(s) == (0.0, 0.0)
    s.sim.step(1.5)
    stopped = s.sim.body("boxTruck.chassis").position[0]
    s.sim.step(1.0)
    assert abs(s.sim.body("boxTruck.chassis").position[0] - stopped) < 0.02  # held at 0 rad/s
    s.key(K.KEY_Down, True)
    s.sim.step(2.0)
    back = s.sim.body("boxTruck.chassis").position[0] - stopped
    assert back > 1.0  # Down drives it back


def test_the_scene_decorator_set_up_runs_and_changes_nothing(tutorial_controller):
    model, script, _ = tutorial_controller
    import runpy

    ns = runpy.run_path(str(script), run_name="__plx_controller__")
    assert ns["initialize_scene_decorator"]() is None
    s = ViewSession(str(model), say=lambda _line: None, controller=str(script))
    assert s.load().ok  # buildScene() calls it again, before loading


def test_display_calls_are_accepted_and_ignored_without_the_tutorial():
    """What a runtime script does to the camera, shadows and lights: no error, no effect (docs/view.md)."""
    from plxtools.view import agx, agxOSG, application

    app = application()
    cam = app.getCameraData()
    cam.eye, cam.nearClippingPlane = agx.Vec3(1, 2, 3), 0.01
    assert app.applyCameraData(cam) is None and cam.eye == (1.0, 2.0, 3.0)
    deco = app.getSceneDecorator()
    light = deco.getLightSource(agxOSG.SceneDecorator.LIGHT2)
    assert light.setPosition(agx.Vec4(10, 19, 10, 1)) is light
    assert deco.setShadowMethod(agxOSG.SceneDecorator.SOFT_SHADOWMAP) is deco
    with pytest.raises(AttributeError):
        deco.__deepcopy__  # noqa: B018 - dunders are not faked
    with pytest.raises(AttributeError):
        agx.Quat  # noqa: B018 - only what the display set-up uses is there
