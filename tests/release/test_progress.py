"""Progress on a terminal: a bar on stderr while `plx check --simulate` or `plx test` works through
several files, each file's report printed as soon as it is done, and nothing of the kind when
stderr is not a terminal or the output is JSON. Run through the CLI with a pseudo-terminal."""

from __future__ import annotations

import os
import pty
import re
import select
import subprocess
import sys
from pathlib import Path

import pytest

SCENE = """Crate is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size:
            x: 0.5
            y: 0.5
            z: 0.5
    inertia.mass: {mass}

Floor is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size:
            x: 10
            y: 10
            z: 0.2
    is_dynamic: false

Scene is Physics3D.System:
    crate is Crate:
        kinematics.local_transform.position.z: 1.0
    floor is Floor
"""
BAR = re.compile(r"\x1b\[|━|\d+/\d+")  # escape sequences, bar segments, "1/2"


def _run(args, cwd: Path, *, terminal: str, delay: str = "0", python: tuple = ("-m", "plxtools"),
         env: dict | None = None) -> tuple[int, str, str]:
    """(exit code, stdout, what the terminal got); terminal: "none", "stderr" or "both"."""
    cmd = [sys.executable, *python, *args]
    env = {**os.environ, **(env or {}), "PLX_PROGRESS_DELAY": delay, "COLUMNS": "100", "TERM": "xterm"}
    for k in ("PLX_NO_PROGRESS", "NO_COLOR", "FORCE_COLOR"):
        env.pop(k, None)
    if terminal == "none":
        r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=300)
        return r.returncode, r.stdout, r.stderr
    master, slave = pty.openpty()
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stderr=slave,
                         stdout=slave if terminal == "both" else subprocess.PIPE)
    os.close(slave)
    seen = b""
    while True:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:
                chunk = b""
            if not chunk:
                break
            seen += chunk
        elif p.poll() is not None:
            break
    out = "" if terminal == "both" else p.stdout.read().decode()
    p.wait(timeout=300)
    os.close(master)
    return p.returncode, out, seen.decode("utf-8", "replace")


@pytest.fixture(scope="module")
def project(tmp_path_factory):
    d = tmp_path_factory.mktemp("progress")
    for i, mass in enumerate((20, 35)):
        (d / f"scene{i}.openplx").write_text(SCENE.format(mass=mass), encoding="utf-8")
    for i in range(2):
        (d / f"drop{i}.scenario.toml").write_text(
            f'model = "scene{i}.openplx"\nroot = "Scene"\nduration = 1.0\n\n'
            '[[expect]]\nat = 1.0\nof = "crate.z"\nbetween = [0.2, 0.5]\n', encoding="utf-8")
    return d


def _stable(text: str) -> str:
    return re.sub(r"\d+\.\d+ s wall|in \d+\.\d+s", "<time>", text)


def test_check_draws_a_bar_on_a_terminal_and_leaves_stdout_as_it_is(project):
    args = ["check", "--simulate", "--duration", "0.5", "-j", "1", "scene0.openplx", "scene1.openplx"]
    code, plain_out, plain_err = _run(args, project, terminal="none")
    assert code == 0, plain_err
    assert not BAR.search(plain_err), repr(plain_err)  # not a terminal: no bar, no escapes
    code, out, term = _run(args, project, terminal="stderr")
    assert code == 0
    assert "check --simulate" in term and re.search(r"[12]/2", term), repr(term[-2000:])
    assert _stable(out) == _stable(plain_out)  # the report on stdout (a pipe) is untouched


def test_on_one_terminal_each_file_is_reported_then_one_summary(project):
    args = ["check", "--simulate", "--duration", "0.5", "-j", "1", "scene0.openplx", "scene1.openplx"]
    code, _, term = _run(args, project, terminal="both")
    assert code == 0
    text = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", term)
    first, second = text.find("scene0.openplx: Scene"), text.find("scene1.openplx: Scene")
    assert 0 <= first < second, text
    assert text.count("All checks passed in 2 files.") == 1 and text.rfind("All checks passed") > second


def test_json_output_and_a_short_run_draw_nothing(project):
    code, out, term = _run(["check", "--output-format", "json", "scene0.openplx", "scene1.openplx"], project,
                           terminal="stderr")
    assert code == 0 and out.lstrip().startswith("{")
    assert not BAR.search(term), repr(term)
    code, out, term = _run(["test", "drop0.scenario.toml", "drop1.scenario.toml"], project, terminal="stderr",
                           delay="60")
    assert code == 0 and "2 passed" in out
    assert not BAR.search(term), repr(term)  # done before the delay: no bar at all


def test_plx_test_draws_a_bar_on_a_terminal(project):
    code, out, term = _run(["test", "."], project, terminal="stderr")
    assert code == 0 and "2 passed" in out, out
    assert "plx test" in term and re.search(r"[12]/2", term), repr(term[-2000:])


def test_bundles_install_draws_a_download_bar_on_a_terminal(tmp_path):
    from tests.bundles.test_fetch_without_pip import NO_PIP, VERSION, _index

    index = _index(tmp_path)
    env = {"PIP_CONFIG_FILE": os.devnull, "PIP_INDEX_URL": index.as_uri() + "/", "PLX_CACHE_DIR": str(tmp_path / "c")}
    code, out, term = _run(["bundles", "install", VERSION], tmp_path, terminal="stderr", python=("-c", NO_PIP), env=env)
    assert code == 0 and out.startswith(f"openplx-bundles {VERSION}: "), (out, term)
    assert f"downloading openplx-bundles {VERSION}" in term, repr(term)
    code, out, term = _run(["bundles", "install", "--force", VERSION], tmp_path, terminal="none",
                           python=("-c", NO_PIP), env=env)
    assert code == 0 and term == "", repr(term)
