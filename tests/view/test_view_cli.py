"""`plx view` arguments and refusals that need no window."""

from __future__ import annotations

import subprocess
import sys

from tests.conftest import run_plx


def test_view_without_a_display_says_what_to_do_instead():
    r = run_plx("view", "examples/viewer/truck.openplx", env={"DISPLAY": "", "WAYLAND_DISPLAY": ""})
    assert r.returncode == 2 and "no display" in r.stderr and "--video" in r.stderr


def test_view_of_a_missing_file_is_a_usage_error(tmp_path):
    r = run_plx("view", str(tmp_path / "nope.openplx"), env={"DISPLAY": ":0"})
    assert r.returncode == 2 and "no such file" in r.stderr and "Traceback" not in r.stderr


def test_view_help_names_the_options():
    r = run_plx("view", "--help")
    for opt in ("--model", "--paused", "--controller", "--keys", "--bundle-path", "--openplx-version"):
        assert opt in r.stdout


def test_lint_and_fmt_do_not_load_the_video_encoders():
    code = ("import sys; from plxtools.cli import main; main(['lint', 'examples/boxtruck/boxtruck.openplx']); "
            "print(sorted(m for m in ('PIL', 'av', 'plxtools.view', 'glfw') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.strip().splitlines()[-1] == "[]"
