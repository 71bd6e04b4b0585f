"""Which .openplx files a command works on: explicit files, and folders walked with the config's
excludes. Shared by lint, fmt and check.

Only regular files are ever taken. A FIFO, a device or a socket (or a symlink to one) named on the
command line is a usage error naming it: a gate must never pass a file it did not read. Met while
walking a folder (a repository can ship a link to /dev/zero), it is named in a warning and skipped;
it is never opened, so it can neither block (a FIFO) nor be read without end (a device)."""

from __future__ import annotations

import os
import stat
import sys
from collections.abc import Callable
from pathlib import Path

from plxtools.cache.reads import what_is
from plxtools.config import DEFAULT_EXCLUDE, config_for
from plxtools.diagnostics import printable


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


def warn_skipped(path: Path, why: str) -> None:
    print(printable(f"plx: warning: {path}: {why}; skipped"), file=sys.stderr)


def _special(path: Path) -> str | None:
    """What `path` is when it is there and neither a regular file nor a folder (symlinks followed),
    else None. A stat, never an open."""
    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):
        return None  # missing or dangling: reading it reports why (E001)
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return None
    return what_is(mode)


def discover(paths: list[str], *, use_exclude: str = "lint", suffixes: tuple[str, ...] = (".openplx",),
             skipped: Callable[[Path, str], None] = warn_skipped) -> list[Path]:
    """Expand folders into their .openplx files (`suffixes`: `plx migrate` also finds the .brick
    files of before OpenPLX 0.15); explicit files are always taken. `skipped` hears of every
    non-regular file met in a folder."""
    out: list[Path] = []
    seen: set[Path] = set()
    for raw in paths:
        p = Path(raw)
        if not p.exists():
            raise UsageError(printable(f"{raw}: no such file or folder"))
        what = _special(p)
        if what is not None:
            raise UsageError(printable(f"{raw}: it is {what}, not a regular file: not read"))
        if p.is_file():
            if p not in seen:
                seen.add(p)
                out.append(p)
            continue
        # a folder named on the command line is walked even if an exclude pattern matches it;
        # patterns still skip what they match below it
        root_excluded = config_for(p).is_excluded(p)
        for dirpath, dirnames, filenames in os.walk(p):
            dirnames[:] = sorted(d for d in dirnames if d not in DEFAULT_EXCLUDE and not d.startswith("."))
            for name in sorted(filenames):
                if not name.endswith(suffixes):
                    continue
                f = Path(dirpath) / name
                cfg = config_for(f)
                patterns = cfg.exclude + (cfg.fmt_exclude if use_exclude == "fmt" else [])
                if not root_excluded and cfg.is_excluded(f, patterns):
                    continue
                what = _special(f)
                if what is not None:
                    skipped(f, f"it is {what}, not a regular file: not read")
                    continue
                if f not in seen:
                    seen.add(f)
                    out.append(f)
    return out
