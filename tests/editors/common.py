"""Shared pieces of the real-editor tests (Neovim, Helix): the documented snippets, a project to open, and the editors."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
REQUIRED = os.environ.get("PLX_EDITOR_TESTS") == "1"

MODEL = """\
Ball is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    geometry is Physics3D.Geometries.Sphere:
        raduis: 0.5
    spot is Math.Vec3: Math.Vec3.from_xyz(1, 2, 3)
"""


def doc_blocks(section: str, lang: str) -> list[str]:
    """The fenced `lang` blocks of one `## section` of docs/editors.md, as written there."""
    page = (REPO / "docs" / "editors.md").read_text(encoding="utf-8")
    start = page.index(f"## {section}")
    end = page.find("\n## ", start + 1)
    return re.findall(rf"```{lang}\n(.*?)```", page[start:end if end > 0 else None], re.S)


def make_project(tmp_path: Path) -> Path:
    project = tmp_path / "project"
    project.mkdir()
    subprocess.run(["git", "init", "-q", str(project)], check=True)
    (project / "plx.toml").write_text("", encoding="utf-8")
    (project / "model.openplx").write_text(MODEL, encoding="utf-8")
    return project


def editor_env(home: Path) -> dict[str, str]:
    """A clean home for the editor, and this checkout's `plx` first on PATH."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("XDG_", "NVIM", "VIM"))}
    env.update(HOME=str(home), XDG_CONFIG_HOME=str(home / ".config"), XDG_DATA_HOME=str(home / ".local/share"),
               XDG_STATE_HOME=str(home / ".local/state"), XDG_CACHE_HOME=str(home / ".cache"),
               PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ["PATH"])
    return env


def debian_editor(suite: str, package: str) -> Path:
    """The launcher of `package` from Debian `suite`, fetched when the editor tests are required.

    Without PLX_EDITOR_TESTS=1 only an editor fetched before is used (no download in a plain test run).
    """
    from tests.editors import debian_editors

    stamp = debian_editors.cache_root() / suite / f"ready-{package}"
    if not REQUIRED and not stamp.exists():
        pytest.skip(f"{package} from Debian {suite} not fetched (PLX_EDITOR_TESTS=1 fetches it)")
    if shutil.which("dpkg-deb") is None:
        if REQUIRED:
            pytest.fail("PLX_EDITOR_TESTS=1 but dpkg-deb is missing")
        pytest.skip("dpkg-deb is missing")
    try:
        return debian_editors.launcher(suite, package)
    except OSError as exc:  # the archive cannot be reached
        if REQUIRED:
            pytest.fail(f"PLX_EDITOR_TESTS=1 but {package} from Debian {suite} could not be fetched: {exc}")
        pytest.skip(f"{package} from Debian {suite} could not be fetched: {exc}")
