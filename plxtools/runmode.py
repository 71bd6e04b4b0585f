"""How this process runs: one command and then it ends (`plx lint`, `plx fmt`, `plx check`, ...),
or long-lived (the language server, library callers, tests running commands in-process).

Only the console entry (`cli.entry`) knows which: it calls `one_shot()` before a command runs.
The policies that depend on it ask `is_one_shot()`: the garbage collector is not enabled again just
before the process leaves (`gcpolicy.py`), a slow cache write is left to a forked child, and
folders found in no bundle are not walked up again (`model/workspace.py`). This module imports
nothing, so the entry can say it before anything heavy is loaded (an answer replayed by
`runmemo` loads nothing at all).
"""

from __future__ import annotations

_one_shot = False


def one_shot(on: bool = True) -> None:
    """Say that the process ends right after the command (in-process runs may say False again)."""
    global _one_shot
    _one_shot = on


def is_one_shot() -> bool:
    return _one_shot


_interrupted = False


def watch_interrupts() -> None:
    """Ctrl-C still raises KeyboardInterrupt, and is also remembered here.  Native code can turn
    that exception into an error of its own: MuJoCo's bindings, interrupted inside a step, raise
    `UnexpectedError: cannot find callable`.  A command that catches errors per file asks
    `interrupted()` so it ends as interrupted instead of reporting a bug."""
    import signal

    def on_sigint(signum, frame):
        global _interrupted
        _interrupted = True
        signal.default_int_handler(signum, frame)

    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, on_sigint)


def interrupted() -> bool:
    return _interrupted
