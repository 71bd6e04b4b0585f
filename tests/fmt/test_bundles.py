"""Every official bundle file: formatting is stable, keeps the meaning, and leaves lint's
diagnostics as they were (codes and messages; lines may move). C006 (siblings indented
differently) is the one diagnostic formatting is meant to remove."""

from __future__ import annotations

import difflib
import time
from collections import Counter

from plxtools.config import config_for
from plxtools.fmt import format_bytes
from plxtools.lint.runner import lint_file
from plxtools.rules.analysis import analyse_tree
from plxtools.syntax import parse_text
from tests.fmt.helpers import assert_fixed_point, assert_same_meaning

FIXED_BY_FORMATTING = {"C006"}


def _lint_key(diags) -> Counter:
    return Counter((d.code, d.message) for d in diags if d.code not in FIXED_BY_FORMATTING)


def changed_line_count(old: str, new: str) -> int:
    """Lines of the old text that are replaced or removed, or new lines added (the larger side)."""
    ops = difflib.SequenceMatcher(None, old.splitlines(), new.splitlines(), autojunk=False).get_opcodes()
    return sum(max(i2 - i1, j2 - j1) for tag, i1, i2, j1, j2 in ops if tag != "equal")


def test_bundle_files_format_stably_with_the_same_meaning_and_lint(bundles):
    started = time.perf_counter()
    changed_lines = 0
    for path in bundles:
        data = path.read_bytes()
        result = format_bytes(data, str(path))
        assert result.ok, (path, result.internal_error, result.diagnostics)
        source = data.decode("utf-8-sig")
        if not result.changed:
            continue
        assert_same_meaning(source, result.text)
        assert_fixed_point(result.text)
        before = _lint_key(lint_file(path).diagnostics)
        after = _lint_key(analyse_tree(parse_text(result.text, str(path)), config_for(path)))
        assert before == after, path
        changed_lines += changed_line_count(source, result.text)
    assert time.perf_counter() - started < 30
    # the style was chosen to match the bundles: most of their lines must survive untouched
    assert changed_lines < 0.05 * sum(len(p.read_text(encoding="utf-8").splitlines()) for p in bundles)
