"""plxtools' own code is part of every key (the bundle program cache used to ignore it): its stamp
is a digest of its files' contents, kept cheap by a stat index that cannot be fooled."""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

from plxtools.cache import reads, stamp
from tests.cache.stamps import tree_digest as _digest

PKG = Path(stamp.__file__).resolve().parents[1]


def test_an_edit_keeping_size_and_mtime_changes_the_stamp(tmp_path, monkeypatch):
    tree = tmp_path / "plxtools"
    shutil.copytree(PKG / "cache", tree / "cache")
    (tree / "model").mkdir()
    f = tree / "model" / "symbols.py"
    f.write_text("X = 1\n")
    cache = tmp_path / "c"
    first = _digest(tree, cache)
    monkeypatch.setattr(reads, "RACY_NS", -10**12)  # every stat trusted: only the ctime can tell
    assert _digest(tree, cache) == first  # the stat index answers
    st = f.stat()
    time.sleep(0.02)  # past the file system's clock tick: the edit gets a new ctime
    f.write_text("X = 2\n")
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))
    assert _digest(tree, cache) != first
    (tree / "model" / "new.py").write_text("")
    assert len({first, _digest(tree, cache)}) == 2


def test_a_planted_index_does_not_change_the_stamp(tmp_path):
    tree = tmp_path / "plxtools"
    shutil.copytree(PKG / "cache", tree / "cache")
    cache = tmp_path / "c"
    truth = _digest(tree, cache)
    for p in (cache / "plxtools" / "stamps").iterdir():
        p.write_bytes(bytes(32) + b'{"cache/store.py": [1, 2, 3, 4, 5, "00", 6]}')
    assert _digest(tree, cache) == truth
