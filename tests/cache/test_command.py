"""`plx cache dir|info|clean`, and the size cap (least recently used entries go first)."""

from __future__ import annotations

import os
import time

from tests.cache.inproc import run
from tests.conftest import run_plx


def test_dir_info_clean(tmp_path):
    cache = tmp_path / "cache"
    env = {"PLX_CACHE_DIR": str(cache)}
    d = tmp_path / "p"
    d.mkdir()
    (d / "a.openplx").write_text("Scene is Physics3D.System:\n")
    run(["lint", "a.openplx"], d, env)
    assert run_plx("cache", "dir", env=env).stdout.strip() == str(cache / "plxtools")
    info = run_plx("cache", "info", env=env).stdout
    assert "replays" in info and "results" in info and "programs" in info
    entries = [p for p in (cache / "plxtools").rglob("*") if p.is_file()]
    assert entries
    out = run_plx("cache", "clean", env=env)
    assert out.returncode == 0 and "removed" in out.stdout
    assert not [p for p in (cache / "plxtools").rglob("*") if p.is_file()]
    assert run_plx("cache", "bogus", env=env).returncode == 2


def test_the_cache_is_pruned_least_recently_used_first(tmp_path):
    cache = tmp_path / "cache"
    d = tmp_path / "p"
    d.mkdir()
    env = {"PLX_CACHE_DIR": str(cache)}
    for i in range(4):
        f = d / f"f{i}.openplx"
        f.write_text(f"Scene{i} is Physics3D.System:\n")
        run(["lint", f.name], d, env)
    entries = [p for p in (cache / "plxtools").rglob("*") if p.is_file()]
    old = time.time() - 3600
    for k, p in enumerate(entries):  # the order of use: entries[0] least recently
        os.utime(p, (old + k, old + k))
    total = sum(p.stat().st_size for p in entries)
    from plxtools.cache import folder, store

    saved = os.environ.get("PLX_CACHE_DIR")
    os.environ["PLX_CACHE_DIR"] = str(cache)
    try:
        folder.forget()
        removed = store.prune(cap=total - 1)
        assert store.prune(cap=total) == 0  # under the cap: nothing to do
    finally:
        os.environ["PLX_CACHE_DIR"] = saved
        folder.forget()
    assert removed >= 1 and not entries[0].exists() and entries[-1].exists()
    left = sum(p.stat().st_size for p in entries if p.exists())
    assert left <= (total - 1) * 0.8
    gone = [p for p in entries if not p.exists()]
    assert gone == entries[:len(gone)]  # the least recently used, in order
