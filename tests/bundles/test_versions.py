"""Every official openplx-bundles version parses and lints with no error-severity diagnostic.

The default suite covers the oldest (0.15.0) and the newest (0.19.0); `PLX_ALL_VERSIONS=1` (run by
.ci/run) covers each minor's latest patch plus 0.17.26, and `PLX_ALL_VERSIONS=every` every release.
Wheels are fetched once into plx's cache (PLX_CACHE_DIR), so later runs are offline and fast.
"""

from __future__ import annotations

import json
import os

import pytest

from tests.conftest import run_plx
from plxtools.model.versions import KNOWN_VERSIONS, SUPPORTED_LATEST

_ALL = os.environ.get("PLX_ALL_VERSIONS", "")
SLOW = [v for v in (KNOWN_VERSIONS if _ALL == "every" else SUPPORTED_LATEST) if v not in ("0.15.0", "0.19.0")]


def _lint_version(fetched, version: str) -> None:
    root = fetched(version)
    r = run_plx("lint", "--openplx-version", version, str(root), "--output-format", "json")
    assert r.returncode in (0, 1), r.stderr
    diags = json.loads(r.stdout)
    errors = [d for d in diags if d["severity"] == "error"]
    assert errors == [], f"{version}: {len(errors)} errors, first: {errors[:3]}"
    files = list(root.rglob("*.openplx"))
    assert len(files) > 300, f"{version}: only {len(files)} bundle files"
    # the run used that version's bundles, not the installed ones
    s = run_plx("lint", "--openplx-version", version, str(root), "--show-settings")
    assert any(ln.split()[:2] == ["Physics3D", version] for ln in s.stdout.splitlines()), s.stdout


@pytest.mark.parametrize("version", ["0.15.0", "0.19.0"])
def test_oldest_and_newest_lint_clean(fetched, version):
    _lint_version(fetched, version)


@pytest.mark.skipif(not _ALL, reason="slow: set PLX_ALL_VERSIONS=1 (CI does) or =every")
@pytest.mark.parametrize("version", SLOW)
def test_every_version_lints_clean(fetched, version):
    _lint_version(fetched, version)


def test_check_evaluates_a_017_model_under_017(fetched):
    """A model written for 0.17 (Charges namespace, `charges:` on a mate) checks clean under 0.17.26."""
    fetched("0.17.26")
    case = os.path.join(os.path.dirname(__file__), "cases", "pendulum_017.openplx")
    r = run_plx("check", "--openplx-version", "0.17.26", case, "--output-format", "json")
    assert r.returncode == 0, r.stdout + r.stderr
    doc = json.loads(r.stdout)
    assert [d for d in doc["diagnostics"] if d["severity"] == "error"] == []
    assert doc["assembly"][case]["model"] == "Pendulum"
    assert "bob" in doc["assembly"][case]["bodies"]
    # and the same file under 0.19.0 is reported: the Charges namespace is gone there, and the
    # moved names are U001 with the new name as the fix
    r19 = run_plx("check", "--openplx-version", "0.19.0", case, "--output-format", "json")
    codes = {d["code"] for d in json.loads(r19.stdout)["diagnostics"]}
    assert "U001" in codes
