"""The view's logic without a window: loading, live reload, keys driving inputs, controller scripts."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from plxtools.view.keys import GuiEventListener as K
from plxtools.view.keys import KeyboardCallback, key_code
from plxtools.view.session import ViewSession

LEFT = "box_truck.front_left_drive_motor.target_angular_velocity_input"


def _session(path, **kw):
    lines: list[str] = []
    s = ViewSession(str(path), say=lines.append, **kw)
    return s, lines


def _touch_edit(path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    st = os.stat(path)  # a second save within the file system's time resolution still shows
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))


def _x(s) -> float:
    return s.sim.body("box_truck.chassis").position[0]


def test_load_shows_the_model_and_steps_in_real_time(truck):
    s, lines = _session(truck)
    r = s.load()
    assert r.ok and s.sim is not None and s.error is None
    assert lines[0].startswith("loaded Scene from")
    assert s.advance(0.1) == 50  # 0.1 s of wall clock at 2 ms steps
    assert s.sim.time == pytest.approx(0.1)
    s.key(K.KEY_E)
    assert s.paused and s.advance(0.1) == 0
    assert "paused" in s.status()[0]


def test_a_saved_edit_reloads_the_new_model(truck):
    s, lines = _session(truck)
    s.load()
    assert s.poll() is None  # nothing changed
    z0 = s.sim.body("box_truck.chassis").position[2]
    _touch_edit(truck, "position.z: 1.1", "position.z: 2.5")
    r = s.poll()
    assert r is not None and r.ok and s.generation == 2
    assert s.sim.body("box_truck.chassis").position[2] == pytest.approx(z0 + 1.4)
    assert any(line.startswith("changed:") for line in lines)


def test_an_edit_of_a_mesh_the_model_reads_reloads_it(truck):
    s, _ = _session(truck)
    s.load()
    mesh = truck.parent / "wheel.obj"
    assert str(mesh) in s.stamps
    mesh.write_text(mesh.read_text() + "\n")
    assert s.poll() is not None and s.generation == 2


def test_a_model_that_stops_compiling_keeps_the_last_good_scene_and_says_why(truck):
    s, lines = _session(truck)
    s.load()
    good = s.sim
    _touch_edit(truck, "radius: 0.26", "radius: ")
    r = s.poll()
    assert r is not None and not r.ok
    assert s.sim is good and s.generation == 1
    assert s.error and "truck.openplx" in s.error
    status = s.status()
    assert status[0].startswith("LOAD FAILED at truck.openplx:"), status
    assert any("showing the last good scene" in ln for ln in status), status
    assert any("still showing the last good scene" in line for line in lines)
    assert any(":" in d and "truck.openplx:" in d for d in r.details)  # located findings
    _touch_edit(truck, "radius: \n", "radius: 0.3\n")
    assert s.poll().ok and s.error is None and s.generation == 2


def test_a_model_that_never_loads_gives_a_located_message(tmp_path):
    bad = tmp_path / "bad.openplx"
    bad.write_text("Scene is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody:\n        inertia.mass: oops\n")
    s, lines = _session(bad)
    r = s.load()
    assert not r.ok and s.sim is None
    assert "bad.openplx" in s.error
    # issue 40.6: where once (file:line:col, no second path), then why, wrapped to fit the window
    status = s.status()
    assert status[0] == "LOAD FAILED at bad.openplx:3:9:", status  # the first finding's place
    assert all(len(ln) <= 70 for ln in status) and "".join(status).count("bad.openplx") == 1, status
    assert " ".join(ln.strip() for ln in status[1:]) == s.error.replace(f"{bad}:3:9: ", "").replace(f"{bad}: ", "")
    assert lines and lines[0].startswith("cannot load:")


def test_the_reload_key_reloads_by_hand(truck):
    s, _ = _session(truck)
    s.load()
    assert s.key(K.KEY_1) == "reload" and s.generation == 2


def test_g_switches_between_visuals_and_collision_geometry(truck):
    s, _ = _session(truck)
    s.load()
    assert s.key(K.KEY_G) == "collision" and s.show_collision
    assert s.key(K.KEY_G) == "visuals" and not s.show_collision


def test_a_key_table_drives_inputs_while_held(truck):
    s, _ = _session(truck, keymap=str(truck.parent / "truck.keys.toml"))
    s.load()
    s.sim.step(1.0)  # land
    x0 = _x(s)
    assert s.key(K.KEY_Up, True) == "bound"
    s.sim.step(2.0)
    x1 = _x(s)
    assert x1 < x0 - 0.5  # forward is -x (the front wheels sit at -x)
    s.key(K.KEY_Up, False)
    s.sim.step(1.5)
    x2 = _x(s)
    s.sim.step(1.0)
    assert abs(_x(s) - x2) < 0.02  # released: the motors hold the wheels at 0 rad/s
    assert s.key(K.KEY_Down, True) == "bound"
    s.sim.step(2.0)
    assert _x(s) > x2 + 0.5


def test_a_key_table_with_a_wrong_path_is_a_message_not_a_dead_key(truck):
    km = truck.parent / "bad.keys.toml"
    km.write_text('[keys.Up]\n"box_truck.front_left_drive_motor.target_angular_velocity_inptu" = 1\n')
    s, _ = _session(truck, keymap=str(km))
    r = s.load()
    assert not r.ok and "bad.keys.toml" in s.error and "did you mean" in s.error
    km.write_text('[keys.Hyper]\n"x" = 1\n')
    assert not s.load().ok and "unknown key 'Hyper'" in s.error
    km.write_text(f'[keys.Up]\n"{LEFT}" = [1, 2]\n')
    assert not s.load().ok and "takes a number" in s.error


def test_the_controller_script_drives_the_truck_with_the_arrow_keys(truck):
    s, _ = _session(truck, controller=str(truck.parent / "truck_controller.py"))
    assert s.load().ok
    assert sorted(KeyboardCallback.bindings()) == [("backward", K.KEY_Down), ("forward", K.KEY_Up)]
    s.sim.step(1.0)
    x0 = _x(s)
    s.key(K.KEY_Up, True)
    s.sim.step(2.0)
    x1 = _x(s)
    assert x1 < x0 - 0.5
    s.key(K.KEY_Up, False)
    s.sim.step(1.5)
    x2 = _x(s)
    s.sim.step(1.0)
    assert abs(_x(s) - x2) < 0.02
    # a reload runs buildScene() again against the new simulation: the keys drive the new one
    s.key(K.KEY_1)
    assert s.generation == 2 and len(KeyboardCallback.bindings()) == 2
    s.sim.step(1.0)
    x0 = _x(s)
    s.key(K.KEY_Up, True)
    s.sim.step(1.0)
    assert _x(s) < x0 - 0.2


def test_a_failing_controller_shows_its_own_traceback(truck):
    script = truck.parent / "broken_controller.py"
    script.write_text("def buildScene():\n    raise ValueError('no such motor')\n")
    s, lines = _session(truck, controller=str(script))
    r = s.load()
    assert not r.ok and "broken_controller.py" in s.error
    text = "\n".join(r.details)
    assert "ValueError: no such motor" in text and "plxtools/view" not in text


def test_key_names_and_bind_errors():
    assert key_code("Up") == K.KEY_Up == 265 and key_code("w") == ord("W") and key_code("F5") == 294
    assert key_code("page_up") == K.KEY_Page_Up
    with pytest.raises(ValueError, match="unknown key"):
        key_code("Hyper")
    with pytest.raises(TypeError, match="callable"):
        KeyboardCallback.bind(name="x", key=K.KEY_Up, callback=None)


def test_a_held_key_sends_one_press_and_one_release(truck):
    s, _ = _session(truck)
    s.load()
    seen = []
    KeyboardCallback.bind(name="t", key=K.KEY_Up, callback=lambda k: seen.append(k.down))
    for _ in range(3):  # the window's key repeats while held
        s.key(K.KEY_Up, True)
    s.key(K.KEY_Up, False)
    assert seen == [True, False]


def test_watched_files_include_user_bundles_and_config():
    from pathlib import Path

    ex = Path(__file__).resolve().parents[2] / "examples" / "user_bundle" / "cart_scene.openplx"
    s, _ = _session(ex)
    assert s.load().ok
    watched = set(s.stamps)
    assert str(ex.parent / "plx.toml") in watched
    assert any(p.endswith(os.path.join("Machines", "Carts", "MotorCart.openplx")) for p in watched)
    t = time.perf_counter()
    assert s.changed() == []
    assert time.perf_counter() - t < 0.5


EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("model", [
    *sorted(str(p.relative_to(EXAMPLES / "tutorial")) for p in (EXAMPLES / "tutorial").glob("*/*.openplx")),
    "../boxtruck/boxtruck.openplx", "../user_bundle/cart_scene.openplx", "../viewer/truck.openplx",
])
def test_every_example_and_tutorial_step_loads_and_runs(model):
    s, lines = _session(EXAMPLES / "tutorial" / model)
    r = s.load()
    assert r.ok, lines
    if s.paused:  # it would leave the view at once (the tutorial's step 3 falls): waits for E, says why
        assert s.waiting and any("waiting: " in line for line in s.status()), s.status()
        assert s.advance(0.05) == 0 and s.key(K.KEY_E) == "play" and s.waiting is None
    assert s.advance(0.05) == 25 and s.status()
    assert all(line.startswith("out ") and " = " in line or line.startswith("in ") and " <- " in line
               for line in s.signals())


def test_a_saved_edit_of_an_imported_bundle_file_shows(tmp_path):
    """The process keeps its workspace between loads: a changed user bundle file must not be
    answered from the old one (plx view and plx view --web reload what the model imports)."""
    import shutil

    shutil.copytree(Path(__file__).resolve().parents[2] / "examples" / "user_bundle", tmp_path / "ub")
    s, _ = _session(tmp_path / "ub" / "cart_scene.openplx")
    assert s.load().ok

    def radii():
        return {round(g.radius, 3) for b in s.sim.prepared.compiled.scene.bodies for g in b.geoms if g.radius}

    assert radii() == {0.15}
    _touch_edit(tmp_path / "ub" / "Parts" / "Wheels" / "SolidWheel.openplx", "radius is Real: 0.15", "radius is Real: 0.5")
    r = s.poll()
    assert r is not None and r.ok and radii() == {0.5}



def test_choosing_another_root_gives_the_findings_of_a_plain_check(tmp_path):
    """Issue 40.7: `plx view --model Wheel` on a file whose scene is `Scene` reported C003 "Scene never
    used" and C002 (the `ignore[C003]` on Wheel unused), and a --fix would have removed that comment.
    A file with a model that nothing uses yet, suppressed as the tutorial does, and one that is not."""
    f = tmp_path / "parts.openplx"
    f.write_text("Wheel is Physics3D.Bodies.RigidBody:  # plx: ignore[C003]\n"
                 "    geometry is Physics3D.Geometries.Cylinder:\n        radius: 0.3\n        height: 0.2\n"
                 "    inertia.mass: 10\n\n"
                 "Axle is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2\n\n"
                 "Scene is Physics3D.System:\n    ground is Physics3D.Bodies.RigidBody:\n"
                 "        is_dynamic: false\n        inertia.mass: 1\n")
    findings = {}
    for model in (None, "Wheel", "Axle"):
        s, _ = _session(f, model=model)
        r = s.load()
        assert r.ok, r.details
        findings[model] = [d.split(": ", 1)[1] for d in r.details]
    assert findings["Wheel"] == findings[None] == findings["Axle"], findings
    assert any("C003" in d and "'Axle'" in d for d in findings[None])  # Axle is unused, whoever is root
    assert not any("C002" in d or "'Scene'" in d for d in findings["Wheel"])


def test_a_scene_that_falls_out_of_view_at_once_starts_paused_and_says_why(truck):
    """Issue 40.6: the tutorial's step 3 (a chassis, no ground) had fallen out of view before the first
    frame, a black window; like the AGX viewer, the view now waits for E. A truck that lands does not wait."""
    s, lines = _session(EXAMPLES / "tutorial" / "step03-chassis" / "boxtruck.openplx")
    assert s.load().ok and s.paused
    assert any(line.startswith("paused: it leaves the view within") and "(E plays)" in line for line in lines), lines
    z = s.sim.body("chassis").position[2]
    assert s.advance(0.5) == 0 and s.sim.body("chassis").position[2] == z  # nothing moved while waiting
    assert "waiting: it leaves the view" in "\n".join(s.status())
    assert s.key(K.KEY_E) == "play" and s.advance(0.1) > 0 and s.sim.body("chassis").position[2] < z
    assert "waiting" not in "\n".join(s.status())
    landing, _ = _session(truck)
    assert landing.load().ok and not landing.paused and landing.waiting is None
    explicit, _ = _session(EXAMPLES / "tutorial" / "step03-chassis" / "boxtruck.openplx", paused=True)
    assert explicit.load().ok and explicit.paused and explicit.waiting is None  # --paused: no reason needed


def test_signal_lines_fit_the_width_given_in_ascii(truck):
    """The panel's lines fit the room the window gives them (so they stay clear of MuJoCo's F1 help)
    and use no character MuJoCo's overlay font lacks (a "…" was drawn as a box)."""
    s, _ = _session(truck)
    assert s.load().ok
    s.sim.send(__import__("plxtools.check.api", fromlist=["RealInputSignal"]).RealInputSignal.create(
        2.5, s.sim.scene().getObject(LEFT)))
    for width in (40, 60, 100):
        lines = s.signals(width)
        assert lines and all(len(line) <= width and line.isascii() for line in lines), (width, lines)
    assert f"in  {LEFT} <- 2.5" in s.signals(100)  # what was sent, not the joint's velocity
    # narrower: the root goes, then the `_input` the line's `in` already says; left and right stay apart
    assert "in  front_left_drive_motor.target_angular_velocity <- 2.5" in s.signals(60)
