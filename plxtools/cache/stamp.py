"""A stamp of plxtools' own code: the digest of its source and data files' contents.

Every key starts with it, so an edited checkout (a contributor's change to model/symbols.py, a
new release) never meets an answer computed by other code. Hashing ~200 files at every start
would cost more than a replayed run, so the digests are kept in a stat index (an authenticated
entry of the cache, `reads`' racy-clean rule): only files whose stat changed are read again.
"""

from __future__ import annotations

import os

from plxtools.cache import reads, store

_SUFFIXES = (".py", ".lark", ".json", ".gz", ".toml")
_stamps: dict[str, str] = {}


def package_files(top: str) -> list[str]:
    out: list[str] = []
    subs = []
    with os.scandir(top) as it:
        for e in sorted(it, key=lambda e: e.name):
            if e.is_dir(follow_symlinks=False):
                if e.name != "__pycache__" and not e.name.startswith("."):
                    subs.append(e.path)
            elif e.name.endswith(_SUFFIXES):
                out.append(e.path)
    for p in subs:
        out.extend(package_files(p))
    return out


def _signature(path: str) -> list:
    """The stat index's record of one file: `reads`' signature (stat taken from the open file
    before reading, then the content digest), without a recording around it. A cold run signs
    every source file, so this stays a few system calls and one hash."""
    st, data = store.read_whole(path)
    return reads._sig(st, data)


def tree_digest(top: str, use_index: bool = True) -> str:
    """The digest of every source file's path (relative to `top`) and content."""
    top = os.path.realpath(top)
    files = package_files(top)
    key = store.new_hash(f"{top}\0stat-index".encode()).hexdigest()
    index = store.get_json("stamps", key) if use_index else None
    old = index if isinstance(index, dict) else {}
    new: dict = {}
    h = store.new_hash()
    cut = len(top) + 1
    stat = os.stat
    racy = reads.RACY_NS
    changed = False
    for p in files:
        rel = p[cut:]
        sig = old.get(rel)
        try:
            st = stat(p)
        except OSError:
            continue
        if not (sig and st.st_mtime_ns == sig[1] and st.st_ctime_ns == sig[2] and st.st_size == sig[0]
                and st.st_ino == sig[3] and st.st_dev == sig[4] and sig[6] - max(sig[1], sig[2]) > racy):
            try:
                fresh = _signature(p)
            except OSError:
                continue
            changed = changed or fresh != sig
            sig = fresh
        new[rel] = sig
        h.update(f"{rel}\0{sig[5]}\n".encode())
    if use_index and (changed or len(new) != len(old)):
        store.put_json("stamps", key, new)
    return h.hexdigest()


def code_stamp() -> str:
    """plxtools' version and the digest of its files (computed once per process)."""
    import plxtools

    top = os.path.dirname(os.path.realpath(plxtools.__file__))
    if top not in _stamps:
        _stamps[top] = f"{plxtools.__version__}-{tree_digest(top)}"
    return _stamps[top]
