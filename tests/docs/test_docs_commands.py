"""Every `plx` command shown in the docs works and prints what the page says it prints.

Conventions in the pages (docs/getting-started.md explains them to readers):

- A fenced ```sh block holds commands, one per line. Lines that run `plx` (directly, or at the end
  of a pipe) are run from the repository root; install and set-up lines (`python3 -m venv`, `pip`,
  `. .venv/bin/activate`) are skipped, and any other command fails this test, so nothing shown is
  silently left untested.
- A trailing `# exits N` states the exit code; without one the command must exit 0.
- A ```text block right after a one-command ```sh block is the expected output (stdout, then
  stderr). Its lines must match the output's lines in order, exactly (trailing spaces aside), where
  `…` inside a line matches any text and a line that is only `…` matches any number of lines.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.conftest import REPO

DOCS = REPO / "docs"
# the pages whose ```sh blocks are runnable examples (pages written by other teams are not listed)
PAGES = ["getting-started.md", "index.md", "examples.md", "lint.md", "cli.md", "testing.md"]
SETUP = re.compile(r"^(python3? -m venv |\. \.venv/bin/activate$|pip install )")
FENCE = re.compile(r"^```(?P<lang>[\w-]*)\n(?P<body>.*?)^```[ \t]*$", re.S | re.M)
EXITS = re.compile(r"\s+#\s*exits\s+(\d+)\s*$")


@dataclass
class Command:
    page: str
    line: str
    exit_code: int
    expected: str | None  # the text block after it, if any

    @property
    def id(self) -> str:
        return f"{self.page}: {self.line}"


def _is_plx(cmd: str) -> bool:
    return cmd.startswith("plx ") or cmd == "plx" or re.search(r"\|\s*plx\b", cmd) is not None


def commands(page: str) -> list[Command]:
    text = (DOCS / page).read_text(encoding="utf-8")
    blocks = list(FENCE.finditer(text))
    out: list[Command] = []
    for i, m in enumerate(blocks):
        if m.group("lang") != "sh":
            continue
        expected = None
        nxt = blocks[i + 1] if i + 1 < len(blocks) else None
        if nxt is not None and nxt.group("lang") == "text" and text[m.end():nxt.start()].strip() == "":
            expected = nxt.group("body")
        lines = [ln.strip() for ln in m.group("body").splitlines()]
        lines = [ln for ln in lines if ln and not ln.startswith("#")]
        runnable = []
        for ln in lines:
            code = 0
            em = EXITS.search(ln)
            if em:
                code = int(em.group(1))
                ln = ln[: em.start()].rstrip()
            if _is_plx(ln):
                runnable.append(Command(page, ln, code, None))
            elif not SETUP.match(ln):
                raise AssertionError(f"{page}: a ```sh block has a command this test cannot run: {ln!r}")
        if expected is not None:
            assert len(runnable) == 1, f"{page}: expected output follows a block with {len(runnable)} commands"
            runnable[0].expected = expected
        out.extend(runnable)
    return out


ALL = [c for p in PAGES for c in commands(p)]


def expected_regex(expected: str) -> re.Pattern:
    parts = []
    for ln in expected.rstrip("\n").split("\n"):
        ln = ln.rstrip()
        if ln == "…":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            parts.append(".*?".join(re.escape(piece) for piece in ln.split("…")) + r"\n")
    return re.compile("".join(parts) + r"\Z")


def _env() -> dict:
    env = dict(os.environ)
    env.pop("FORCE_COLOR", None)
    env["NO_COLOR"] = "1"
    env["COLUMNS"] = "100"
    # the `plx` next to this interpreter, whatever PATH says
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    return env


def test_the_pages_have_commands():
    assert len([c for c in ALL if c.page == "getting-started.md"]) >= 8
    assert any("check --simulate" in c.line for c in ALL if c.page == "getting-started.md")
    assert all(c.expected is not None for c in ALL if c.page == "getting-started.md" and "lint" in c.line)


def test_the_matcher():
    rx = expected_regex("a\n…\nc … d\n")
    assert rx.match("a\nb\nb\nc x y d\n")
    assert rx.match("a\nc  d\n")
    assert not rx.match("a\nb\n")
    assert not rx.match("x\na\nc d\n")


@pytest.mark.parametrize("cmd", ALL, ids=[c.id for c in ALL])
def test_command(cmd: Command):
    r = subprocess.run(["bash", "-c", "set -o pipefail; " + cmd.line], cwd=REPO, env=_env(),
                       capture_output=True, text=True, timeout=120)
    output = "\n".join(ln.rstrip() for ln in (r.stdout + r.stderr).splitlines()) + "\n"
    assert r.returncode == cmd.exit_code, f"{cmd.id}: exit {r.returncode}, the page says {cmd.exit_code}\n{output}"
    if cmd.expected is not None:
        assert expected_regex(cmd.expected).match(output), (
            f"{cmd.id}: the output differs from the page\n--- page:\n{cmd.expected}--- actual:\n{output}")
