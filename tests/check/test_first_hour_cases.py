"""Issue 32, points 4 and 6: each case file's `plx check --simulate` findings, as a user reads them.

`tests/cases/check/first_hour/<case>.expected` holds every diagnostic of the run (location,
severity, code, message, help) with decimal numbers written as `#`: the simulated figures move
with the physics backend, the words and the places must not. Regenerate after a deliberate change
with `PLX_UPDATE_SNAPSHOTS=1 python -m pytest tests/check/test_first_hour_cases.py`.
"""

from __future__ import annotations

import json
import os
import re

import pytest

from tests.check.check_helpers import CASES
from tests.conftest import run_plx

CASE_FILES = sorted((CASES / "first_hour").glob("*.openplx"))
UPDATE = os.environ.get("PLX_UPDATE_SNAPSHOTS") == "1"
DECIMAL = re.compile(r"-?\d+\.\d+(e[-+]?\d+)?|\b\d{3,}\b")


def findings(path) -> str:
    r = run_plx("check", "--simulate", "--output-format", "json", str(path))
    assert r.returncode in (0, 1), r.stderr
    out = []
    for d in json.loads(r.stdout)["diagnostics"]:
        start = d["range"]["start"]
        out.append(f"{start['line']}:{start['column']}: {d['severity']} {d['code']} {d['message']}")
        if d.get("help"):
            out.append(f"  help: {d['help']}")
    return DECIMAL.sub("#", "\n".join(out) + "\n")


@pytest.mark.parametrize("path", CASE_FILES, ids=lambda p: p.stem)
def test_case_findings(path):
    got = findings(path)
    expected = path.with_suffix(".expected")
    if UPDATE:
        expected.write_text(got, encoding="utf-8")
    assert got == expected.read_text(encoding="utf-8"), f"findings differ: {expected.name}\n{got}"
