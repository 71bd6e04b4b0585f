"""Which .openplx files a command works on: explicit files, and folders walked with the config's
excludes. Shared by lint, fmt and check."""

from __future__ import annotations

import os
from pathlib import Path

from plxtools.config import DEFAULT_EXCLUDE, config_for


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


def discover(paths: list[str], *, use_exclude: str = "lint", suffixes: tuple[str, ...] = (".openplx",)) -> list[Path]:
    """Expand folders into their .openplx files (`suffixes`: `plx migrate` also finds the .brick
    files of before OpenPLX 0.15); explicit files are always taken."""
    out: list[Path] = []
    seen: set[Path] = set()
    for raw in paths:
        p = Path(raw)
        if not p.exists():
            raise UsageError(f"{raw}: no such file or folder")
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
                if f not in seen:
                    seen.add(f)
                    out.append(f)
    return out
