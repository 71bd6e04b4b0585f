"""Running the plx command line in this process, as `cli.entry` does (the replay first), with the
per-process memos a new process would not have cleared: fast enough for thousands of runs."""

from __future__ import annotations

import io
import os
import sys

from tests.conftest import environment  # noqa: F401 - also imported from here


def forget_process_state() -> None:
    """What a new `plx` process would not know: the per-process memos of config and workspaces."""
    from plxtools import config
    from plxtools.cache import folder
    from plxtools.model import workspace

    config._config_for_dir.cache_clear()
    workspace._CLI_WORKSPACES.clear()
    folder.forget()


def run(argv: list[str], cwd, env: dict) -> tuple[int, str, str]:
    """(exit code, stdout, stderr) of `plx ARGV` run in `cwd` with `env` added to the environment."""
    from plxtools import cli, runmemo, runmode

    forget_process_state()
    runmode.one_shot(False)  # no forked cache writer: the entry is written before this returns
    out, err = io.StringIO(), io.StringIO()
    saved = sys.stdout, sys.stderr, os.getcwd()
    os.chdir(cwd)
    sys.stdout, sys.stderr = out, err
    try:
        with environment(env):
            code = runmemo.replay(argv)
            if code is None:
                token = runmemo.start(argv)
                try:
                    code = cli.main(argv)
                except SystemExit as exc:
                    code = exc.code if isinstance(exc.code, int) else 2
                runmemo.finish(token, code)
    finally:
        sys.stdout, sys.stderr = saved[0], saved[1]
        os.chdir(saved[2])
    return code, out.getvalue(), err.getvalue()
