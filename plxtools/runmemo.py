"""Replaying an unchanged run: `plx lint FILE` or `plx fmt --check FILE` again, nothing changed.

The per-file result cache (lint/resultcache.py) already skips parsing and checking an unchanged
file, but reaching it still costs the imports of a whole command (argparse, the config and its
TOML reader, the dataclasses of diagnostics, pickle): about as much again as Python's own start.
This module is the step before: `cli.entry` asks it first, and it answers from a small entry
written by the last identical run, importing nothing but `os`, `sys`, `marshal` and `_blake2`.

An entry is found by a key of everything the command line decides: the arguments, the working
folder, plxtools itself (`runcache.code_stamp`), the interpreter and its `sys.path`, the
environment variables plx reads (PLX_*, OPENPLX_*, AGX_*, colour and cache settings) and whether stdout
and stderr are terminals. It holds the run's output and exit code and the list of what else the
run depended on, each checked again before the output is replayed:

- each linted file's bytes (a BLAKE2b digest, not its mtime) and where its path leads (symbolic
  links resolved);
- in every folder from each linted file (and from the working folder) up to the root, the files
  plx looks for there: `plx.toml`, `pyproject.toml` (the configuration) and `config.openplx` (a
  bundle the file belongs to, or a version pin), by their size, mtime and inode, or their absence;
- the bundle set: the official bundles' folder and their config files (a released version) or
  every file (otherwise), the folder holding them (another version installed beside), an
  `openplxbundles` earlier on `sys.path`, and every file of the user's bundle folders;
- the files a linted file imports (`import @"..."`).

Anything else on the command line (folders, stdin, `--fix`, `--diff`, `--no-cache`, unknown or
abbreviated options) is never replayed, and a run is only recorded when every file's result came
from or went to the result cache under the same rules (a file inside a bundle, or with an unknown
name whose help may name a nearby folder, is checked every time). A missing, stale or unreadable
entry is a miss: the command runs as usual. `--no-cache` neither reads nor writes entries.
"""

from __future__ import annotations

import os
import sys

_FORMAT = 1
# per command: options without a value and options with one that change only what is printed or
# what is decided from the key's inputs, and the options a replayed run must have
_COMMANDS = {
    "lint": (frozenset({"-q", "--quiet", "--exit-zero", "--statistics"}),
             frozenset({"--output-format", "--select", "--ignore", "--bundle-path", "--openplx-version"}),
             frozenset()),
    "fmt": (frozenset({"-q", "--quiet", "--check"}), frozenset(), frozenset({"--check"})),  # never writes
}
_ENV = ("XDG_CACHE_HOME", "HOME", "NO_COLOR", "FORCE_COLOR", "TERM", "COLUMNS", "LINES", "PYTHONPATH")
_CONFIG_NAMES = ("plx.toml", "pyproject.toml", "config.openplx")

_record: list | None = None  # what the run depended on, once the command says it may be replayed


def candidate(argv: list[str]) -> list[str] | None:
    """The files of a command line that may be replayed, or None."""
    spec = _COMMANDS.get(argv[0]) if argv else None
    if spec is None or not spec[2] <= set(argv):
        return None
    flags, values, _needed = spec
    files: list[str] = []
    i = 1
    while i < len(argv):
        a = argv[i]
        if a.startswith("-"):
            name = a.split("=", 1)[0]
            if a in flags:
                pass
            elif name in values:
                if "=" not in a:
                    i += 1
                    if i >= len(argv):
                        return None
            else:
                return None
        else:
            try:
                st = os.stat(a)
            except (OSError, ValueError):
                return None
            if not (st.st_mode & 0o170000 == 0o100000 and a.endswith(".openplx")):
                return None  # a folder (its listing is not a dependency) or something odd
            files.append(a)
        i += 1
    return files or None


def _key(argv: list[str]) -> str:
    from plxtools.runcache import code_stamp, new_hash

    h = new_hash(code_stamp())
    env = sorted((k, v) for k, v in os.environ.items()
                 if k.startswith(("PLX_", "OPENPLX_", "AGX_")) or k in _ENV)
    tty = tuple(os.isatty(fd) for fd in (1, 2))
    h.update(repr((_FORMAT, sys.executable, sys.path, os.getcwd(), argv, env, tty)).encode())
    return h.hexdigest()


def _entry_path(key: str) -> str:
    from plxtools.runcache import cache_root

    return os.path.join(cache_root(), "runs", key[:2], key[2:])


def _sig(path: str):
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    return (st.st_mtime_ns, st.st_size, st.st_ino)


def _digest(path: str):
    from plxtools.runcache import new_hash

    try:
        with open(path, "rb") as fh:
            return new_hash(fh.read()).digest()
    except OSError:
        return None


def _tree(folder: str) -> bytes:
    from plxtools.runcache import new_hash, tree_stamp

    h = new_hash()
    tree_stamp(folder, (".openplx",), h)
    return h.digest()


def _holds(dep: tuple) -> bool:
    kind, path, value = dep
    if kind == "stat":
        return _sig(path) == value
    if kind == "bytes":
        return _digest(path) == value
    if kind == "tree":
        return _tree(path) == value
    if kind == "real":
        return os.path.realpath(path) == value
    return False


def replay(argv: list[str]) -> int | None:
    """Write the recorded output of this command line and return its exit code, or None (a miss)."""
    if candidate(argv) is None:
        return None
    import marshal

    try:
        with open(_entry_path(_key(argv)), "rb") as fh:
            fmt, deps, out, err, code = marshal.load(fh)
        if fmt != _FORMAT or not all(_holds(tuple(d)) for d in deps) or not isinstance(code, int):
            return None
    except Exception:  # noqa: BLE001 - an unreadable or foreign entry is a miss, never an error
        return None
    if err:
        sys.stderr.write(err)
    if out:
        sys.stdout.write(out)
    return code


# ---------------------------------------------------------------------------- recording


class _Tee:
    """A text stream that passes everything on and keeps a copy."""

    def __init__(self, stream) -> None:
        self._stream = stream
        self.parts: list[str] = []

    def write(self, s: str) -> int:
        self.parts.append(s)
        return self._stream.write(s)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def start(argv: list[str]):
    """Before running a candidate command line: capture its output. Returns a token for `finish`."""
    if candidate(argv) is None:
        return None
    out, err = _Tee(sys.stdout), _Tee(sys.stderr)
    sys.stdout, sys.stderr = out, err
    return argv, out, err


def finish(token, code: int) -> None:
    """After the run: restore the streams and, if the command allowed it (`allow`), write the entry."""
    global _record
    if token is None:
        return
    argv, out, err = token
    sys.stdout, sys.stderr = out._stream, err._stream
    deps, _record = _record, None
    if deps is None or code not in (0, 1):
        return
    import marshal

    try:
        path = _entry_path(_key(argv))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "wb") as fh:
            marshal.dump((_FORMAT, deps, "".join(out.parts), "".join(err.parts), code), fh)
        os.replace(tmp, path)
    except (OSError, ValueError):
        pass


def allow(files, bundle_set=None, imports: list[str] = ()) -> None:
    """The command's word that this run may be replayed: record what it depended on. `files` are the
    files it read, `imports` the files they import (`import @"..."`), `bundle_set` the bundles used
    (None: none, as for `plx fmt`)."""
    global _record
    deps: list[tuple] = []
    folders: set[str] = set()
    for f in files:
        p = os.fspath(f)
        deps.append(("bytes", p, _digest(p)))
        deps.append(("real", p, os.path.realpath(p)))  # a symbolic link on the way that now points elsewhere
        folders.add(os.path.dirname(os.path.realpath(p)))
        folders.add(os.path.dirname(os.path.abspath(p)))
    folders.add(os.path.realpath(os.getcwd()))
    seen: set[str] = set()
    for start_at in sorted(folders):
        d = start_at
        while d not in seen:  # the config and bundle files plx looks for above a file, there or not
            seen.add(d)
            for name in _CONFIG_NAMES:
                c = os.path.join(d, name)
                deps.append(("stat", c, _sig(c)))
            parent = os.path.dirname(d)
            if parent == d:
                break
            d = parent
    official = bundle_set.official_root if bundle_set is not None else None
    if official is not None:
        root = os.fspath(official)
        site = os.path.dirname(root)
        deps.append(("stat", root, _sig(root)))
        deps.append(("stat", site, _sig(site)))  # another version installed there
        for entry in sys.path:  # a package of that name earlier on the path would be found first
            entry = os.path.abspath(entry or os.curdir)
            if entry == site:
                break
            deps.append(("stat", os.path.join(entry, "openplxbundles"), _sig(os.path.join(entry, "openplxbundles"))))
        if bundle_set.official_version:  # a release is not edited in place (as lint/resultcache.py)
            for name in sorted(os.listdir(root)):
                c = os.path.join(root, name, "config.openplx")
                if os.path.exists(c):
                    deps.append(("stat", c, _sig(c)))
        else:
            deps.append(("tree", root, _tree(root)))
    for src in bundle_set.sources if bundle_set is not None else ():
        deps.append(("tree", os.fspath(src.path), _tree(os.fspath(src.path))))
    if bundle_set is not None:  # an AGX installed (or removed) since: model/agx.py finds it
        from plxtools.model.agx import usual_folders

        for where in [os.path.dirname(p) for p in usual_folders()] + [os.path.join(os.path.abspath(e or os.curdir),
                                                                                    "agx") for e in sys.path]:
            deps.append(("stat", where, _sig(where)))
    for p in imports:
        deps.append(("stat", p, _sig(p)))
    _record = deps
