"""Each case file triggers its rules at the expected positions, and its near misses stay silent."""

from pathlib import Path

import pytest

from plxtools.lint.runner import lint_file
from tests.conftest import CASES

CASE_FILES = sorted((CASES / "lint").glob("*.openplx"))


@pytest.mark.parametrize("path", CASE_FILES, ids=lambda p: p.stem)
def test_case_file(path: Path, workspace):
    expected = path.with_suffix(".expected").read_text().split()
    expected = [f"{a} {b}" for a, b in zip(expected[::2], expected[1::2])]
    result = lint_file(path, workspace=workspace)
    got = [f"{d.span.start.line + 1}:{d.span.start.column + 1} {d.code}" for d in result.diagnostics]
    assert got == expected


def test_every_semantic_code_has_a_case_or_a_dedicated_test():
    from plxtools.rules.registry import all_rules

    covered = set()
    for p in (CASES / "lint").glob("*.expected"):
        covered |= {line.split()[1] for line in p.read_text().splitlines() if line.strip()}
    # B000: tests/ide/test_bundles_unavailable.py
    dedicated = {"B000", "B001", "B002", "B003", "B004", "B005", "E001", "T007", "M009"}
    semantic = {r.code for r in all_rules() if r.stage == "lint" and r.code[0] in "NTMBC"}
    assert semantic - covered - dedicated == set()
