"""Helpers shared by the benchmark scripts: corpora, CPU-time of child processes, tables."""

from __future__ import annotations

import glob
import os
import resource
import statistics
import subprocess
import sys
import sysconfig
import time
from pathlib import Path


def bundle_root() -> Path:
    import openplxbundles

    return Path(openplxbundles.package_dir())


def bundle_files() -> list[Path]:
    return sorted(Path(p) for p in glob.glob(str(bundle_root() / "**" / "*.openplx"), recursive=True))


def count_lines(paths) -> int:
    return sum(p.read_text(encoding="utf-8", errors="replace").count("\n") + 1 for p in paths)


def python_corpus(target_lines: int) -> list[Path]:
    """Standard-library .py files, in a fixed order, until about `target_lines` lines."""
    stdlib = Path(sysconfig.get_paths()["stdlib"])
    out, n = [], 0
    for p in sorted(stdlib.glob("*.py")):
        lines = count_lines([p])
        if n + lines > target_lines * 1.05:
            continue
        out.append(p)
        n += lines
        if n >= target_lines * 0.95:
            break
    return out


def run_cpu(cmd: list[str], cwd=None, env=None) -> tuple[float, float, int]:
    """(wall seconds, CPU seconds of the child, exit code)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, r.returncode


def median_of(cmd, runs: int, **kw) -> tuple[float, float]:
    walls, cpus = [], []
    for _ in range(runs):
        w, c, _ = run_cpu(cmd, **kw)
        walls.append(w)
        cpus.append(c)
    return statistics.median(walls), statistics.median(cpus)


def tool(name: str) -> str:
    """A console script next to this interpreter (plx, flake8, black)."""
    p = Path(sys.executable).parent / name
    return str(p) if p.exists() else name


def table(rows: list[tuple], headers: tuple) -> str:
    widths = [max(len(str(x)) for x in col) for col in zip(headers, *rows)]
    line = "  ".join(str(h).ljust(w) for h, w in zip(headers, widths))
    out = [line, "  ".join("-" * w for w in widths)]
    out += ["  ".join(str(x).ljust(w) for x, w in zip(r, widths)) for r in rows]
    return "\n".join(out)


def machine() -> str:
    return f"{os.cpu_count()} cores, Python {sys.version.split()[0]}"
