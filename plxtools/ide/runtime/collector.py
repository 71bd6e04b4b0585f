"""How the language server runs Python's cyclic garbage collector around checks.

A check allocates ~10^5 objects per 2,000 lines (the new tree and symbols), and it leaves no
reference cycles behind (the checker uses no self-calling closures, and a replaced file's
symbols are taken apart by Program.remove_unit), so reference counting frees the previous
version at once. What the check built is then frozen (`gc.freeze()`, constant time): the
collector never rescans it, so the automatic passes between requests only walk what was
allocated since, and no request waits for a pass over a 20,000-line tree. Anything cyclic
that still slipped into the frozen generation is swept when the editor has been idle
(`_idle_sweep`), never on a request's path.
"""

from __future__ import annotations

import asyncio
import gc
import time

IDLE_SWEEP_AFTER = 10.0  # seconds without a check before the sweep
IDLE_SWEEP_EVERY = 120.0  # at most one sweep per this many seconds
_sweep_handle = None
_last_sweep = 0.0
_checks_since_sweep = 0


class no_gc:
    """No cyclic garbage collection while a file is checked (or completed while typing) and the
    result is sent, and none forced after it either (see the module's docstring).

    Before it, one collection over what is not frozen: only what requests and edits allocated since
    the last check (everything older is frozen), so it is short, but without it the cyclic garbage
    they left (a request's exception and its traceback, the formatter's parse) was frozen by the
    check's `gc.freeze()` and never collected while the user kept typing (issue 40.3)."""

    def __enter__(self):
        if gc.isenabled():
            gc.collect()
        gc.disable()

    def __exit__(self, *exc):
        _settle_gc()


def _settle_gc() -> None:
    """After a check: freeze what it built, resume automatic (now small) passes, and (re)arm the
    idle sweep."""
    global _sweep_handle, _checks_since_sweep
    gc.freeze()
    gc.enable()
    _checks_since_sweep += 1
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        return
    if _sweep_handle is not None:
        _sweep_handle.cancel()
    _sweep_handle = loop.call_later(IDLE_SWEEP_AFTER, _idle_sweep)


def _idle_sweep() -> None:
    """One full collection over everything, frozen objects included, when nobody is waiting."""
    global _sweep_handle, _last_sweep, _checks_since_sweep
    _sweep_handle = None
    now = time.monotonic()
    if not _checks_since_sweep:
        return
    if now - _last_sweep < IDLE_SWEEP_EVERY:
        try:
            _sweep_handle = asyncio.get_running_loop().call_later(IDLE_SWEEP_EVERY - (now - _last_sweep), _idle_sweep)
        except RuntimeError:
            pass
        return
    _last_sweep = now
    _checks_since_sweep = 0
    gc.unfreeze()
    gc.collect()
    gc.freeze()


def freeze_loaded() -> None:
    """Move everything loaded so far (the bundles' trees and symbols, which live as long as the
    server) out of the collector's sight, so collections only walk what edits create."""
    gc.collect()
    gc.freeze()


def reload_model(host) -> None:
    """A new bundle set: the old model is garbage now; load the new one and freeze it."""
    gc.unfreeze()
    _ = host.workspace
    freeze_loaded()
