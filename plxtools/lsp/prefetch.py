"""Cold start: the bundles parsed in a forked process while pygls loads (issue 40.1).

Without a cached `initialize` reply the server must import pygls and lsprotocol (~0.7 s of CPU)
before it can answer, and only then, at `initialized`, parse the bundles (~0.5 s on a first start).
The two do not depend on each other, and the machine has more than one core: so a child forked at
the first `initialize` loads the bundle set the server will choose (the same settings as early.py
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
    if not hasattr(os, "fork") or os.environ.get("PLX_LSP_NO_EARLY") or _child is not None:
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


def wait() -> None:
    """Until the forked loader is done (called where the server loads the bundles)."""
    global _child
    pid, _child = _child, None
    if pid is not None:
        try:
            os.waitpid(pid, 0)
        except ChildProcessError:
            pass
