"""Ctrl-C that arrives while MuJoCo is stepping can come out of its bindings as an error of their own
(`UnexpectedError: cannot find callable`, seen once under load in the pool test), not as
KeyboardInterrupt.  `plx check` and `plx test` must still end as interrupted (exit 130, no
"internal error" report).  The driver below makes MuJoCo's step do exactly that: the interrupt
arrives inside it, and the step turns it into a RuntimeError."""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("mujoco")

from check_helpers import EXAMPLE  # noqa: E402

DRIVER = r"""
import os, signal, sys
import mujoco
from plxtools import runmode
from plxtools.cli import main

runmode.watch_interrupts()
real = {"mj_step": mujoco.mj_step, "mj_step2": mujoco.mj_step2}
calls = [0]

def interrupted_inside(name):
    def step(*a, **k):
        calls[0] += 1
        if calls[0] == 50:
            try:
                os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C while "inside" the native step
            except KeyboardInterrupt:
                raise RuntimeError("cannot find `callable`")  # what the bindings make of it
        return real[name](*a, **k)
    return step

mujoco.mj_step = interrupted_inside("mj_step")
mujoco.mj_step2 = interrupted_inside("mj_step2")
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("command", [["check", "--simulate", "--duration", "5", str(EXAMPLE)],
                                     ["test", str(EXAMPLE.parent)]], ids=["check", "test"])
def test_an_interrupt_turned_into_an_error_by_native_code_still_ends_the_run_as_interrupted(command):
    r = subprocess.run([sys.executable, "-c", DRIVER, *command], capture_output=True, text=True, timeout=300)
    assert r.returncode == 130, r.stdout[-2000:] + r.stderr[-2000:]
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr
