"""The server's own timings and counters (its `plx/stats` request, read by bench/lsp_bench.py and the
large-document tests): recent wall and CPU times per kind of work, and how many background checks
started, finished or were cancelled."""

from __future__ import annotations

import time

KEEP = 200  # recent timings kept per kind


class Stats:
    def __init__(self) -> None:
        self.timings: dict[str, list[tuple[float, float]]] = {}  # kind -> recent (wall ms, CPU ms)
        self.counters: dict[str, int] = {}

    def record(self, kind: str, t0: float, c0: float) -> None:
        """One piece of work of `kind` that started at perf_counter `t0` and process_time `c0`."""
        self.add(kind, (time.perf_counter() - t0) * 1000, (time.process_time() - c0) * 1000)

    def add(self, kind: str, wall_ms: float, cpu_ms: float) -> None:
        got = self.timings.setdefault(kind, [])
        got.append((wall_ms, cpu_ms))
        del got[:-KEEP]

    def count(self, name: str) -> None:
        self.counters[name] = self.counters.get(name, 0) + 1

    def report(self) -> dict:
        out: dict = {kind: [list(x) for x in vals] for kind, vals in self.timings.items()}
        out["counters"] = dict(self.counters)
        return out
