"""Shared checks for the formatter tests: meaning, comments and stability, judged independently
of the formatter's own safety net."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from plxtools.fmt import format_text
from plxtools.syntax import ast, parse_text

REPO = Path(__file__).resolve().parents[2]


def assert_same_meaning(before: str, after: str) -> None:
    a, b = parse_text(before), parse_text(after)
    assert not b.has_errors, [d.message for d in b.diagnostics]
    assert ast.structure(a.statements) == ast.structure(b.statements)
    assert [c.text.rstrip() for c in a.comments] == [c.text.rstrip() for c in b.comments]


def assert_fixed_point(text: str) -> None:
    again = format_text(text)
    assert again.ok, again.internal_error or again.diagnostics
    assert again.text == text, "formatting the output again changed it"


def formatted(text: str) -> str:
    result = format_text(text)
    assert result.ok, result.internal_error or [d.message for d in result.diagnostics]
    return result.text


def run_fmt(*args: str, stdin: bytes | None = None, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """`python -m plxtools fmt ...` in a subprocess, bytes in and out."""
    env = dict(os.environ)
    env["NO_COLOR"] = "1"
    return subprocess.run(
        [sys.executable, "-m", "plxtools", "fmt", *args],
        input=stdin,
        capture_output=True,
        cwd=cwd or REPO,
        env=env,
        timeout=120,
    )
