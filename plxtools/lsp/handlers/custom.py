"""plx's own requests: `plx/stats` (timings and counters), `plx/memory` and `plx/documentText`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from plxtools.ide.runtime.memory import allocation_growth, memory_report

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer


def register(server, server_feature) -> None:
    @server.feature("plx/stats")
    def stats(ls: PlxServer, params) -> dict:
        """Recent server-side timings (wall and CPU ms) of checks and completions, for bench/lsp_bench.py."""
        return ls.stats.report()

    @server.feature("plx/memory")
    def memory(ls: PlxServer, params) -> dict:
        """What the server holds (for tests and bench/lsp_large_doc.py): the syntax trees alive
        (path and length of their text, found by the collector, frozen objects included), resident
        memory, and Python's own allocations when tracemalloc traces; with `{"growth": "start"}` or
        `{"growth": "diff"}` also where allocations grew since a baseline (bench/lsp_soak.py)."""
        out = memory_report()
        action = params.get("growth") if isinstance(params, dict) else getattr(params, "growth", None)
        if action in ("start", "diff", "sweep"):
            out["growth"] = allocation_growth(action)
        return out

    @server.feature("plx/documentText")
    def document_text(ls: PlxServer, params) -> dict | None:
        """The text and version the server holds for an open document (for sync checks and bug reports)."""
        uri = getattr(params, "uri", None) if not isinstance(params, dict) else params.get("uri")
        doc = ls.documents.get(uri) if isinstance(uri, str) else None
        if doc is None:
            return None
        return {"version": doc.version, "text": doc.text}
