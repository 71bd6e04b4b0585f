"""Replaying an unchanged run: `plx lint FILE` or `plx fmt --check FILE` again, nothing changed.

The per-file result cache (lint/resultcache.py) already skips parsing and checking an unchanged
file, but reaching it still costs the imports of a whole command (argparse, the config and its
TOML reader, the diagnostics): about as much again as Python's own start. This module is the step
before: `cli.entry` asks it first, and it answers from an entry of plx's cache (`plxtools.cache`)
written by the last identical run, importing nothing but the cache package.

An entry is found by a key of everything the command line decides: the arguments, the working
folder, plxtools itself (`cache.stamp.code_stamp`), the interpreter and its `sys.path`, the
environment variables plx reads (PLX_*, OPENPLX_*, AGX_*, colour and cache settings) and whether stdout
and stderr are terminals. It holds the run's output and exit code and every read the run made
(`cache.reads`: the files it linted or formatted, by content; the config files it found and the
ones it looked for and did not find; the bundle files the loader read or the record of them its
cache entry holds; the files imports name and the variables a `$"..."` path read). Each read is
checked again before the output is replayed.

Anything else on the command line (folders, stdin, `--fix`, `--diff`, `--no-cache`, unknown or
abbreviated options) is never replayed, and a run is recorded only when the command says so
(`allow`): when every file's result came from or went to the result cache. A missing, stale,
planted or unreadable entry is a miss: the command runs as usual.
"""

from __future__ import annotations

import os
import sys

_FORMAT = 3
# per command: options without a value and options with one that change only what is printed or
# what is decided from the key's inputs, and the options a replayed run must have
_COMMANDS = {
    "lint": (frozenset({"-q", "--quiet", "--exit-zero", "--statistics"}),
             frozenset({"--output-format", "--select", "--ignore", "--bundle-path", "--openplx-version"}),
             frozenset()),
    "fmt": (frozenset({"-q", "--quiet", "--check"}), frozenset(), frozenset({"--check"})),  # never writes
}
_ENV = ("XDG_CACHE_HOME", "XDG_CONFIG_HOME", "HOME", "NO_COLOR", "FORCE_COLOR", "TERM", "COLUMNS", "LINES",
        "PYTHONPATH")

_allowed = False  # the command's word that this run may be replayed


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
    from plxtools.cache.stamp import code_stamp
    from plxtools.cache.store import new_hash

    env = sorted((k, v) for k, v in os.environ.items()
                 if k.startswith(("PLX_", "OPENPLX_", "AGX_")) or k in _ENV)
    tty = tuple(os.isatty(fd) for fd in (1, 2))
    h = new_hash(repr((_FORMAT, code_stamp(), sys.executable, sys.path, os.getcwd(), argv, env, tty)).encode())
    return h.hexdigest()


def replay(argv: list[str]) -> int | None:
    """Write the recorded output of this command line and return its exit code, or None (a miss)."""
    if candidate(argv) is None:
        return None
    from plxtools.cache import reads, store

    entry = store.get_data("replays", _key(argv))
    try:
        deps, out, err, code = entry["deps"], entry["out"], entry["err"], entry["code"]
        if not (isinstance(out, str) and isinstance(err, str) and code in (0, 1)) or not reads.all_hold(deps):
            return None
    except (TypeError, KeyError):
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
    """Before running a candidate command line: capture its output and record its reads. Returns
    a token for `finish`."""
    global _allowed
    if candidate(argv) is None:
        return None
    from plxtools.cache import reads

    _allowed = False
    rec = reads.recording()
    deps = rec.__enter__()
    for a in argv[1:]:  # where each named path leads (a symbolic link on the way retargeted)
        if not a.startswith("-"):
            reads.realpath(a)
    reads.realpath(".")
    out, err = _Tee(sys.stdout), _Tee(sys.stderr)
    sys.stdout, sys.stderr = out, err
    return argv, out, err, rec, deps


def finish(token, code: int) -> None:
    """After the run: restore the streams and, if the command allowed it, write the entry."""
    global _allowed
    if token is None:
        return
    argv, out, err, rec, deps = token
    sys.stdout, sys.stderr = out._stream, err._stream
    rec.__exit__(None, None, None)
    allowed, _allowed = _allowed, False
    if not allowed or code not in (0, 1):
        return
    from plxtools.cache import reads, store

    store.put_data("replays", _key(argv), {"deps": reads.dedupe(deps), "out": "".join(out.parts),
                                           "err": "".join(err.parts), "code": code})


def allow() -> None:
    """The command's word that this run may be replayed: everything it read was recorded."""
    global _allowed
    _allowed = True
