"""The worker pool of the one-shot commands (`plx lint`, `plx check`): many independent items on
all cores, results in the items' order.

Workers are forked from the command's process once it has loaded what every item needs (the
bundle program; for `plx check --simulate` also numpy and MuJoCo), so they inherit it instead of
loading it again, and the items themselves are inherited too: only their indices go to a worker and
only the results come back (they must pickle).

* **Order**: results come back in the order of ``items``, whatever order the workers finish in.
* **Ctrl-C**: the workers ignore SIGINT (the terminal sends it to the whole process group); the
  command's process gets the KeyboardInterrupt, ends its workers and re-raises it, so the command
  exits as a serial run does (130, no traceback from any worker).
* **A worker that dies** (killed, a crash inside a native library): its unfinished items are run
  again one at a time, each in a fresh single worker; an item that kills that one too gets
  ``on_death(item, reason)`` as its result, and the other items are unaffected.
"""

from __future__ import annotations

import gc
import os
import signal
import sys
from typing import Callable, Sequence, TypeVar

T = TypeVar("T")
R = TypeVar("R")

# the task of the pool being run: set before the fork, read by the workers
_TASK: tuple | None = None


def cores() -> int:
    """The cores this process may run on (its affinity), at most 8."""
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    return max(1, min(n, 8))


def can_fork() -> bool:
    import multiprocessing

    return "fork" in multiprocessing.get_all_start_methods()


def map_ordered(fn: Callable[[T], R], items: Sequence[T], *, workers: int,
                on_death: Callable[[T, str], R] | None = None, chunks_per_worker: int = 4,
                meanwhile: Callable[[], object] | None = None,
                on_result: Callable[[int, R], object] | None = None) -> list[R]:
    """``[fn(x) for x in items]`` computed by ``workers`` forked processes.

    ``fn`` and ``items`` are inherited by the fork (neither needs to pickle); each result is pickled
    back.  An exception raised by ``fn`` is raised here, as in the serial loop.  ``meanwhile`` is
    called in this process once the workers are started (work of its own that overlaps theirs).
    ``on_result(i, result)`` is called here as results come in, in order (the items of a worker that
    died, once they are done again, at the end)."""
    global _TASK
    if not items:
        return []
    _TASK = (fn, items)
    try:
        n = len(items)
        per = max(1, -(-n // (workers * max(1, chunks_per_worker))))  # a few chunks per worker: an even finish
        chunks = [range(i, min(i + per, n)) for i in range(0, n, per)]
        results: list = [None] * n
        failed = _run(chunks, min(workers, len(chunks)), results, meanwhile, on_result)
        for i in failed:  # their worker died: once more, one at a time, alone in a fresh worker
            if _run([range(i, i + 1)], 1, results):
                why = "the worker process died (killed, or a crash in a native library)"
                if on_death is None:
                    raise RuntimeError(f"item {i}: {why}")
                results[i] = on_death(items[i], why)
            if on_result is not None:
                on_result(i, results[i])
        return results
    finally:
        _TASK = None


def _run(chunks: list[range], workers: int, results: list, meanwhile=None, on_result=None) -> list[int]:
    """Run the chunks into ``results``; the indices of the items whose worker died."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool

    sys.stdout.flush()  # a forked worker flushes its copy of these buffers when it exits
    sys.stderr.flush()
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork"),
                               initializer=_worker_start)
    # SIGINT is blocked while the workers are forked (they inherit the mask and ignore the signal
    # before unblocking it); one that arrives meanwhile is delivered here when the mask is restored
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    died: list[int] = []
    try:
        # what exists now is inherited: frozen, the workers' collector never scans it (nor touches
        # its pages, which would copy them)
        gc.freeze()
        try:
            futures = [pool.submit(_chunk, c.start, c.stop) for c in chunks]
        finally:
            gc.unfreeze()
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
        if meanwhile is not None:
            meanwhile()
        for c, fut in zip(chunks, futures):
            try:
                results[c.start:c.stop] = fut.result()
            except BrokenProcessPool:
                died.extend(c)
                continue
            if on_result is not None:
                for i in c:
                    on_result(i, results[i])
    except BaseException:  # Ctrl-C, or an exception of fn or meanwhile: no worker outlives the command
        _terminate(pool)
        raise
    pool.shutdown(wait=True)
    return died


def _terminate(pool) -> None:
    for p in list((getattr(pool, "_processes", None) or {}).values()):
        try:
            p.terminate()
        except (OSError, ValueError):
            pass
    pool.shutdown(wait=False, cancel_futures=True)


def _worker_start() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _chunk(start: int, stop: int) -> list:
    fn, items = _TASK
    return [fn(items[i]) for i in range(start, stop)]
