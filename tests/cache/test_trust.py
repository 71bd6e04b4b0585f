"""Nothing in the cache folder is trusted (cache-pickle-exec): a planted entry of any kind neither
runs code nor changes an answer; a folder or secret that is not private to the user is not used."""

from __future__ import annotations

import os
import pickle
import stat
from pathlib import Path

import pytest

from tests.cache.inproc import run

BAD = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: -1\n"
FORGED = b'{"deps":[],"out":"All checks passed in 1 file.\\n","err":"","code":0}'


class _Exec:
    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"echo PWNED > {self.marker}",))


def _project(tmp_path) -> Path:
    d = tmp_path / "p"
    d.mkdir()
    (d / "a.openplx").write_text(BAD)
    return d


def _plant(cache: Path, marker: Path) -> int:
    """Overwrite every entry, and plant files where older versions of plx read pickles."""
    root = cache / "plxtools"
    n = 0
    evil = pickle.dumps(_Exec(marker))
    for p in [p for p in root.rglob("*") if p.is_file()]:
        p.write_bytes(evil if p.parent.name in ("programs", "results") else (
            bytes(32) + FORGED if p.parent.name == "replays" else evil))
        n += 1
    for legacy in ("grammar.lark-cache", "official-00000000-00000000-465.pickle", "lint-results/x.pickle"):
        (root / legacy).parent.mkdir(parents=True, exist_ok=True)
        (root / legacy).write_bytes(evil)
    return n


def test_planted_entries_neither_run_code_nor_change_the_answer(tmp_path):
    d = _project(tmp_path)
    cache = tmp_path / "cache"
    env = {"PLX_CACHE_DIR": str(cache)}
    fresh = run(["lint", "-q", "a.openplx"], d, {"PLX_CACHE_DIR": str(tmp_path / "fresh")})
    assert fresh[0] == 1 and "A032" in fresh[1]
    for argv in (["lint", "-q", "a.openplx"], ["fmt", "--check", "a.openplx"], ["lint", "a.openplx"]):
        run(argv, d, env)
    marker = tmp_path / "pwned"
    assert _plant(cache, marker) >= 5
    for argv in (["lint", "-q", "a.openplx"], ["lint", "-q", "--output-format", "text", "a.openplx"]):
        assert run(argv, d, env) == run(argv, d, {"PLX_CACHE_DIR": str(tmp_path / f"fresh{len(argv)}")})
    assert run(["lint", "-q", "a.openplx"], d, env) == fresh
    assert not marker.exists()


def test_an_entry_made_with_another_secret_is_not_believed(tmp_path, monkeypatch):
    """A cache restored from another machine (or planted by someone who can write the folder but
    not read the secret): its entries are misses, then rewritten."""
    d = _project(tmp_path)
    env = {"PLX_CACHE_DIR": str(tmp_path / "cache")}
    other = tmp_path / "other-secret"
    first = run(["lint", "-q", "a.openplx"], d, {**env, "PLX_CACHE_SECRET_FILE": str(other)})
    (d / "a.openplx").write_text(BAD.replace("-1", "1"))
    clean = run(["lint", "-q", "a.openplx"], d, {**env, "PLX_CACHE_SECRET_FILE": str(other)})
    (d / "a.openplx").write_text(BAD)
    # the other secret's entries say "clean" for nothing of ours; ours answers A032
    assert clean[0] == 0 and first[0] == 1
    assert run(["lint", "-q", "a.openplx"], d, env) == first


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="POSIX permissions")
def test_a_folder_writable_by_others_is_not_used(tmp_path):
    d = _project(tmp_path)
    cache = tmp_path / "cache"
    (cache / "plxtools").mkdir(parents=True)
    os.chmod(cache / "plxtools", 0o777)
    got = run(["lint", "-q", "a.openplx"], d, {"PLX_CACHE_DIR": str(cache)})
    assert got[0] == 1 and "A032" in got[1]
    assert got[2].count("warning") == 1 and "can be written by other users" in got[2]
    assert not [p for p in (cache / "plxtools").rglob("*") if p.is_file()]  # nothing written


@pytest.mark.skipif(not hasattr(os, "getuid") or os.getuid() != 0, reason="needs root to give a folder away")
def test_a_folder_owned_by_someone_else_is_not_used(tmp_path):
    d = _project(tmp_path)
    cache = tmp_path / "cache"
    (cache / "plxtools").mkdir(parents=True)
    os.chown(cache / "plxtools", 65534, -1)
    got = run(["lint", "-q", "a.openplx"], d, {"PLX_CACHE_DIR": str(cache)})
    assert got[0] == 1 and "owned by another user" in got[2]


def test_the_cache_folder_and_secret_are_private(tmp_path):
    d = _project(tmp_path)
    cache = tmp_path / "cache"
    secret = tmp_path / "cfg" / "secret"
    run(["lint", "a.openplx"], d, {"PLX_CACHE_DIR": str(cache), "PLX_CACHE_SECRET_FILE": str(secret)})
    assert stat.S_IMODE((cache / "plxtools").stat().st_mode) == 0o700
    assert stat.S_IMODE(secret.stat().st_mode) == 0o600 and secret.stat().st_size == 32
    os.chmod(secret, 0o644)  # readable by others: not a secret any more, so the run is uncached
    got = run(["lint", "a.openplx"], d, {"PLX_CACHE_DIR": str(cache), "PLX_CACHE_SECRET_FILE": str(secret)})
    assert got[0] == 1 and "not using the cache secret" in got[2]
