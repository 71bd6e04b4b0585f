"""Our pre-commit hooks, run by the real `pre-commit` tool against a temporary git repository.

The hooks are `language: python`, so pre-commit would build a virtualenv and pip-install
plxtools with all its dependencies (about 18 s here, see docs/pre-commit.md). To keep the suite
fast, the default tests copy `.pre-commit-hooks.yaml` into a throw-away hook repository with
`language: system`, which runs the `plx` of this environment; everything else (ids, entries, file
patterns, serial runs) is ours as committed. `PLX_SLOW_TESTS=1` also runs the real
`language: python` install through `pre-commit try-repo`.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.fmt.helpers import REPO

PRE_COMMIT = shutil.which("pre-commit", path=str(Path(sys.executable).parent)) or shutil.which("pre-commit")
pytestmark = pytest.mark.skipif(PRE_COMMIT is None, reason="pre-commit is not installed")

UGLY = "Scene is Physics3D.System:\n  ground is Physics3D.Bodies.RigidBody:\n      is_dynamic:   false\n"
PRETTY = "Scene is Physics3D.System:\n    ground is Physics3D.Bodies.RigidBody:\n        is_dynamic: false\n"
LOCAL_CONFIG = """repos:
  - repo: local
    hooks:
      - id: plx-fmt
        name: plx fmt
        entry: plx fmt
        language: system
        files: '\\.openplx$'
        require_serial: true
      - id: plx-lint
        name: plx lint
        entry: plx lint
        language: system
        files: '\\.openplx$'
        require_serial: true
"""


def _env(tmp_path: Path) -> dict:
    env = dict(os.environ)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    env["PRE_COMMIT_HOME"] = str(tmp_path / "pre-commit-home")
    env.update(
        GIT_AUTHOR_NAME="t",
        GIT_AUTHOR_EMAIL="t@example.invalid",
        GIT_COMMITTER_NAME="t",
        GIT_COMMITTER_EMAIL="t@example.invalid",
    )
    env.pop("PLX_DEBUG", None)
    return env


def _git(cwd: Path, env: dict, *args: str) -> None:
    subprocess.run(["git", *args], cwd=cwd, env=env, check=True, capture_output=True)


def _project(tmp_path: Path, env: dict) -> Path:
    proj = tmp_path / "project"
    proj.mkdir()
    _git(proj, env, "init", "-q")
    (proj / "ugly.openplx").write_text(UGLY)
    (proj / "pretty.openplx").write_text(PRETTY)
    (proj / "notes.txt").write_text("  not   openplx  \n")
    _git(proj, env, "add", "-A")
    return proj


def _run(cwd: Path, env: dict, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([PRE_COMMIT, *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=600)


def _hook_repo(tmp_path: Path, env: dict, language: str = "system") -> Path:
    repo = tmp_path / "hooks"
    repo.mkdir()
    text = (REPO / ".pre-commit-hooks.yaml").read_text()
    assert text.count("language: python") == 2
    (repo / ".pre-commit-hooks.yaml").write_text(text.replace("language: python", f"language: {language}"))
    _git(repo, env, "init", "-q")
    _git(repo, env, "add", "-A")
    _git(repo, env, "commit", "-q", "-m", "hooks")
    return repo


def test_our_hooks_file_declares_both_hooks():
    text = (REPO / ".pre-commit-hooks.yaml").read_text()
    for needle in (
        "id: plx-fmt",
        "entry: plx fmt",
        "id: plx-lint",
        "entry: plx lint",
        "files: '\\.openplx$'",
        "require_serial: true",
    ):
        assert needle in text


def test_try_repo_plx_fmt_fails_and_reformats_then_passes(tmp_path):
    env = _env(tmp_path)
    hooks = _hook_repo(tmp_path, env)
    proj = _project(tmp_path, env)
    ok = _run(proj, env, "try-repo", str(hooks), "plx-fmt", "--files", "pretty.openplx")
    assert ok.returncode == 0, ok.stdout + ok.stderr
    bad = _run(proj, env, "try-repo", str(hooks), "plx-fmt", "--files", "ugly.openplx", "notes.txt")
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "files were modified by this hook" in bad.stdout
    assert (proj / "ugly.openplx").read_text() == PRETTY
    assert (proj / "notes.txt").read_text() == "  not   openplx  \n"  # not an .openplx file
    again = _run(proj, env, "try-repo", str(hooks), "plx-fmt", "--files", "ugly.openplx")
    assert again.returncode == 0, again.stdout


def test_local_repo_config_from_the_docs(tmp_path):
    env = _env(tmp_path)
    proj = _project(tmp_path, env)
    (proj / ".pre-commit-config.yaml").write_text(LOCAL_CONFIG)
    (proj / "broken.openplx").write_text("Scene is Physics3D.System:\n    x: = 1\n")
    _git(proj, env, "add", "-A")
    first = _run(proj, env, "run", "--all-files")
    assert first.returncode == 1, first.stdout + first.stderr
    assert "plx fmt" in first.stdout and "Failed" in first.stdout
    assert "broken.openplx:2:8: error S008" in first.stdout  # refused by fmt, reported by lint
    assert (proj / "ugly.openplx").read_text() == PRETTY
    (proj / "broken.openplx").unlink()
    _git(proj, env, "add", "-A")
    second = _run(proj, env, "run", "--all-files")
    assert "plx fmt" in second.stdout
    fmt_line = next(line for line in second.stdout.splitlines() if line.startswith("plx fmt"))
    assert fmt_line.endswith("Passed"), second.stdout


@pytest.mark.skipif(not os.environ.get("PLX_SLOW_TESTS"), reason="set PLX_SLOW_TESTS=1 (pip-installs plxtools)")
def test_try_repo_with_the_real_python_install(tmp_path):
    env = _env(tmp_path)
    env["PATH"] = os.environ.get("PATH", "")
    src = tmp_path / "plxtools-repo"
    shutil.copytree(
        REPO,
        src,
        ignore=shutil.ignore_patterns(
            ".git", ".venv", "node_modules", "vscode-extension", "*.egg-info", "__pycache__", ".hypothesis"
        ),
    )
    _git(src, env, "init", "-q")
    _git(src, env, "add", "-A")
    _git(src, env, "commit", "-q", "-m", "snapshot")
    proj = _project(tmp_path, env)
    bad = _run(proj, env, "try-repo", str(src), "plx-fmt", "--files", "ugly.openplx")
    assert bad.returncode == 1 and (proj / "ugly.openplx").read_text() == PRETTY, bad.stdout + bad.stderr
    assert _run(proj, env, "try-repo", str(src), "plx-fmt", "--files", "ugly.openplx").returncode == 0
