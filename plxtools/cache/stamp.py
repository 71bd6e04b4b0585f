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
    out = []
    for d, dirs, files in os.walk(top):
        dirs[:] = sorted(x for x in dirs if x != "__pycache__" and not x.startswith("."))
        out.extend(os.path.join(d, n) for n in sorted(files) if n.endswith(_SUFFIXES))
    return out


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
    for p in files:
        sig = old.get(p)
        if sig is None or reads.is_racy(sig) or not reads.holds(["f", p, sig]):
            try:
                with reads.recording() as got:
                    reads.read_bytes(p)
                sig = got[0][2]
            except (OSError, IndexError):
                continue
        new[p] = sig
        h.update(f"{p[cut:]}\0{sig[5]}\n".encode())
    if use_index and (len(new) != len(old) or any(old.get(p) != s for p, s in new.items())):
        store.put_json("stamps", key, new)
    return h.hexdigest()


def code_stamp() -> str:
    """plxtools' version and the digest of its files (computed once per process)."""
    import plxtools

    top = os.path.dirname(os.path.realpath(plxtools.__file__))
    if top not in _stamps:
        _stamps[top] = f"{plxtools.__version__}-{tree_digest(top)}"
    return _stamps[top]
