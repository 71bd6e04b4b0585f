"""What the language server holds in memory (its `plx/memory` request, for tests and
bench/lsp_large_doc.py)."""

from __future__ import annotations

import gc
import os
from plxtools.syntax import ast


def memory_report() -> dict:
    """The syntax trees alive (path and length of their text, found by the collector, frozen objects
    included), resident memory, and Python's own allocations when tracemalloc traces."""

    gc.unfreeze()  # frozen objects are invisible to gc.get_objects(); freezing again is constant time
    try:
        trees = [{"path": o.path, "chars": len(o.text)} for o in gc.get_objects() if type(o) is ast.File]
    finally:
        gc.freeze()
    rss = 0
    try:
        with open(f"/proc/{os.getpid()}/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    rss = int(line.split()[1])
    except OSError:
        pass
    import tracemalloc

    traced = tracemalloc.get_traced_memory()[0] // 1024 if tracemalloc.is_tracing() else None
    return {"trees": trees, "rss_kb": rss, "python_kb": traced, "frozen": gc.get_freeze_count()}


_baseline = None  # the tracemalloc snapshot `allocation_growth("start")` took


def allocation_growth(action: str, top: int = 20, frames: int = 12) -> list | None:
    """Where Python's allocations grew since a baseline (for bench/lsp_soak.py): `start` takes the
    baseline (and starts tracemalloc if it is not tracing yet); `diff` lists the `top` call sites whose
    allocations grew most since it (size and count of the growth, innermost frames first).
    None when tracemalloc is not tracing."""
    global _baseline
    import tracemalloc

    if action == "sweep":  # what a full collection finds, frozen objects included
        frozen = gc.get_freeze_count()
        gc.unfreeze()
        found = gc.collect()
        gc.freeze()
        return [{"frozen_before": frozen, "unreachable": found, "frozen_after": gc.get_freeze_count()}]
    if action == "start" and not tracemalloc.is_tracing():
        tracemalloc.start(frames)  # from now on: only what is allocated after the baseline is traced
    if not tracemalloc.is_tracing():
        return None
    gc.collect()
    snap = tracemalloc.take_snapshot().filter_traces([
        tracemalloc.Filter(False, tracemalloc.__file__), tracemalloc.Filter(False, "<frozen importlib._bootstrap>")])
    if action == "start" or _baseline is None:
        _baseline = snap
        return []
    out = []
    for st in snap.compare_to(_baseline, "traceback")[:top]:
        where = [f"{f.filename.rsplit('/site-packages/', 1)[-1]}:{f.lineno}" for f in list(st.traceback)[::-1][:frames]]
        out.append({"kb": st.size_diff / 1024, "count": st.count_diff, "where": where})
    return out
