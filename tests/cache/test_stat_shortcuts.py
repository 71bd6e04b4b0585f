"""The replay's stat shortcuts cannot miss a change: a folder's listing is believed from its stat
(entries added, removed or renamed set the folder's mtime and ctime), and the code stamp skips
listing plxtools' folders when their stats are the ones of its last walk."""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

from plxtools.cache import reads, stamp
from tests.cache.stamps import tree_digest as _digest

PKG = Path(stamp.__file__).resolve().parents[1]


def _recorded(path: Path) -> list:
    with reads.recording() as deps:
        reads.listdir(path)
    return deps


def test_a_listing_is_believed_from_the_folder_stat_only_while_nothing_was_added(tmp_path, monkeypatch):
    (tmp_path / "a.openplx").write_text("")
    deps = _recorded(tmp_path)
    assert [d[0] for d in deps] == ["d"]
    monkeypatch.setattr(reads, "RACY_NS", -10**12)  # every stat trusted
    listed = []
    real = os.listdir
    monkeypatch.setattr(os, "listdir", lambda p: listed.append(p) or real(p))
    assert reads.all_hold(deps) and not listed  # the stat answered
    time.sleep(0.02)
    (tmp_path / "b.openplx").write_text("")
    assert not reads.all_hold(deps)
    (tmp_path / "b.openplx").unlink()
    assert reads.all_hold(deps) and listed  # a new stat, the same names: listed, and it holds
    (tmp_path / "a.openplx").rename(tmp_path / "c.openplx")
    assert not reads.all_hold(deps)


def test_a_listing_recorded_while_racy_is_listed_again(tmp_path, monkeypatch):
    deps = _recorded(tmp_path)  # the folder was just made: racily clean
    listed = []
    real = os.listdir
    monkeypatch.setattr(os, "listdir", lambda p: listed.append(p) or real(p))
    assert reads.all_hold(deps) and listed


def test_the_listing_digest_is_by_names_not_stats(tmp_path):
    (tmp_path / "a.openplx").write_text("")
    first = reads.content_digest(_recorded(tmp_path))
    time.sleep(0.02)
    (tmp_path / "b").write_text("")
    (tmp_path / "b").unlink()
    assert reads.content_digest(_recorded(tmp_path)) == first


def test_the_code_stamp_sees_a_new_file_in_a_folder_whose_listing_it_skipped(tmp_path, monkeypatch):
    tree = tmp_path / "plxtools"
    shutil.copytree(PKG / "cache", tree / "cache")
    (tree / "model" / "deep").mkdir(parents=True)
    cache = tmp_path / "c"
    first = _digest(tree, cache)
    monkeypatch.setattr(reads, "RACY_NS", -10**12)
    scanned = []
    real = os.scandir
    monkeypatch.setattr(os, "scandir", lambda p: scanned.append(p) or real(p))
    assert _digest(tree, cache) == first and not scanned  # folders by stat, files by stat
    time.sleep(0.02)
    (tree / "model" / "deep" / "new.py").write_text("X = 1\n")
    second = _digest(tree, cache)
    assert second != first and scanned
    assert _digest(tree, cache) == second
    shutil.rmtree(tree / "model" / "deep")
    assert _digest(tree, cache) == _digest(tree, tmp_path / "fresh") != second
