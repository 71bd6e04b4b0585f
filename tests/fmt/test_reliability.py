"""`plx fmt` keeps what `# plx: ignore` covers, never bakes in an indentation mistake, and leaves
the user's file theirs (symlinks, hard links, mode, read-only files, OS errors) — issues 14, 16."""

from __future__ import annotations

import os
import stat
import sys
import subprocess

from plxtools.fmt import document, format_text
from tests.conftest import REPO, plx_here

HEAD = "Scene is Physics3D.System:\n"
MESSY = HEAD + "    x is   Real: 1\n"
TIDY = HEAD + "    x is Real: 1\n"


# ------------------------------------------------------------ suppressions


def _lint_fmt_lint(tmp_path, text: str) -> tuple[str, str, str]:
    p = tmp_path / "x.openplx"
    p.write_text(text)
    before = plx_here("lint", str(p))
    r = plx_here("fmt", str(p))
    assert r.returncode == 0, r.stderr
    after = plx_here("lint", str(p))
    return before.stdout, after.stdout, p.read_text()


def test_a_split_bracket_keeps_its_suppression(tmp_path):
    text = HEAD + "    # plx: ignore[N003]\n    v is Real[]: [foo,\n        1]\n"
    before, after, _ = _lint_fmt_lint(tmp_path, text)
    assert "All checks passed" in before and "All checks passed" in after


def test_a_trailing_suppression_keeps_its_statement_as_written(tmp_path):
    text = HEAD + "    v is Real[]: [foo,  # plx: ignore[N003]\n        1]\n    w is   Real: 1\n"
    before, after, out = _lint_fmt_lint(tmp_path, text)
    assert "All checks passed" in before and "All checks passed" in after
    assert "    v is Real[]: [foo,  # plx: ignore[N003]\n        1]\n" in out
    assert "    w is Real: 1\n" in out  # the rest of the file is formatted


def test_the_safety_check_refuses_output_that_moves_suppressed_code(monkeypatch):
    # without the pinning, the formatter spreads the bracket over lines and `foo` leaves the
    # suppressed line: the lint comparison must catch it and refuse
    monkeypatch.setattr(document, "_pinned", lambda piece, prev: False)
    result = format_text(HEAD + "    # plx: ignore[N003]\n    v is Real[]: [foo,\n        1]\n")
    assert not result.ok
    assert "would change what a `# plx: ignore` comment covers" in result.internal_error
    assert "N003" in result.internal_error


# ------------------------------------------------------------ indentation between levels


def test_fmt_refuses_a_line_between_two_levels(tmp_path):
    text = "A is B:\n    c is B:\n        a: 1\n      b: 2\n        d: 3\n"
    p = tmp_path / "x.openplx"
    p.write_text(text)
    r = plx_here("fmt", str(p))
    assert r.returncode == 2
    assert f"{p}:4:7: error S015" in r.stderr and "not formatted" in r.stderr
    assert p.read_text() == text


# ------------------------------------------------------------ files are the user's


def test_fmt_writes_through_a_symlink(tmp_path):
    real = tmp_path / "real.openplx"
    real.write_text(MESSY)
    link = tmp_path / "link.openplx"
    link.symlink_to(real)
    r = plx_here("fmt", str(link))
    assert r.returncode == 0, r.stderr
    assert link.is_symlink() and real.read_text() == TIDY


def test_fmt_keeps_hard_links_and_mode(tmp_path):
    a = tmp_path / "a.openplx"
    a.write_text(MESSY)
    os.chmod(a, 0o640)
    b = tmp_path / "b.openplx"
    os.link(a, b)
    ino = a.stat().st_ino
    r = plx_here("fmt", str(a))
    assert r.returncode == 0, r.stderr
    assert a.stat().st_ino == ino and b.read_text() == TIDY and a.stat().st_nlink == 2
    assert stat.S_IMODE(a.stat().st_mode) == 0o640
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".plxtmp")]


def test_fmt_keeps_mode_on_a_single_link(tmp_path):
    a = tmp_path / "a.openplx"
    a.write_text(MESSY)
    os.chmod(a, 0o604)
    assert plx_here("fmt", str(a)).returncode == 0
    assert a.read_text() == TIDY and stat.S_IMODE(a.stat().st_mode) == 0o604


def test_fmt_refuses_a_read_only_file(tmp_path):
    a = tmp_path / "a.openplx"
    a.write_text(MESSY)
    os.chmod(a, 0o444)
    r = plx_here("fmt", str(a))
    assert r.returncode == 2
    assert "is read-only; not changing it" in r.stderr
    assert "bug" not in r.stderr and a.read_text() == MESSY


def _plx_with(patch: str, *args: str) -> subprocess.CompletedProcess:
    """The CLI with one OS call replaced (a read-only folder, a full disk), as a user would meet it."""
    code = f"import sys, os, errno, tempfile\n{patch}\nfrom plxtools.cli import main\nsys.exit(main(sys.argv[1:]))"
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=REPO)


def test_a_read_only_folder_is_reported_as_such(tmp_path):
    a = tmp_path / "a.openplx"
    a.write_text(MESSY)
    patch = ("def deny(*a, **k): raise PermissionError(errno.EACCES, 'Permission denied')\n"
             "tempfile.mkstemp = deny")
    r = _plx_with(patch, "fmt", str(a))
    assert r.returncode == 2
    assert f"cannot write {a}: cannot create a temporary file in {tmp_path}: Permission denied" in r.stderr
    assert "bug" not in r.stderr and a.read_text() == MESSY


def test_a_full_disk_is_reported_and_leaves_the_file_whole(tmp_path):
    a = tmp_path / "a.openplx"
    a.write_text(MESSY)
    b = tmp_path / "b.openplx"
    unused = HEAD + "    x is Real: 1  # plx: ignore[N003]\n"  # C002 with a safe fix: lint --fix writes
    b.write_text(unused)
    patch = ("def full(fd): raise OSError(errno.ENOSPC, 'No space left on device')\n"
             "os.fsync = full")
    for cmd in (("fmt", str(a)), ("lint", "--fix", str(b))):
        r = _plx_with(patch, *cmd)
        assert r.returncode == 2, r.stdout + r.stderr
        assert "No space left on device" in r.stderr and "bug" not in r.stderr
    assert a.read_text() == MESSY and b.read_text() == unused
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".plxtmp")]
