"""`plx check` over many files on a pool of worker processes (--jobs): the same report, the same
exit code and the same stderr as the serial run; Ctrl-C and a worker that dies behave."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from check_helpers import BROKEN, EXAMPLE, REPO

from tests.conftest import run_plx

pytestmark = pytest.mark.skipif(not Path("/proc/self/task").is_dir() or os.name != "posix",
                                reason="the pool forks (POSIX); the tests look at /proc")


def _scenes(folder: Path) -> Path:
    """A folder of scenes of every kind: clean ones, ones whose errors block the simulation, one
    that does not parse, one without a model, one that is not text."""
    folder.mkdir()
    text = EXAMPLE.read_text(encoding="utf-8")
    for i in range(3):
        (folder / f"a{i}_truck.openplx").write_text(text.replace("target_speed: 1\n", f"target_speed: {1 + i}\n"),
                                                    encoding="utf-8")
    for name in ("moved_connector", "zero_box_size", "mirrored_motors"):
        shutil.copy(BROKEN / f"{name}.openplx", folder / f"b_{name}.openplx")
    (folder / "c_syntax.openplx").write_text("Scene is Physics3D.System:\n    x is Real: (\n", encoding="utf-8")
    (folder / "d_empty.openplx").write_text("# nothing here\n", encoding="utf-8")
    (folder / "e_binary.openplx").write_bytes(b"\x00\x01\x02PK\x03\x04" * 20)
    return folder


WALL = re.compile(r"\d+\.\d+ s wall\)")  # after "(integrator, "


def _untimed(x):
    if isinstance(x, dict):
        return {k: _untimed(v) for k, v in x.items() if k not in ("wall_time_s", "compile_ms")}
    if isinstance(x, list):
        return [_untimed(v) for v in x]
    return x


@pytest.mark.parametrize("fmt", ["text", "json"])
def test_pool_report_is_the_serial_report(tmp_path, fmt):
    folder = _scenes(tmp_path / "scenes")
    args = ["check", "--simulate", "--duration", "0.5", "--output-format", fmt, str(folder)]
    serial = run_plx(*args, "--jobs", "1")
    pooled = run_plx(*args, "--jobs", "2")
    assert serial.returncode == pooled.returncode == 1, serial.stderr + pooled.stderr
    assert serial.stderr == pooled.stderr
    assert "Traceback" not in pooled.stderr
    if fmt == "json":
        a, b = json.loads(serial.stdout), json.loads(pooled.stdout)
        assert _untimed(a) == _untimed(b)
        assert list(b["assembly"]) == sorted(b["assembly"])  # the files' order
        assert len(b["simulation"]) == 9
        assert sum("steps" in s for s in b["simulation"].values()) == 5  # 3 trucks, the mirrored motors, the moved connector (A016)
    else:
        assert WALL.sub("", serial.stdout) == WALL.sub("", pooled.stdout)
        assert pooled.stdout.count("simulated 0.50 s in 250 steps") == 5
        assert "c_syntax.openplx: not assembled: the file has syntax errors" in pooled.stdout


def test_auto_is_the_serial_report_without_simulation(tmp_path):
    folder = _scenes(tmp_path / "scenes")
    serial = run_plx("check", "--output-format", "json", "--jobs", "1", str(folder))
    auto = run_plx("check", "--output-format", "json", str(folder))
    assert (serial.returncode, serial.stderr) == (auto.returncode, auto.stderr) == (1, "")
    assert json.loads(serial.stdout) == json.loads(auto.stdout)


@pytest.mark.parametrize("value", ["0", "-2", "many", "1.5"])
def test_bad_jobs_is_a_usage_error(value):
    r = run_plx("check", "--jobs", value, str(EXAMPLE.relative_to(REPO)))
    assert r.returncode == 2
    assert "argument -j/--jobs: expected 'auto' or a whole number >= 1" in r.stderr
    assert "Traceback" not in r.stderr


def _children(pid: int) -> list[int]:
    try:
        text = Path(f"/proc/{pid}/task/{pid}/children").read_text()
    except OSError:
        return []
    return [int(x) for x in text.split()]


def _start_pool(folder: Path, *extra: str) -> tuple[subprocess.Popen, list[int]]:
    """`plx check --simulate` of the folder with 2 workers, once both workers exist."""
    env = dict(os.environ, NO_COLOR="1")
    p = subprocess.Popen([sys.executable, "-m", "plxtools", "check", "--simulate", "--jobs", "2", *extra,
                          str(folder)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         cwd=REPO, start_new_session=True)
    deadline = time.monotonic() + 120
    while len(_children(p.pid)) < 2 and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    kids = _children(p.pid)
    if len(kids) < 2:
        p.kill()
        p.communicate()
        pytest.fail("the pool's workers were not started")
    return p, kids


def _gone(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().split(") ")[1][0] in "ZX"
    except OSError:
        return True


def _trucks(folder: Path, n: int) -> Path:
    folder.mkdir()
    for i in range(n):
        shutil.copy(EXAMPLE, folder / f"truck{i}.openplx")
    return folder


def test_ctrl_c_ends_the_run_and_its_workers_quietly(tmp_path):
    p, kids = _start_pool(_trucks(tmp_path / "trucks", 4), "--duration", "600")
    os.killpg(p.pid, signal.SIGINT)  # what a terminal's Ctrl-C does: the whole foreground group
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err
    deadline = time.monotonic() + 10
    while not all(_gone(k) for k in kids) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert all(_gone(k) for k in kids), "a worker outlived the command"


def test_a_worker_that_dies_is_replaced(tmp_path):
    folder = _trucks(tmp_path / "trucks", 3)
    p, kids = _start_pool(folder, "--duration", "20", "--output-format", "json")
    os.kill(kids[0], signal.SIGKILL)
    out, err = p.communicate(timeout=280)
    # its files are checked again, one at a time in a fresh worker: the report is complete
    assert p.returncode == 0, err
    assert "Traceback" not in err
    doc = json.loads(out)
    assert [s["steps"] for s in doc["simulation"].values()] == [10000, 10000, 10000]
