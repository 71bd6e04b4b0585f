"""Every reproduction of ../shared/repros/round3/cache-*: the cached answer is the fresh one.

Runs are in-process (tests/cache/inproc.py: the replay first, as `plx` does) against the real
bundles; "fresh" is a run on an empty cache folder."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from tests.cache.inproc import run

REPO = Path(__file__).resolve().parents[2]
OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def _write(p: Path, text: str) -> None:
    with open(p, "w", encoding="utf-8", newline="") as fh:
        fh.write(text)


def _fresh(tmp_path, argv, cwd, env=None):
    fresh = tmp_path / f"fresh-{len(list(tmp_path.glob('fresh-*')))}"
    return run(argv, cwd, {**(env or {}), "PLX_CACHE_DIR": str(fresh)})


def _cached(tmp_path, argv, cwd, env=None):
    return run(argv, cwd, {**(env or {}), "PLX_CACHE_DIR": str(tmp_path / "cache")})


@pytest.mark.parametrize("text", [
    '\ufeffimport @"m.obj" as M\n\nScene is Physics3D.System:\n    v is M\n',  # cache-bom-import
    '\fimport @"m.obj" as M\n\nScene is Physics3D.System:\n    v is M\n',  # cache-formfeed-import
    '# c\rimport @"m.obj" as M\r\rScene is Physics3D.System:\r    v is M\r',  # cache-lonecr-import
], ids=["bom", "formfeed", "lonecr"])
def test_an_import_the_old_pattern_missed_is_a_dependency(tmp_path, text):
    d = tmp_path / "p"
    d.mkdir()
    _write(d / "m.obj", OBJ)
    _write(d / "f.openplx", text)
    argv = ["lint", "f.openplx"]
    assert _cached(tmp_path, argv, d)[0] == 0
    (d / "m.obj").unlink()
    got = _cached(tmp_path, argv, d)
    assert got[0] == 1 and "N006" in got[1]
    assert got == _fresh(tmp_path, argv, d)
    _write(d / "m.obj", OBJ)  # and back: a stale N006 is not kept either
    assert _cached(tmp_path, argv, d) == _fresh(tmp_path, argv, d) and _cached(tmp_path, argv, d)[0] == 0


def test_an_environment_variable_an_import_reads_is_a_dependency(tmp_path):
    """cache-lonecr-import, second half: `$"{MODELS}/m.obj"`."""
    d = tmp_path / "p"
    d.mkdir()
    _write(d / "m.obj", OBJ)
    _write(d / "e.openplx", '# c\rimport $"{MODELS}/m.obj" as M\r\rScene is Physics3D.System:\r    v is M\r')
    argv = ["lint", "-q", "e.openplx"]
    assert _cached(tmp_path, argv, d, {"MODELS": str(d)})[0] == 0
    for value in ("/nonexistent", None, str(d)):
        got = _cached(tmp_path, argv, d, {"MODELS": value})
        assert got == _fresh(tmp_path, argv, d, {"MODELS": value})
        assert got[0] == {"/nonexistent": 1, str(d): 0}.get(value, got[0])


def test_a_config_edited_keeping_size_and_mtime(tmp_path):
    """cache-config-same-mtime."""
    d = tmp_path / "p"
    d.mkdir()
    _write(d / "e.openplx", 'import @"missing.obj" as U\n\nScene is Physics3D.System:\n    v is U\n')
    _write(d / "plx.toml", 'ignore = ["N006"]\n')
    argv = ["lint", "-q", "e.openplx"]
    assert _cached(tmp_path, argv, d)[0] == 0
    st = (d / "plx.toml").stat()
    _write(d / "plx.toml", 'ignore = ["N007"]\n')
    os.utime(d / "plx.toml", ns=(st.st_atime_ns, st.st_mtime_ns))
    got = _cached(tmp_path, argv, d)
    assert got[0] == 1 and got == _fresh(tmp_path, argv, d)


def test_a_config_that_appears_in_a_parent_folder(tmp_path):
    d = tmp_path / "p" / "deep"
    d.mkdir(parents=True)
    _write(d / "e.openplx", 'import @"missing.obj" as U\n\nScene is Physics3D.System:\n    v is U\n')
    argv = ["lint", "-q", "e.openplx"]
    assert _cached(tmp_path, argv, d)[0] == 1
    _write(tmp_path / "p" / "pyproject.toml", '[tool.plx]\nignore = ["N006"]\n')
    got = _cached(tmp_path, argv, d)
    assert got[0] == 0 and got == _fresh(tmp_path, argv, d)
    (tmp_path / "p" / "pyproject.toml").unlink()
    assert _cached(tmp_path, argv, d)[0] == 1


def _user_bundle(tmp_path, symlinked: bool) -> tuple[Path, Path]:
    src = REPO / "examples" / "user_bundle"
    if not symlinked:
        proj = tmp_path / "ub"
        shutil.copytree(src, proj)
        return proj, proj / "Parts" / "Materials" / "Rubber.openplx"
    (tmp_path / "vendor").mkdir()
    shutil.copytree(src / "Parts", tmp_path / "vendor" / "Parts")
    proj = tmp_path / "proj"
    shutil.copytree(src / "Machines", proj / "Machines")
    (proj / "Parts").symlink_to("../vendor/Parts")
    for name in ("cart_scene.openplx", "plx.toml"):
        shutil.copy(src / name, proj / name)
    return proj, tmp_path / "vendor" / "Parts" / "Materials" / "Rubber.openplx"


@pytest.mark.parametrize("symlinked", [False, True], ids=["same-size-and-mtime", "symlinked-bundle"])
def test_an_edited_user_bundle_file(tmp_path, symlinked):
    """cache-userbundle-same-mtime (the edit keeps size and mtime) and cache-symlinked-bundle (the
    bundle folder is a symbolic link; an ordinary edit)."""
    proj, rubber = _user_bundle(tmp_path, symlinked)
    for argv in (["lint", "-q", "cart_scene.openplx"], ["lint", "-q", "--output-format", "text", "cart_scene.openplx"]):
        assert _cached(tmp_path, argv, proj)[0] == 0
    st = rubber.stat()
    text = rubber.read_text()
    _write(rubber, text.replace("const Rubber is", "const Rubbel is" if not symlinked else "const Rubberized is"))
    if not symlinked:
        os.utime(rubber, ns=(st.st_atime_ns, st.st_mtime_ns))
    for argv in (["lint", "-q", "cart_scene.openplx"], ["lint", "-q", "--output-format", "text", "cart_scene.openplx"]):
        got = _cached(tmp_path, argv, proj)
        assert got[0] == 1 and "N003" in got[1]
        assert got == _fresh(tmp_path, argv, proj)


def test_a_save_while_plx_runs_does_not_poison_the_cache(tmp_path, monkeypatch):
    """cache-race-key-vs-content: the file is saved right after plx read it; the result stored is
    that of the bytes read (read once), so linting the old content later is not answered with the
    new content's result."""
    from plxtools.cache import reads

    d = tmp_path / "p"
    d.mkdir()
    a = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: -1\n"
    b = a.replace("-1", "1")
    f = d / "w.openplx"
    _write(f, a)
    real = reads.read_bytes
    saved = []

    def read_then_save(path, *args, **kwargs):  # (read_bytes also takes the size limit)
        data = real(path, *args, **kwargs)
        if not saved and os.path.abspath(os.fspath(path)) == str(f):
            saved.append(1)
            _write(f, b)
        return data

    monkeypatch.setattr(reads, "read_bytes", read_then_save)
    first = _cached(tmp_path, ["lint", "-q", "w.openplx"], d)
    monkeypatch.setattr(reads, "read_bytes", real)
    assert saved and first[0] == 1  # the run linted what it read: content A
    assert _cached(tmp_path, ["lint", "-q", "w.openplx"], d) == _fresh(tmp_path, ["lint", "-q", "w.openplx"], d)
    _write(f, a)
    got = _cached(tmp_path, ["lint", "-q", "w.openplx"], d)
    assert got[0] == 1 and got == _fresh(tmp_path, ["lint", "-q", "w.openplx"], d)


def test_a_full_disk_leaves_no_temporary_files(tmp_path, monkeypatch):
    """cache-tmp-leak-full-disk: every cache write fails with ENOSPC; the answers stay right and
    nothing is left behind."""
    import errno

    from plxtools.cache import store

    d = tmp_path / "p"
    d.mkdir()
    _write(d / "w.openplx", "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: -1\n")
    real_write = os.write

    def full(fd, data):
        if len(data) > 64:  # the cache entries (the secret is 32 bytes)
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_write(fd, data)

    monkeypatch.setattr(store.os, "write", full)
    for argv in (["lint", "w.openplx"], ["fmt", "--check", "w.openplx"], ["lint", "w.openplx"]):
        got = _cached(tmp_path, argv, d)
        monkeypatch.setattr(store.os, "write", real_write)
        assert got == _fresh(tmp_path, argv, d)
        monkeypatch.setattr(store.os, "write", full)
    left = [p for p in (tmp_path / "cache").rglob("*") if p.name.endswith(".tmp")]
    assert not left
