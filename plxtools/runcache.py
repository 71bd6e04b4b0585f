"""Small per-file results kept between CLI runs (lint's diagnostics, fmt's "already formatted").

Keys are 256-bit BLAKE2b digests (`new_hash`) that the caller builds from everything a result depends on, starting
with `code_stamp()` (plxtools itself). Entries are one small pickle each under plx's cache folder
(PLX_CACHE_DIR); a broken or unreadable entry is a miss, a failed write is ignored.
"""

from __future__ import annotations

import os

from plxtools import __version__

_FORMAT = 2


def new_hash(data: bytes = b""):
    """A 256-bit BLAKE2b hash object. Taken from CPython's own `_blake2` module when it is there:
    `import hashlib` loads OpenSSL first (libcrypto and its config file), about a fifth of a cached
    one-file run's start-up."""
    try:
        from _blake2 import blake2b
    except ImportError:  # pragma: no cover - another Python implementation
        from hashlib import blake2b
    return blake2b(data, digest_size=32)

_STAMP: bytes | None = None


def cache_root() -> str:
    """plx's cache folder: the same as `model.versions.cache_dir()`, computed without importing
    the model (a replayed run, `plxtools.runmemo`, imports nothing else)."""
    base = os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or os.path.join(
        os.path.expanduser("~"), ".cache")
    return os.path.join(base, "plxtools")


def tree_stamp(root, suffixes: tuple[str, ...], h) -> None:
    """Feed the path, size and mtime of every file under `root` ending in `suffixes` to `h`."""
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__" and not d.startswith("."))
        for name in sorted(files):
            if name.endswith(suffixes):
                try:
                    st = os.stat(os.path.join(folder, name))
                except OSError:
                    continue
                h.update(f"{folder}/{name}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())


def code_stamp() -> bytes:
    """plxtools' version and the size and mtime of its source and data files (an edited checkout
    invalidates every entry)."""
    global _STAMP
    if _STAMP is None:
        h = new_hash(f"{_FORMAT}\0{__version__}\n".encode())
        tree_stamp(os.path.dirname(os.path.realpath(__file__)), (".py", ".lark", ".json", ".gz"), h)
        _STAMP = h.digest()
    return _STAMP


class Store:
    def __init__(self, name: str) -> None:
        from pathlib import Path

        self.folder = Path(cache_root()) / name

    def _file(self, key: str):
        return self.folder / key[:2] / f"{key[2:]}.pickle"

    def get(self, key: str | None):
        if key is None:
            return None
        import pickle

        try:
            with open(self._file(key), "rb") as fh:
                return pickle.load(fh)
        except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError, ValueError, TypeError,
                IndexError):
            return None

    def put(self, key: str | None, value) -> None:
        if key is None:
            return
        import pickle

        path = self._file(key)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
            with open(tmp, "wb") as fh:
                pickle.dump(value, fh, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, path)
        except (OSError, pickle.PicklingError, TypeError, AttributeError, RecursionError):
            pass
