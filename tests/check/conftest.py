"""Shared fixtures of the `plx check` tests: one workspace for the session, and helpers that run the
check pipeline (in process, no MuJoCo unless asked) on a file or on inline OpenPLX text."""

from __future__ import annotations

from pathlib import Path

import pytest

from check_helpers import EXAMPLE


@pytest.fixture(scope="session")
def ws():
    from plxtools.model.workspace import workspace_for_cli

    return workspace_for_cli([], [EXAMPLE])


@pytest.fixture(scope="session")
def check_file(ws):
    """check_file(path, model=None, simulate=False, duration=3.0) -> FileCheck"""
    from plxtools.check.pipeline import analyse, blocking_reason, run_backend
    from plxtools.config import config_for

    def run(path: Path, model: str | None = None, simulate: bool = False, duration: float = 3.0):
        fc = analyse(Path(path), ws, config_for(Path(path)), model=model)
        if simulate:
            assert blocking_reason(fc) is None, [d.to_json() for d in fc.diagnostics]
            run_backend(fc, simulate=True, duration=duration)
        return fc

    return run


@pytest.fixture
def check_text(check_file, tmp_path):
    """check_text(text, model=None, name="scene.openplx") -> FileCheck"""

    def run(text: str, model: str | None = None, name: str = "scene.openplx", simulate: bool = False):
        p = tmp_path / name
        p.write_text(text.lstrip("\n"), encoding="utf-8")
        return check_file(p, model=model, simulate=simulate)

    return run
