"""A stamp of plxtools' own code: the digest of its source and data files' contents.

Every key starts with it, so an edited checkout (a contributor's change to model/symbols.py, a
new release) never meets an answer computed by other code. Hashing ~200 files at every start
would cost more than a replayed run, so the digests are kept in a stat index (an authenticated
entry of the cache, `reads`' racy-clean rule): only files whose stat changed are read again.
"""

from __future__ import annotations

import os
import time

from plxtools.cache import reads, store

_SUFFIXES = (".py", ".lark", ".json", ".gz", ".toml")
_stamps: dict[str, str] = {}


def package_files(top: str, folders: dict | None = None) -> list[str]:
    """Every source and data file under `top`, in a fixed order. With `folders`, each folder's
    stat (taken before it is listed) is kept there by its path relative to `top`."""
    out: list[str] = []
    subs = []
    if folders is not None:
        st = os.stat(top)
        folders[top] = [st.st_mtime_ns, st.st_ctime_ns, st.st_ino, st.st_dev, time.time_ns()]
    with os.scandir(top) as it:
        for e in sorted(it, key=lambda e: e.name):
            if e.is_dir(follow_symlinks=False):
                if e.name != "__pycache__" and not e.name.startswith("."):
                    subs.append(e.path)
            elif e.name.endswith(_SUFFIXES):
                out.append(e.path)
    for p in subs:
        out.extend(package_files(p, folders))
    return out


def _signature(path: str) -> list:
    """The stat index's record of one file: `reads`' signature (stat taken from the open file
    before reading, then the content digest), without a recording around it. A cold run signs
    every source file, so this stays a few system calls and one hash."""
    st, data = store.read_whole(path)
    return reads._sig(st, data)


def _same_listings(top: str, folders) -> bool:
    """Whether every folder of the last walk has the stat it had then, so that each still lists
    the same names: adding, removing or renaming an entry (a new subfolder included) sets its
    folder's mtime and ctime (POSIX), a user cannot set a ctime, and a folder changed within
    `reads.RACY_NS` of its record is racily clean: it is listed again. A replayed run checks
    ~80 folders with one stat each instead of listing them."""
    if not isinstance(folders, dict) or not folders:
        return False
    stat = os.stat
    racy = reads.RACY_NS
    prefix = top + os.sep  # (concatenated: os.path.join would be a third of a replay's stamp)
    for rel, (mtime, ctime, ino, dev, recorded) in folders.items():
        try:
            st = stat(prefix + rel if rel else top)
        except OSError:
            return False
        if not (st.st_mtime_ns == mtime and st.st_ctime_ns == ctime and st.st_ino == ino and st.st_dev == dev
                and recorded - max(mtime, ctime) > racy):
            return False
    return True


def tree_digest(top: str, use_index: bool = True) -> str:
    """The digest of every source file's path (relative to `top`) and content."""
    top = os.path.realpath(top)
    key = store.new_hash(f"{top}\0stat-index-2".encode()).hexdigest()
    index = store.get_data("stamps", key) if use_index else None
    try:
        old, old_folders = index["files"], index["folders"]
        if not isinstance(old, dict):
            raise TypeError
    except (TypeError, KeyError):
        old, old_folders = {}, None
    cut = len(top) + 1
    if _same_listings(top, old_folders):
        prefix = top + os.sep
        files = [prefix + rel for rel in old]  # (in the walk's order: the index keeps it)
        folders = old_folders
    else:
        walked: dict = {}
        files = package_files(top, walked)
        folders = {p[cut:]: v for p, v in walked.items()}
    new: dict = {}
    h = store.new_hash()
    stat = os.stat
    racy = reads.RACY_NS
    changed = folders is not old_folders
    for p in files:
        rel = p[cut:]
        sig = old.get(rel)
        try:
            st = stat(p)
        except OSError:
            changed = True
            continue
        if not (sig and st.st_mtime_ns == sig[1] and st.st_ctime_ns == sig[2] and st.st_size == sig[0]
                and st.st_ino == sig[3] and st.st_dev == sig[4] and sig[6] - max(sig[1], sig[2]) > racy):
            try:
                fresh = _signature(p)
            except OSError:
                changed = True
                continue
            changed = changed or fresh != sig
            sig = fresh
        new[rel] = sig
        h.update(f"{rel}\0{sig[5]}\n".encode())
    if use_index and (changed or len(new) != len(old)):
        store.put_data("stamps", key, {"files": new, "folders": folders})
    return h.hexdigest()


def code_stamp() -> str:
    """plxtools' version and the digest of its files (computed once per process)."""
    import plxtools

    top = os.path.dirname(os.path.realpath(plxtools.__file__))
    if top not in _stamps:
        _stamps[top] = f"{plxtools.__version__}-{tree_digest(top)}"
    return _stamps[top]
