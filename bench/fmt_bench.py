"""Benchmark `plx fmt --check` against `black --check`, its peer, on corpora of the same size.

Throughput: `plx fmt --check` over the official OpenPLX bundles (and the same corpus copied ten
times, so start-up weighs less) next to `black --check` over standard-library Python files with
the same line count (+-10 %), in lines per CPU-second. CPU time is the user+sys time of the
command and every process it started (black runs workers on every core; CPU time counts them).
Start-up: one file of about the same size for each, median wall and CPU time of repeated runs
(CPU time is the steadier figure when other work shares the machine).

black's cache is pointed at a fresh empty folder for every run, so black does the full work
each time, as plx does. Run:  python bench/fmt_bench.py  [--runs 5] [--startup-runs 15]
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

PEER = "black"


def _bundle_root() -> Path:
    import openplxbundles

    return Path(openplxbundles.package_dir())


def _lines(paths: list[Path]) -> int:
    return sum(len(p.read_text(encoding="utf-8-sig").splitlines()) for p in paths)


def python_corpus(target_lines: int) -> list[Path]:
    """Standard-library modules, in name order, until their line count is within 10 % of the target."""
    stdlib = Path(sysconfig.get_paths()["stdlib"])
    chosen: list[Path] = []
    total = 0
    for p in sorted(stdlib.glob("*.py")):
        n = len(p.read_text(encoding="utf-8", errors="replace").splitlines())
        if total + n > target_lines * 1.1:
            continue
        chosen.append(p)
        total += n
        if total >= target_lines * 0.9:
            return chosen
    raise SystemExit("not enough standard-library Python to match the OpenPLX corpus")


def _copy(files: list[Path], root: Path, dest: Path, times: int) -> Path:
    for k in range(times):
        for f in files:
            target = dest / f"copy{k}" / f.relative_to(root)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(f, target)
    return dest


def _timed(cmd: list[str], env: dict | None = None) -> tuple[float, float, int]:
    """(CPU seconds of the command and its children, wall seconds, exit code)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, proc.returncode


def _black_env(scratch: Path) -> dict:
    env = dict(os.environ)
    cache = Path(tempfile.mkdtemp(prefix="black-cache-", dir=scratch))
    env["BLACK_CACHE_DIR"] = str(cache)
    return env


def plx_cmd(*args: str) -> list[str]:
    return [sys.executable, "-m", "plxtools", "fmt", "--check", "-q", *args]


def black_cmd(*args: str) -> list[str]:
    return [sys.executable, "-m", "black", "--check", "-q", *args]


def measure(cmd: list[str], runs: int, scratch: Path, black: bool) -> tuple[float, float, int]:
    """Median CPU and wall seconds over `runs` runs (after one warm-up run)."""
    cpus, walls, code = [], [], 0
    for i in range(runs + 1):
        cpu, wall, code = _timed(cmd, _black_env(scratch) if black else None)
        if i:
            cpus.append(cpu)
            walls.append(wall)
    return statistics.median(cpus), statistics.median(walls), code


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=5, help="runs per throughput figure (median)")
    ap.add_argument("--startup-runs", type=int, default=15, help="runs per start-up figure (median, >= 10)")
    args = ap.parse_args()

    root = _bundle_root()
    plx_files = sorted(root.rglob("*.openplx"))
    plx_lines = _lines(plx_files)
    py_files = python_corpus(plx_lines)
    py_root = Path(sysconfig.get_paths()["stdlib"])
    py_lines = _lines(py_files)

    rows = []
    with tempfile.TemporaryDirectory(prefix="fmt-bench-") as tmp:
        scratch = Path(tmp)
        for times in (1, 10):
            plx_dir = _copy(plx_files, root, scratch / f"plx{times}", times)
            py_dir = _copy(py_files, py_root, scratch / f"py{times}", times)
            cpu, wall, _ = measure(plx_cmd(str(plx_dir)), args.runs, scratch, black=False)
            rows.append(
                (f"OpenPLX bundles x{times}", "plx fmt --check", len(plx_files) * times, plx_lines * times, cpu, wall)
            )
            cpu, wall, _ = measure(black_cmd(str(py_dir)), args.runs, scratch, black=True)
            rows.append(
                (f"Python stdlib x{times}", f"{PEER} --check", len(py_files) * times, py_lines * times, cpu, wall)
            )

        one_plx = root / "Physics3D" / "Bodies" / "RigidBody.openplx"
        one_py = min(py_root.glob("*.py"), key=lambda p: abs(_lines([p]) - _lines([one_plx])))
        startup = []
        for name, cmd, black, path in (
            ("plx fmt --check", plx_cmd(str(one_plx)), False, one_plx),
            (f"{PEER} --check", black_cmd(str(one_py)), True, one_py),
        ):
            runs = [_timed(cmd, _black_env(scratch) if black else None) for _ in range(args.startup_runs + 1)][1:]
            wall_ms = statistics.median(r[1] for r in runs) * 1000
            cpu_ms = statistics.median(r[0] for r in runs) * 1000
            startup.append((name, path.name, _lines([path]), wall_ms, cpu_ms))

    import black as black_module

    print(
        f"plx fmt benchmark, {datetime.date.today().isoformat()}, {os.cpu_count()} cores, "
        f"Python {platform.python_version()}, peer: {PEER} {black_module.__version__}"
    )
    print()
    print(f"{'corpus':24} {'command':18} {'files':>6} {'lines':>7} {'CPU s':>7} {'lines/CPU-s':>12} {'wall s':>7}")
    for corpus, tool, files, lines, cpu, wall in rows:
        print(f"{corpus:24} {tool:18} {files:6d} {lines:7d} {cpu:7.2f} {lines / cpu:12,.0f} {wall:7.2f}")
    print()
    print(f"one-file start-up, median of {args.startup_runs} runs")
    print(f"{'command':18} {'file':28} {'lines':>6} {'wall ms':>8} {'CPU ms':>8}")
    for tool, name, lines, wall_ms, cpu_ms in startup:
        print(f"{tool:18} {name:28} {lines:6d} {wall_ms:8.1f} {cpu_ms:8.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
