"""Issue 45: a newcomer's mistakes, one case file each (tests/cases/mistakes/), each graded as rustc
or Elm messages are: does the first error or warning name the cause (the expected code), point at
the place (the mistaken line), and say the fix (a help line)?

Each case's first line is the command (`# plx lint` or `# plx check`, the file name appended), its
third says where the mistake is (`# expect: CODE at line N`). The test compares the output with
`<case>.expected` and the grades with the table in docs/mistakes.md (both recorded by
`PLX_UPDATE_SNAPSHOTS=1`; review the diff), and fails when a case grades below B, so a message
that gets worse, or a mistake that passes silently, fails here."""

from __future__ import annotations

import os
import re
import shlex
from pathlib import Path

import pytest

from tests.conftest import plx_here

REPO = Path(__file__).resolve().parents[2]
CASES = REPO / "tests" / "cases" / "mistakes"
DOC = REPO / "docs" / "mistakes.md"
UPDATE = os.environ.get("PLX_UPDATE_SNAPSHOTS") == "1"
EXPECT = re.compile(r"# expect: (\w+) at line (\d+)")
LINE = re.compile(r"^(?P<file>[^\s:]+):(?P<line>\d+):\d+: (?P<sev>error|warning|info) (?P<code>[A-Z]\d{3})")
FILES = sorted(CASES.glob("*.openplx"))


def run(path: Path) -> tuple[str, int]:
    command = shlex.split(path.read_text(encoding="utf-8").splitlines()[0].lstrip("# "))[1:]
    r = plx_here(*command, path.name, cwd=CASES)
    return r.stdout, r.returncode


def grade(path: Path, out: str) -> tuple[str, str, str]:
    """(grade, what plx says first, why that grade)."""
    code, line = EXPECT.search(path.read_text(encoding="utf-8")).groups()
    lines = []
    for s in out.splitlines():  # a long message continues on indented lines (reporters.fit)
        if s.startswith("    ") and lines:
            lines[-1] += " " + s.strip()
        else:
            lines.append(s)
    findings = [(i, LINE.match(s)) for i, s in enumerate(lines) if LINE.match(s)]
    serious = [(i, m) for i, m in findings if m["sev"] != "info"]
    if not serious:
        return "D", "(nothing)", "silent"
    i, first = next(((i, m) for i, m in serious if m["sev"] == "error"), serious[0])
    said = lines[i].split(f" {first['code']} ", 1)[1].removeprefix("[*] ")
    helped = i + 1 < len(lines) and lines[i + 1].startswith("  help: ")
    if helped:
        said += " / help: " + lines[i + 1][8:]
    cause = first["code"] == code
    place = first["line"] == line
    named = [p for c, p in ((cause, "cause"), (place, "place")) if c] + (["fix"] if helped else [])
    score = len(named)
    letter = {3: "A", 2: "B", 1: "C", 0: "D"}[score]
    if not cause and any(m["code"] == code and m["line"] == line for _i, m in serious):
        letter = "C" if letter == "D" else letter  # found, but not first
    return letter, said, ", ".join(named) or "wrong finding first"


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_mistake_case(path: Path):
    out, code = run(path)
    got = out + f"# exit code {code}\n"
    expected = path.with_suffix(".expected")
    if UPDATE:
        expected.write_text(got, encoding="utf-8")
    assert got == expected.read_text(encoding="utf-8"), f"snapshot differs: {expected.name}"
    letter, _said, why = grade(path, out)
    assert letter in ("A", "B"), f"{path.stem} grades {letter} ({why})"


def table() -> str:
    rows = ["| case | the mistake | plx says first | grade | because it names |", "|---|---|---|---|---|"]
    for path in FILES:
        text = path.read_text(encoding="utf-8").splitlines()
        out, _code = run(path)
        letter, said, why = grade(path, out)
        what = text[1].lstrip("# ").removeprefix("A newcomer ").rstrip(".")
        said = said.replace("|", "\\|")
        if len(said) > 160:
            said = said[:157] + "..."
        rows.append(f"| `{path.stem}` | {what} | {said} | {letter} | {why} |")
    return "\n".join(rows) + "\n"


def test_the_grading_table_in_the_docs_is_current():
    start, end = "<!-- grades -->\n", "<!-- /grades -->"
    doc = DOC.read_text(encoding="utf-8")
    new = doc[:doc.index(start) + len(start)] + table() + doc[doc.index(end):]
    if UPDATE:
        DOC.write_text(new, encoding="utf-8")
    assert new == doc, "docs/mistakes.md's table is stale: PLX_UPDATE_SNAPSHOTS=1 python -m pytest tests/mistakes"
    assert len(FILES) >= 30
