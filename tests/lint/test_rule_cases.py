"""Each case file triggers its rules at the expected places with the expected words, and its near
misses stay silent.

`<case>.expected` is a snapshot of everything a user sees for `<case>.openplx`: each diagnostic as
`plx lint` prints it (location, severity, code, message, help) and the unified diff that
`plx lint --fix --unsafe-fixes` would apply. After a deliberate change, regenerate the snapshots
with `PLX_UPDATE_SNAPSHOTS=1 python -m pytest tests/lint/test_rule_cases.py` and review the diff.
"""

import io
import os
from pathlib import Path

import pytest

from plxtools.fileio import unified_diff
from plxtools.lint.runner import fixed_text, lint_file
from plxtools.rules.reporters import render_text
from tests.conftest import CASES

CASE_FILES = sorted((CASES / "lint").glob("*.openplx"))
UPDATE = os.environ.get("PLX_UPDATE_SNAPSHOTS") == "1"


def snapshot(path: Path, workspace) -> str:
    result = lint_file(path, workspace=workspace)
    for d in result.diagnostics:
        d.file = path.name  # the snapshot does not depend on where the checkout is
    out = io.StringIO()
    render_text(result.diagnostics, out, summary=False)
    text = out.getvalue()
    if result.tree is not None and not result.tree.has_errors_of_syntax():
        new, n = fixed_text(result.tree, result.diagnostics, unsafe=True)
        if n:
            text += "\n# plx lint --fix --unsafe-fixes\n" + unified_diff(path.name, result.tree.text, new)
    return text


@pytest.mark.parametrize("path", CASE_FILES, ids=lambda p: p.stem)
def test_case_file(path: Path, workspace):
    got = snapshot(path, workspace)
    expected_file = path.with_suffix(".expected")
    if UPDATE:
        expected_file.write_text(got, encoding="utf-8")
    assert got == expected_file.read_text(encoding="utf-8"), f"snapshot differs: {expected_file.name}"


# Every registered code has a case somewhere: tests/test_rule_case_files.py, generated from the
# registry (this folder's topic cases count there).
