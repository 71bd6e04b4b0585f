"""`plx fmt` and `plx lint --fix` never lose the user's file (issue 33, points 1 and 2).

A hard-linked file on a nearly full disk keeps its old contents byte for byte (a real tmpfs when
the test runs as root, as CI does; an injected short write elsewhere), and a save made by another
program while the command works is kept: the command leaves the file and says so, exit 2."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from tests.conftest import REPO, run_plx

HEAD = "Scene is Physics3D.System:\n"


def _one_space_model(bodies: int) -> str:
    """Valid OpenPLX indented by one space: `plx fmt` makes it about a third longer."""
    lines = [HEAD.rstrip("\n")]
    for i in range(bodies):
        lines += [f" b{i} is Physics3D.Bodies.RigidBody:", f"  inertia.mass: {i + 1}",
                  f"  inertia.locked: false"]
    return "\n".join(lines) + "\n"


def _plx_with(patch: str, *args: str) -> subprocess.CompletedProcess:
    """The CLI with one call replaced (a short write, an editor saving meanwhile), as a user meets it."""
    code = f"import sys, os, errno\n{patch}\nfrom plxtools.cli import main\nsys.exit(main(sys.argv[1:]))"
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=REPO)


def _no_temporaries(folder: Path) -> bool:
    return not [p for p in folder.iterdir() if p.name.endswith(".plxtmp")]


# ------------------------------------------------------------ a full disk, a hard link


@pytest.fixture
def small_disk():
    """A 64 KiB tmpfs (root only: CI runs as root); skipped where it cannot be mounted."""
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    folder = Path(tempfile.mkdtemp(prefix="plx-small-disk-"))
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(folder)], capture_output=True)
    if r.returncode != 0:
        folder.rmdir()
        pytest.skip(f"cannot mount a tmpfs here: {r.stderr.decode().strip()}")
    try:
        yield folder
    finally:
        subprocess.run(["umount", str(folder)], check=False)
        folder.rmdir()


def _fill_leaving(folder: Path, free: int) -> None:
    st = os.statvfs(folder)
    left = st.f_bavail * st.f_frsize - free
    assert left > 0
    (folder / "filler").write_bytes(b"\0" * left)


def _hard_linked_on_a_full_disk(folder: Path) -> tuple[Path, bytes]:
    """m.openplx (hard-linked) on a disk with room for the formatted copy but not for the file to
    grow in place as well: the state of the reproduction fmt-hardlink-full-disk-corrupts."""
    text = _one_space_model(300)
    formatted = run_plx("fmt", "-", stdin=text).stdout
    page = os.statvfs(folder).f_frsize
    assert math.ceil(len(formatted) / page) > math.ceil(len(text) / page)  # growing needs a new page
    m = folder / "m.openplx"
    m.write_text(text)
    os.link(m, folder / "link.openplx")
    _fill_leaving(folder, math.ceil(len(formatted) / page) * page)
    return m, text.encode()


def test_fmt_on_a_full_disk_leaves_a_hard_linked_file_whole(small_disk):
    m, before = _hard_linked_on_a_full_disk(small_disk)
    r = run_plx("fmt", str(m))
    assert r.returncode == 2, r.stderr
    assert "No space left on device" in r.stderr and "left as it was" in r.stderr
    assert "Traceback" not in r.stderr and "reformatted" not in r.stderr
    assert m.read_bytes() == before and (small_disk / "link.openplx").read_bytes() == before
    assert m.stat().st_nlink == 2 and _no_temporaries(small_disk)


def test_a_failed_in_place_write_is_undone_when_space_cannot_be_reserved(small_disk):
    """A file system without posix_fallocate: the write runs out of space part-way; the old
    contents are written back into the blocks the file already had."""
    m, before = _hard_linked_on_a_full_disk(small_disk)
    patch = ("def unsupported(*a): raise OSError(errno.EOPNOTSUPP, 'Operation not supported')\n"
             "os.posix_fallocate = unsupported")
    r = _plx_with(patch, "fmt", str(m))
    assert r.returncode == 2, r.stderr
    assert "No space left on device" in r.stderr and "left as it was" in r.stderr
    assert m.read_bytes() == before and (small_disk / "link.openplx").read_bytes() == before
    assert _no_temporaries(small_disk)


def test_lint_fix_on_a_full_disk_leaves_a_hard_linked_file_whole(small_disk):
    body = "    x is Real: 1  # plx: ignore[N003]\n"  # C002 (unused) has a safe fix: lint --fix writes
    text = HEAD + body * 400  # the fix deletes lines: the file shrinks, so the full disk is the temp copy
    m = small_disk / "m.openplx"
    m.write_text(text)
    os.link(m, small_disk / "link.openplx")
    _fill_leaving(small_disk, 0)
    r = run_plx("lint", "--fix", "--no-cache", str(m))
    assert r.returncode == 2, r.stdout + r.stderr
    assert "No space left on device" in r.stderr and "Traceback" not in r.stderr
    assert m.read_text() == text and _no_temporaries(small_disk)


def test_a_write_cut_short_in_place_restores_the_old_text(tmp_path):
    """Anywhere (no root): the in-place write of a hard-linked file stops after 100 bytes."""
    m = tmp_path / "m.openplx"
    text = _one_space_model(30)
    m.write_text(text)
    os.link(m, tmp_path / "link.openplx")
    patch = ("_real = os.pwrite\n"
             "calls = []\n"
             "def short(fd, data, offset):\n"
             "    calls.append(1)\n"
             "    if len(calls) == 1:\n"
             "        _real(fd, bytes(data[:100]), offset)\n"
             "        raise OSError(errno.ENOSPC, 'No space left on device')\n"
             "    return _real(fd, data, offset)\n"
             "os.pwrite = short")
    r = _plx_with(patch, "fmt", str(m))
    assert r.returncode == 2 and "left as it was" in r.stderr, r.stderr
    assert m.read_text() == text and _no_temporaries(tmp_path)


def test_when_even_the_restore_fails_the_complete_copy_is_kept_and_named(tmp_path):
    m = tmp_path / "m.openplx"
    m.write_text(_one_space_model(30))
    os.link(m, tmp_path / "link.openplx")
    formatted = run_plx("fmt", "-", stdin=m.read_text()).stdout
    patch = ("_real = os.pwrite\n"
             "def short(fd, data, offset):\n"
             "    _real(fd, bytes(data[:100]), offset)\n"
             "    raise OSError(errno.EIO, 'Input/output error')\n"
             "os.pwrite = short")
    r = _plx_with(patch, "fmt", str(m))
    assert r.returncode == 2
    kept = [p for p in tmp_path.iterdir() if p.name.endswith(".plxtmp")]
    assert len(kept) == 1 and str(kept[0]) in r.stderr and "could not be restored" in r.stderr
    assert kept[0].read_text() == formatted


# ------------------------------------------------------------ a save made meanwhile


_EDITOR_SAVES_DURING = {
    # the command's own step between reading the file and writing it, with an editor's save added
    "fmt": ("import plxtools.fmt.api as api\n_orig = api.format_bytes\n"
            "def format_bytes(data, name):\n"
            "    r = _orig(data, name)\n"
            "    open(name, 'a').write('# SAVED BY EDITOR\\n')\n"
            "    return r\n"
            "api.format_bytes = format_bytes"),
    "lint": ("import plxtools.lint.runner as runner\n_orig = runner.fixed_text\n"
             "def fixed_text(tree, diags, unsafe):\n"
             "    r = _orig(tree, diags, unsafe)\n"
             "    open(tree.path, 'a').write('# SAVED BY EDITOR\\n')\n"
             "    return r\n"
             "runner.fixed_text = fixed_text"),
}


@pytest.mark.parametrize("command", ["fmt", "lint"])
def test_a_save_made_while_the_command_works_is_kept(tmp_path, command):
    m = tmp_path / "m.openplx"
    text = HEAD + " x is   Real: 1  # plx: ignore[N003]\n"  # fmt changes the layout; lint --fix drops x
    m.write_text(text)
    args = ("fmt", str(m)) if command == "fmt" else ("lint", "--fix", "--no-cache", str(m))
    r = _plx_with(_EDITOR_SAVES_DURING[command], *args)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "changed on disk after it was read" in r.stderr and "left as it is" in r.stderr
    assert m.read_text() == text + "# SAVED BY EDITOR\n" and _no_temporaries(tmp_path)


def test_a_hard_linked_file_saved_meanwhile_is_kept_too(tmp_path):
    m = tmp_path / "m.openplx"
    text = HEAD + " x is   Real: 1\n"
    m.write_text(text)
    os.link(m, tmp_path / "link.openplx")
    r = _plx_with(_EDITOR_SAVES_DURING["fmt"], "fmt", str(m))
    assert r.returncode == 2 and "changed on disk" in r.stderr
    assert (tmp_path / "link.openplx").read_text() == text + "# SAVED BY EDITOR\n"


def test_without_a_concurrent_save_the_file_is_formatted(tmp_path):
    """The comparison does not refuse an untouched file (the control for the tests above)."""
    m = tmp_path / "m.openplx"
    m.write_text(HEAD + " x is   Real: 1\n")
    r = run_plx("fmt", str(m))
    assert r.returncode == 0, r.stderr
    assert m.read_text() == HEAD + "    x is Real: 1\n"
