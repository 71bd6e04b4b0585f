"""Shared checks for the formatter tests: meaning, comments and stability, judged independently
of the formatter's own safety net."""

from __future__ import annotations

import os
import re
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


# An independent tokenizer (not plxtools' lexer): strings, backtick names, numbers, words,
# `->` and single characters; comments and whitespace are layout.
_ORACLE = re.compile(r'"""[\s\S]*?(?:"""|$)|[@$]?"[^"\r\n]*"?|`[^`\r\n]*`|\d+(?:\.\d+)?(?:[eE][+-]?\d+)?|\w+|->|#[^\r\n]*|\S')


def oracle_tokens(text: str) -> list[str]:
    """The text's tokens without comments, and without a comma right before a closing bracket."""
    toks = [t for t in _ORACLE.findall(text) if not t.startswith("#")]
    return [t for i, t in enumerate(toks) if not (t == "," and i + 1 < len(toks) and toks[i + 1] in ")]}")]


def assert_same_tokens(before: str, after: str) -> None:
    assert oracle_tokens(before) == oracle_tokens(after)


def lint_signature(text: str) -> list[tuple[str, str]]:
    """What the public lint API reports (suppressions applied), minus what fmt fixes by design
    (C006 indentation, S003 tabs) and the line numbers messages quote."""
    from dataclasses import replace

    from plxtools.config import Config
    from plxtools.rules.analysis import analyse_tree

    cfg = replace(Config(), ignore=["C006"])
    diags = analyse_tree(parse_text(text), cfg)
    return sorted((d.code, re.sub(r"\d+", "#", d.message)) for d in diags if d.code not in ("C006", "S003"))


def assert_same_lint(before: str, after: str) -> None:
    assert lint_signature(before) == lint_signature(after)
