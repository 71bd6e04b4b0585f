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
