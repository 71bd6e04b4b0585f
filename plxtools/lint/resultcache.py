"""Per-file lint results kept between runs, as ruff does: an unchanged file is not re-checked.

A result is stored under a key made of everything it depends on:

- the file's path and bytes;
- its configuration (every field of the Config in effect, --select/--ignore included);
- the bundle set (its folders and version) and the size and mtime of every .openplx file in the
  user's bundle folders (of a released official version, its bundles' config files: a release is
  not edited in place, and reinstalling it rewrites them);
- plxtools itself (its version and the size and mtime of its source files).

Only loose files are cached: a file inside a bundle is named by its neighbours (and loads them),
so it is always checked. A result with an unknown name (N001/N003) is not stored either: its help
may name a bundle folder found near the file, which the key does not cover. `--fix`, `--diff` and
stdin runs neither read nor write the cache; `--no-cache` turns it off. Entries live in plx's
cache folder (PLX_CACHE_DIR), one small pickle per file version, all in one folder: on ext4 the
first file written into a new folder costs about as much CPU as creating the folder (each about
0.9 ms here), so a run into an empty cache (a CI job, a benchmark) paid about 1.8 ms per file with
one sub-folder per key prefix, and pays about 0.2 ms with one folder.

On a hit nothing is parsed and the bundle program is not loaded: a warm one-file run imports
neither lark nor the model.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from plxtools import envpath
from plxtools.runcache import Store, code_stamp, new_hash, tree_stamp

_NOT_STORED = frozenset({"N001", "N003"})
_IMPORT = re.compile(rb'(?m)^[ \t]*import[ \t]+([@$])"([^"\r\n]*)"')


def _import_stamp(path: Path, data: bytes, h) -> None:
    """The files a file imports (`import @"wheel.obj"`): whether each exists, its size and mtime,
    and the environment variables a `$"..."` path reads, so creating the file updates the result."""
    folder = path.resolve().parent
    for m in _IMPORT.finditer(data):
        text = m.group(2).decode("utf-8", "replace")
        if m.group(1) == b"$":
            h.update(repr([(n, os.environ.get(n)) for n in envpath.variables(text)]).encode())
            text, _ = envpath.expand(text)
        try:
            st = (folder / text).stat()
            h.update(f"\0{text}\0{st.st_size}\0{st.st_mtime_ns}".encode())
        except (OSError, ValueError):
            h.update(f"\0{text}\0missing".encode())


def imported_files(path: Path, data: bytes) -> list[str] | None:
    """The files a file imports with `import @"..."` (as `_import_stamp` finds them), or None when
    one is a `$"..."` path (it depends on the environment)."""
    if b"import" not in data:
        return []
    folder = path.resolve().parent
    out = []
    for m in _IMPORT.finditer(data):
        if m.group(1) == b"$":
            return None
        out.append(str(folder / m.group(2).decode("utf-8", "replace")))
    return out


def _in_bundle(path: Path, stop_at: set) -> bool:
    """model.bundles.find_user_bundle_root(...) is not None, without importing the model (and lark)."""
    return _folder_in_bundle(path.resolve().parent, stop_at)


def _folder_in_bundle(folder: Path, stop_at: set) -> bool:
    for d in (folder, *folder.parents):
        if d in stop_at:
            return False
        if (d / "config.openplx").is_file():
            return True
    return False


class _FlatStore(Store):
    """The run cache's store with every entry directly in its folder (see the module's notes)."""

    def _file(self, key: str):
        return self.folder / f"{key}.pickle"


class ResultCache:
    def __init__(self, bundle_set) -> None:
        self.store = _FlatStore("lint-results")
        self.bundle_set = bundle_set
        self.official_root = bundle_set.official_root.resolve() if bundle_set.official_root else None
        self._stamp: bytes | None = None
        self._bundle_folders: dict[Path, bool] = {}  # folder -> inside a bundle (asked once per run)

    def _run_stamp(self) -> bytes:
        """The part of every key that is the same for the whole run (computed once, lazily)."""
        if self._stamp is None:
            h = new_hash(code_stamp())
            h.update(f"\0{self.bundle_set.key()}\0{self.bundle_set.official_version}\n".encode())
            official = self.bundle_set.official_root
            if official is not None and self.bundle_set.official_version:
                # a released version (installed package or plx's cache) is not edited in place: a
                # reinstall rewrites its bundles' config files, so those stand for the whole tree
                for cfg in sorted(Path(official).glob("*/config.openplx")):
                    st = cfg.stat()
                    h.update(f"{cfg}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())
            elif official is not None:
                tree_stamp(Path(official), (".openplx",), h)
            for src in self.bundle_set.sources:  # the user's own bundle folders: every file
                tree_stamp(Path(src.path), (".openplx",), h)
            self._stamp = h.digest()
        return self._stamp

    def key(self, path: Path, cfg) -> str | None:
        """The key of this file's result now, or None when it is not cached (a bundle file, an
        unreadable file)."""
        if path.name == "config.openplx":
            return None
        try:
            resolved = path.resolve()
            folder = resolved.parent
            inside = self._bundle_folders.get(folder)
            if inside is None:
                stop = {self.official_root} if self.official_root is not None else set()
                inside = self._bundle_folders[folder] = _folder_in_bundle(folder, stop)
            if inside:
                return None
            data = path.read_bytes()
        except OSError:
            return None
        h = new_hash(self._run_stamp())
        h.update(f"\0{path}\0{resolved}\0{cfg!r}\0".encode())
        h.update(data)
        if b"import" in data:
            _import_stamp(path, data, h)
        return h.hexdigest()

    def get(self, key: str | None):
        value = self.store.get(key)
        return value if isinstance(value, list) else None

    @staticmethod
    def stores(diagnostics: list) -> bool:
        """Whether a result with these diagnostics is kept (see the module's notes)."""
        return not any(d.code in _NOT_STORED for d in diagnostics)

    def put(self, key: str | None, diagnostics: list) -> None:
        if key is None or not self.stores(diagnostics):
            return
        self.store.put(key, diagnostics)
