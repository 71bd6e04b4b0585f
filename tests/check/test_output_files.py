"""The files `plx check` writes on request (`--trace`, `--export-mjcf`) go through the one safe
writer (issue 33, point 3): symlinks are written through, devices, FIFOs and folders are refused
with a clear error and left as they are, and a new file gets the usual mode (umask), not 0600."""

from __future__ import annotations

import os
import stat

import pytest

from check_helpers import CASES

from tests.conftest import run_plx

pytest.importorskip("mujoco")

PENDULUM = CASES.parents[1] / "physics" / "models" / "simple_pendulum.openplx"
OPTIONS = {"trace": ("--duration", "0.1", "--trace"), "export": ("--export-mjcf",)}


def _write(kind: str, out) -> "object":
    return run_plx("check", *OPTIONS[kind], str(out), str(PENDULUM))


@pytest.mark.parametrize("kind", ["trace", "export"])
def test_a_symlink_is_written_through(tmp_path, kind):
    target = tmp_path / "target.out"
    target.write_text("keep\n")
    link = tmp_path / "link.out"
    link.symlink_to("target.out")
    r = _write(kind, link)
    assert r.returncode == 0, r.stderr
    assert link.is_symlink() and os.readlink(link) == "target.out"
    head = target.read_text()[:10]
    assert head.startswith("time," if kind == "trace" else "<mujoco")
    assert not list(tmp_path.glob(".*.plxtmp"))


@pytest.mark.parametrize("kind", ["trace", "export"])
def test_a_dangling_symlink_creates_its_target(tmp_path, kind):
    link = tmp_path / "link.out"
    link.symlink_to("made.out")
    assert _write(kind, link).returncode == 0
    assert link.is_symlink() and (tmp_path / "made.out").stat().st_size > 0


@pytest.mark.parametrize("kind", ["trace", "export"])
def test_a_fifo_is_refused_and_left_alone(tmp_path, kind):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    r = _write(kind, fifo)
    assert r.returncode == 2
    assert f"cannot write {fifo}: it is a FIFO (named pipe), not a regular file" in r.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode) and "Traceback" not in r.stderr


@pytest.mark.parametrize("kind", ["trace", "export"])
def test_a_folder_is_refused(tmp_path, kind):
    r = _write(kind, tmp_path)
    assert r.returncode == 2 and f"cannot write {tmp_path}: it is a folder" in r.stderr


@pytest.mark.parametrize("kind", ["trace", "export"])
def test_a_device_is_refused_and_stays_a_device(tmp_path, kind):
    """The reproduction check-trace-replaces-device-or-symlink: a copy of /dev/full (root only)."""
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    full = tmp_path / "full"
    try:
        os.mknod(full, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
    except PermissionError:
        pytest.skip("device nodes cannot be made here")
    link = tmp_path / "stdout"
    link.symlink_to(full)  # through a symlink, as /dev/stdout is one
    for out in (full, link):
        r = _write(kind, out)
        assert r.returncode == 2
        assert f"cannot write {out}: it is a character device, not a regular file" in r.stderr
    assert stat.S_ISCHR(os.lstat(full).st_mode) and link.is_symlink()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["full", "stdout"]


def test_a_new_file_gets_the_mode_the_umask_gives(tmp_path):
    out = tmp_path / "m.csv"
    old = os.umask(0o022)
    try:
        assert _write("trace", out).returncode == 0
    finally:
        os.umask(old)
    assert stat.S_IMODE(out.stat().st_mode) == 0o644


def test_a_replaced_file_keeps_its_mode_and_hard_links(tmp_path):
    out = tmp_path / "m.csv"
    out.write_text("old\n")
    os.chmod(out, 0o640)
    os.link(out, tmp_path / "other.csv")
    assert _write("trace", out).returncode == 0
    assert stat.S_IMODE(out.stat().st_mode) == 0o640
    assert (tmp_path / "other.csv").read_text().startswith("time,")
