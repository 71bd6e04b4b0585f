"""`plx cache dir|info|clean`: where plx's cache is, what it holds, and emptying it."""

from __future__ import annotations

import os
import sys

from plxtools.cache import folder, store


def _size(n: int) -> str:
    for unit in ("B", "KiB", "MiB", "GiB"):
        if n < 1024 or unit == "GiB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1024
    return f"{n} B"  # pragma: no cover


def run(args) -> int:
    what = args.action
    path = folder.location()
    if what == "dir":
        print(path)
        return 0
    if what == "clean":
        if folder.root(create=False) is None and os.path.exists(path):
            print(f"plx cache: not cleaning {path}: it is not private to you (see 'plx cache info')", file=sys.stderr)
            return 2
        files, size = store.clean()
        print(f"removed {files} entr{'y' if files == 1 else 'ies'} ({_size(size)}) from {path}")
        return 0
    usable = folder.root(create=False)
    print(f"folder:  {path}{'' if usable or not os.path.exists(path) else '  (NOT USED: not private to you)'}")
    print(f"secret:  {folder.secret_path()}")
    found = store.entries(usable) if usable else []
    total = sum(e[2] for e in found)
    print(f"size:    {_size(total)} of {_size(store.cap_bytes())} (PLX_CACHE_MAX_MB)")
    for kind in store.KINDS:
        mine = [e for e in found if e[0] == kind]
        print(f"  {kind:<12} {len(mine):6} entries  {_size(sum(e[2] for e in mine)):>10}")
    return 0
