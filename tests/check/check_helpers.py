"""Helpers shared by the `plx check` tests (a plain module: conftest.py files share one name)."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
BROKEN = REPO / "examples" / "broken"
CASES = REPO / "tests" / "cases" / "check"


def codes(fc) -> list[tuple[str, int]]:
    """(code, 1-based line) of every diagnostic."""
    return [(d.code, d.span.start.line + 1) for d in fc.diagnostics]


def line_of(path: Path, needle: str, occurrence: int = 1) -> int:
    """1-based line of the n-th line containing ``needle``."""
    n = 0
    for i, line in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), 1):
        if needle in line:
            n += 1
            if n == occurrence:
                return i
    raise AssertionError(f"{needle!r} not in {path}")
