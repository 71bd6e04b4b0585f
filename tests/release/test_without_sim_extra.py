"""A plain `pip install plxtools` (no `sim` extra): lint, fmt and the language server work; the
commands that simulate name the extra to install and exit 2 (never "internal error ... a bug").

numpy and mujoco are made unimportable in a child interpreter (None in sys.modules), which is what
an environment without them looks like to plx; .ci/smoke-wheel does the same with a real venv."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

BLOCK = "import sys; sys.modules['numpy'] = None; sys.modules['mujoco'] = None\n"
RUN_PLX = BLOCK + "from plxtools.cli import main; sys.exit(main(sys.argv[1:]))\n"

SCENE = """Crate is Physics3D.Bodies.RigidBody:
    inertia.mass: 20

Scene is Physics3D.System:
    crate is Crate
"""


def _plx(*args: str, cwd, stdin: str | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "PLX_NO_PROGRESS": "1"}
    return subprocess.run([sys.executable, "-c", RUN_PLX, *args], cwd=cwd, capture_output=True, text=True,
                          input=stdin, env=env, timeout=120)


@pytest.fixture
def project(tmp_path):
    (tmp_path / "scene.openplx").write_text(SCENE, encoding="utf-8")
    (tmp_path / "drop.scenario.toml").write_text('model = "scene.openplx"\nduration = 1.0\n', encoding="utf-8")
    return tmp_path


@pytest.mark.parametrize("args, missing", [
    (("check", "scene.openplx"), "numpy"),
    (("check", "--simulate", "scene.openplx"), "numpy and mujoco"),
    (("check", "--export-mjcf", "out.xml", "scene.openplx"), "numpy and mujoco"),
    (("test", "."), "numpy and mujoco"),
    (("view", "scene.openplx"), "numpy and mujoco"),
])
def test_a_command_that_needs_the_sim_extra_says_which_and_exits_2(project, args, missing):
    r = _plx(*args, cwd=project)
    assert r.returncode == 2, (r.stdout, r.stderr)
    assert f"plx {args[0]}: needs {missing}, which" in r.stderr, r.stderr
    assert "pip install 'plxtools[sim]'" in r.stderr, r.stderr
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr
    assert r.stdout == ""
    assert not (project / "out.xml").exists()


def test_lint_and_fmt_work_without_numpy_and_mujoco(project):
    r = _plx("lint", "scene.openplx", cwd=project)
    assert r.returncode == 0 and "All checks passed" in r.stdout, (r.stdout, r.stderr)
    r = _plx("fmt", "-", cwd=project, stdin="Crate is Physics3D.Bodies.RigidBody:\n  inertia.mass:   20\n")
    assert r.returncode == 0 and r.stdout == "Crate is Physics3D.Bodies.RigidBody:\n    inertia.mass: 20\n", r


def test_show_settings_of_check_needs_no_simulation(project):
    r = _plx("check", "--show-settings", "scene.openplx", cwd=project)
    assert r.returncode == 0 and "official bundles" in r.stdout, (r.stdout, r.stderr)


def _message(body: dict) -> bytes:
    data = json.dumps(body).encode()
    return b"Content-Length: %d\r\n\r\n" % len(data) + data


def _responses(raw: bytes) -> dict:
    out = {}
    while raw:
        head, _, rest = raw.partition(b"\r\n\r\n")
        length = int(next(h for h in head.split(b"\r\n") if h.lower().startswith(b"content-length")).split(b":")[1])
        msg = json.loads(rest[:length])
        raw = rest[length:]
        if "id" in msg and "method" not in msg:
            out[msg["id"]] = msg
    return out


def test_the_language_server_starts_and_formats_without_numpy_and_mujoco(project):
    uri = (project / "scene.openplx").as_uri()
    text = "Crate is Physics3D.Bodies.RigidBody:\n  inertia.mass:   20\n"
    stdin = b"".join(_message(m) for m in [
        {"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": {"processId": None, "rootUri": project.as_uri(),
                                                                        "capabilities": {}}},
        {"jsonrpc": "2.0", "method": "initialized", "params": {}},
        {"jsonrpc": "2.0", "method": "textDocument/didOpen",
         "params": {"textDocument": {"uri": uri, "languageId": "openplx", "version": 1, "text": text}}},
        {"jsonrpc": "2.0", "id": 2, "method": "textDocument/formatting",
         "params": {"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": True}}},
        {"jsonrpc": "2.0", "id": 3, "method": "shutdown"},
        {"jsonrpc": "2.0", "method": "exit"},
    ])
    code = RUN_PLX.replace("main(sys.argv[1:])", "main(['lsp'])")
    r = subprocess.run([sys.executable, "-c", code], cwd=project, input=stdin, capture_output=True, timeout=120)
    assert r.returncode == 0, r.stderr.decode()
    replies = _responses(r.stdout)
    assert replies[1]["result"]["capabilities"]["documentFormattingProvider"]
    edits = replies[2]["result"]
    assert edits and any("    inertia.mass: 20" in e["newText"] for e in edits), edits
    assert replies[3]["result"] is None


def test_the_pytest_plugin_names_the_extra_for_scenario_files(project):
    code = BLOCK + "import pytest; sys.exit(pytest.main(['-q', '-p', 'no:cacheprovider', 'drop.scenario.toml']))\n"
    r = subprocess.run([sys.executable, "-c", code], cwd=project, capture_output=True, text=True, timeout=120,
                       env={**os.environ, "PYTEST_ADDOPTS": ""})
    assert r.returncode == 1, r.stdout + r.stderr
    assert "scenario files need numpy and mujoco, not installed: pip install 'plxtools[sim]'" in r.stdout, r.stdout
    assert "Traceback" not in r.stdout and "During handling" not in r.stdout
