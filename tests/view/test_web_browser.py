"""`plx view --web` in a real headless Chromium, looked at through screenshots.

Slow (a browser and a server per module): run with ``PLX_BROWSER_TESTS=1`` (``.ci/run`` does),
after ``npm ci`` in tests/view/browser/ and ``apt-get install chromium``.  Without the flag the
module is skipped; with it a missing browser fails rather than skips.

The screenshots are kept in ``PLX_BROWSER_SHOTS`` (a folder) when it is set.
"""

from __future__ import annotations

import csv
import os
import shutil
import time
from pathlib import Path

import pytest

from tests.conftest import plx_here
from tests.view.web_support import Browser, PlxWeb, browser_missing, png_pixels

pytestmark = pytest.mark.skipif(not os.environ.get("PLX_BROWSER_TESTS"),
                                reason="browser tests: set PLX_BROWSER_TESTS=1 (see .ci/run)")

BOXTRUCK = Path(__file__).resolve().parents[2] / "examples" / "boxtruck" / "boxtruck.openplx"
DRAW_BOUND_S = 5.0  # the issue: the truck is drawn within 5 s of the command
UPDATE_BOUND_S = 2.0  # an edit shows within 1 s of the save, 2 s on a busy machine


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    st = os.stat(path)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))


def _chassis_pixels(shot: Path) -> int:
    """Pixels of the chassis' colour (the palette's red) in a screenshot."""
    w, h, rows = png_pixels(shot)
    return sum(1 for row in rows for (r, g, b) in row if r > 90 and r > g + 50 and r > b + 50)


def _coloured_pixels(shot: Path, top: float, bottom: float) -> int:
    """Pixels of any strong colour (the truck's parts, tinted or not; not the grey ground, the grid or
    the sky) between two heights of the screenshot."""
    w, h, rows = png_pixels(shot)
    return sum(1 for row in rows[int(top):int(bottom)] for px in row if max(px) - min(px) > 60)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    why = browser_missing()
    if why:
        pytest.fail(f"PLX_BROWSER_TESTS=1 but {why}")
    folder = tmp_path_factory.mktemp("webpage")
    shots = Path(os.environ.get("PLX_BROWSER_SHOTS") or folder)
    shots.mkdir(parents=True, exist_ok=True)
    model = folder / "boxtruck.openplx"
    shutil.copy(BOXTRUCK, model)
    revealed = folder / "revealed.txt"
    browser = Browser()  # started first: the 5 s are the command's, not the browser's start
    web = PlxWeb(model, "--paused", "--editor-command", f"sh -c 'echo {{file}}:{{line}} >> {revealed}'")
    try:
        browser.goto(web.url)
        browser.wait_for("window.plxPreview && plxPreview.state.drawnGeneration >= 1", timeout=30)
        drawn_after = time.perf_counter() - web.started
        yield {"web": web, "browser": browser, "model": model, "shots": shots, "drawn_after": drawn_after,
               "revealed": revealed}
    finally:
        browser.close()
        web.stop()


def test_the_truck_is_drawn_within_5_s_of_the_command(page):
    b = page["browser"]
    assert page["drawn_after"] < DRAW_BOUND_S * 2, page["drawn_after"]  # 5 s, doubled for a loaded machine
    print(f"drawn {page['drawn_after']:.2f} s after the command")
    shot = b.screenshot(page["shots"] / "drawn.png")
    x, y = b.eval("plxPreview.screenOf('box_truck.chassis')")
    w, h, rows = png_pixels(shot)
    assert 0 < x < w and 0 < y < h
    # the chassis' red around its centre, the ground elsewhere: the truck is drawn where it is
    near = [rows[int(y) + dy][int(x) + dx] for dy in range(-10, 11, 5) for dx in range(-10, 11, 5)]
    assert all(r > g + 50 for (r, g, _b) in near), near
    assert _chassis_pixels(shot) > 5000
    assert b.eval("plxPreview.state.error") is None


def test_an_edit_that_makes_the_chassis_longer_changes_the_drawing(page):
    b, model = page["browser"], page["model"]
    before = _chassis_pixels(b.screenshot(page["shots"] / "before-edit.png"))
    gen = b.eval("plxPreview.state.drawnGeneration")
    t0 = time.perf_counter()
    _edit(model, "x: 3.3", "x: 5.0")
    b.wait_for(f"plxPreview.state.drawnGeneration > {gen}", timeout=10)
    took = time.perf_counter() - t0
    after = _chassis_pixels(b.screenshot(page["shots"] / "longer.png"))
    print(f"edit to drawing: {took:.2f} s; chassis pixels {before} -> {after}")
    assert took < UPDATE_BOUND_S, took
    assert after > before * 1.2


def test_a_broken_edit_keeps_the_drawing_and_shows_the_finding(page):
    b, model = page["browser"], page["model"]
    top, bottom = 140, 520  # below the banner, above the findings
    before = _coloured_pixels(b.screenshot(page["shots"] / "good.png"), top, bottom)
    loads = page["web"].get("api/state")["loads"]
    _edit(model, "inertia.mass: 1000", "inertia.mass: heavy")
    try:
        page["web"].wait_loaded(loads + 1)
        b.wait_for("!document.getElementById('banner').hidden", timeout=10)
        shot = b.screenshot(page["shots"] / "broken.png")
        banner = b.eval("document.getElementById('banner').textContent")
        assert banner.startswith("LOAD FAILED") and "last good scene" in banner
        assert b.eval("document.getElementById('banner').getBoundingClientRect().bottom") < top
        line = model.read_text().splitlines().index("    inertia.mass: heavy") + 1
        items = b.eval("[...document.querySelectorAll('#findings-list li.error')].map(li => li.textContent)")
        assert any(f"boxtruck.openplx:{line}:" in t for t in items), items
        assert abs(_coloured_pixels(shot, top, bottom) - before) < before * 0.03  # the last good truck, drawn
        # the finding is in the Chassis model: it shows on the chassis (tinted)
        assert "box_truck.chassis" in b.eval("plxPreview.elementsAt(%r, %d)" % (str(model), line))
        chassis = b.eval("plxPreview.state.scene.bodies.findIndex(x => x.path === 'box_truck.chassis')")
        assert f"body:{chassis}" in b.eval("[...plxPreview.state.findingElements]")
    finally:
        _edit(model, "inertia.mass: heavy", "inertia.mass: 1000")
    b.wait_for("document.getElementById('banner').hidden", timeout=10)


def test_a_click_on_a_body_reveals_its_line(page):
    b, model = page["browser"], page["model"]
    x, y = b.eval("plxPreview.screenOf('box_truck.chassis')")
    b.call("click", x=x, y=y)
    b.wait_for("plxPreview.selectedPath() === 'box_truck.chassis'", timeout=5)
    link = b.wait_for("document.getElementById('selection-link') && document.getElementById('selection-link').textContent")
    line = model.read_text().splitlines().index("    chassis is Chassis:") + 1
    assert link == f"{model}:{line}:5"
    b.screenshot(page["shots"] / "selected.png")
    end = time.monotonic() + 5  # --editor-command ran with the file and line
    while time.monotonic() < end and not page["revealed"].exists():
        time.sleep(0.05)
    assert page["revealed"].read_text().splitlines()[-1] == f"{model}:{line}"
    b.call("press", key="Escape")  # clears the selection
    b.wait_for("plxPreview.selectedPath() === null", timeout=5)


def test_the_cursor_in_the_wheel_model_lights_the_four_wheels(page):
    b, model, web = page["browser"], page["model"], page["web"]
    line = model.read_text().splitlines().index("        radius: 0.26") + 1
    web.post("api/cursor", {"file": str(model), "line": line})
    lit = b.wait_for("plxPreview.state.cursor.size === 4 && [...plxPreview.state.cursor]", timeout=5)
    paths = sorted(b.eval(f"plxPreview.elementsAt({str(model)!r}, {line})"))
    assert lit and paths == sorted(f"box_truck.{w}_wheel.geometry" for w in
                                   ("front_left", "front_right", "rear_left", "rear_right"))
    b.eval("plxPreview.setView(-Math.PI / 2, 0.05)")  # from the left side: the wheels below the chassis
    b.wait_for("!plxPreview.state.dirty")
    shot = b.screenshot(page["shots"] / "cursor.png")
    w, h, rows = png_pixels(shot)
    yellow = sum(1 for row in rows for (r, g, bl) in row if r > 120 and g > 100 and bl < 0.6 * g)
    assert yellow > 200, yellow
    web.post("api/cursor", {"file": str(model), "line": 1})
    b.wait_for("plxPreview.state.cursor.size === 0", timeout=5)
    b.eval("plxPreview.setView(-2.3, 0.42)")


def test_the_pages_poses_after_2_s_equal_the_trace(page, tmp_path):
    b, model, web = page["browser"], page["model"], page["web"]
    out = tmp_path / "trace.csv"
    r = plx_here("check", "--simulate", "--duration", "2", "--trace", str(out), str(model))
    assert r.returncode == 0, r.stdout + r.stderr
    last = list(csv.DictReader(out.open()))[-1]
    web.post("api/control", {"action": "seek", "time": 2.0})
    b.wait_for("Math.abs(plxPreview.state.time - 2.0) < 1e-9 && plxPreview.state.drawnPosesTime === plxPreview.state.time")
    poses = b.eval("plxPreview.state.poses")
    bodies = b.eval("plxPreview.state.scene.bodies.map(b => b.path)")
    for i, path in enumerate(bodies):
        want = [float(last[f"{path}.{c}"]) for c in "xyz"]
        assert poses[7 * i:7 * i + 3] == pytest.approx(want, abs=1e-3), path  # 1 mm
        quat = [float(last[f"{path}.{c}"]) for c in ("qw", "qx", "qy", "qz")]
        sign = 1 if sum(a * b for a, b in zip(quat, poses[7 * i + 3:7 * i + 7])) >= 0 else -1
        assert [sign * v for v in poses[7 * i + 3:7 * i + 7]] == pytest.approx(quat, abs=1e-4), path
    b.screenshot(page["shots"] / "t2.png")
