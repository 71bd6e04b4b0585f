"""Cold start: the bundles parsed in a forked process while pygls loads (issue 40.1).

Without a cached `initialize` reply the server must import pygls and lsprotocol (~0.7 s of CPU)
before it can answer, and only then, at `initialized`, parse the bundles (~0.5 s on a first start).
The two do not depend on each other, and the machine has more than one core: so, when plx's cache
holds no bundles' program yet, a child forked at the first `initialize` loads the bundle set the server will choose (the same settings as early.py
reads) into plx's cache and exits; the server's own load waits for it and reads the cache. If the
editor's settings choose other bundles, the server parses them as before; what the child wrote is
an ordinary cache entry (keyed by the bundles' content), equal to a fresh parse.
"""

from __future__ import annotations

import os

_child: int | None = None


def start(init: dict) -> None:
    """Fork the loader for this `initialize` request (a no-op where fork is missing)."""
    global _child
    if not hasattr(os, "fork") or os.environ.get("PLX_LSP_NO_EARLY") or _child is not None or _programs_cached():
        return
    try:
        pid = os.fork()
    except OSError:
        return
    if pid:
        _child = pid
        return
    code = 0
    try:
        from plxtools.lsp.early import host_for

        _ = host_for(init.get("params") if isinstance(init.get("params"), dict) else {})[0].workspace
    except BaseException:  # noqa: BLE001 - the server loads the bundles itself then
        code = 1
    finally:
        os._exit(code)


def _programs_cached() -> bool:
    """Whether plx's cache holds any bundles' program: then the server's own load reads it in ~0.1 s
    and a child would cost more (its imports) than it saves; measured in Emacs, a warm cache with a
    new `initialize`: 4.2-4.4 s to the first diagnostics without the child, 4.8-7.1 s with it."""
    from plxtools.cache import store

    where = store.entry_path("programs", "x")
    try:
        return where is None or any(os.scandir(os.path.dirname(where)))
    except OSError:
        return False


def wait() -> None:
    """Until the forked loader is done (called where the server loads the bundles)."""
    global _child
    pid, _child = _child, None
    if pid is not None:
        try:
            os.waitpid(pid, 0)
        except ChildProcessError:
            pass
