"""Issue 17 goal 3: the start-up of a one-file run, cold and warm, with `python -c pass` beside it.

    python bench/startup_bench.py                  # medians of 7, interleaved
    python bench/startup_bench.py --runs 11
    python bench/startup_bench.py --baseline DIR   # also another checkout (`git archive` of a commit)
    python bench/startup_bench.py --identical      # only: compare lint JSON cold / warm / cached
    python bench/startup_bench.py --identical --baseline DIR   # ... and with DIR's plx --no-cache

Rows (each a whole process, wall and CPU = the child's user + system time):

- cold: `plx lint` of one file with an empty PLX_CACHE_DIR (no bundle program, no lark grammar
  cache, no result); the bundle program's cache may still be written after the run's output, by a
  child process, whose CPU time is reported separately (it is not part of the command's wait);
- warm, no result cache: the bundle program is cached, the file's result is not;
- cached: `plx lint` / `plx fmt --check` of the same unchanged file, once with only the per-file
  result cache (the replay entries of plxtools/runmemo.py removed before the run), once replayed;
- `python -c pass`: the interpreter's own start-up, same venv (its `site`, editable finder included).

The load average is printed beside the figures: on a shared machine the wall times follow it.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
ONE = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
BASELINE_RUNNER = (
    "import sys; sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f)]; "
    "sys.path.insert(0, __import__('os').path.abspath(sys.argv[1])); del sys.argv[1]; sys.argv[0] = 'plx'; "
    "from plxtools.cli import entry; entry()"
)


def run(cmd: list[str], env: dict) -> tuple[float, float]:
    """(wall s, CPU s) of one child process (its own children are not waited for)."""
    t = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            stdin=subprocess.DEVNULL, cwd=REPO)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):
        raise SystemExit(f"failed ({code}): {' '.join(cmd)}")
    return wall, ru.ru_utime + ru.ru_stime


def children_cpu() -> float:
    import resource

    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def become_subreaper() -> bool:
    """Linux: orphaned grandchildren (a cold run's background cache writer) become our children,
    so they can be waited for and their CPU time is counted in RUSAGE_CHILDREN."""
    try:
        import ctypes

        return ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0) == 0  # PR_SET_CHILD_SUBREAPER
    except (OSError, AttributeError):
        return False


def wait_for_writers() -> None:
    """Reap every child left (a cold run's cache writer), so the next run does not share the CPU."""
    while True:
        try:
            os.waitpid(-1, 0)
        except ChildProcessError:
            return


class Runner:
    def __init__(self, name: str, prefix: list[str], tmp: Path) -> None:
        self.name, self.prefix, self.tmp = name, prefix, tmp
        self.env = dict(os.environ, PLX_CACHE_DIR=str(tmp / f"cache-{name}"))
        self.env.pop("PYTHONDONTWRITEBYTECODE", None)
        self.n = 0

    def cmd(self, *args: str) -> list[str]:
        return self.prefix + list(args)

    def cold(self) -> tuple[float, float]:
        self.n += 1
        env = dict(self.env, PLX_CACHE_DIR=str(self.tmp / f"cold-{self.name}-{self.n}"))
        got = run(self.cmd("lint", "--exit-zero", "-q", str(ONE)), env)
        wait_for_writers()
        return got

    def forget(self, *names: str) -> None:
        for name in names:
            shutil.rmtree(Path(self.env["PLX_CACHE_DIR"]) / "plxtools" / name, ignore_errors=True)

    def warm_no_result(self) -> tuple[float, float]:
        self.forget("lint-results", "runs", "results", "replays")  # (older checkouts' folder names too)
        return run(self.cmd("lint", "--exit-zero", "-q", str(ONE)), self.env)

    def cached_lint(self, replay: bool = True) -> tuple[float, float]:
        if not replay:
            self.forget("runs", "replays")  # the per-file result is there, the whole run is not
        return run(self.cmd("lint", "--exit-zero", "-q", str(ONE)), self.env)

    def cached_fmt(self, replay: bool = True) -> tuple[float, float]:
        if not replay:
            self.forget("runs", "replays")
        return run(self.cmd("fmt", "--check", "-q", str(ONE)), self.env)


def identical(prefix: list[str], tmp: Path, baseline: list[str] | None = None) -> int:
    """lint JSON of examples/ and tests/cases (folders and each file), cold, warm and cached (replayed
    where it can be), with --no-cache, and with the baseline's --no-cache if given: all equal."""
    targets = [REPO / "examples", REPO / "tests" / "cases"]
    targets += sorted(p for t in list(targets) for p in t.rglob("*.openplx"))
    bad = 0
    for k, t in enumerate(targets):
        env = dict(os.environ, PLX_CACHE_DIR=str(tmp / f"id-{k}"))
        outs = []
        for _ in range(3):  # cold, then warm (program cached; folders may hold bundle files), then cached
            p = subprocess.run(prefix + ["lint", "--exit-zero", "--output-format", "json", str(t)], env=env,
                               capture_output=True, cwd=REPO)
            outs.append(p.stdout)
            wait_for_writers()
        nocache = subprocess.run(prefix + ["lint", "--exit-zero", "--no-cache", "--output-format", "json", str(t)],
                                 env=env, capture_output=True, cwd=REPO).stdout
        if baseline is not None:
            outs.append(subprocess.run(baseline + ["lint", "--exit-zero", "--no-cache", "--output-format", "json",
                                                   str(t)], env=env, capture_output=True, cwd=REPO).stdout)
        if len(set(outs + [nocache])) != 1:
            bad += 1
            print(f"DIFFERENT: {t}", file=sys.stderr)
    print(f"{len(targets)} targets, {bad} with different output (cold / warm / cached / --no-cache)")
    return 1 if bad else 0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--baseline", help="another checkout's folder (plx run from it, as in perf_table.py)")
    ap.add_argument("--identical", action="store_true", help="only compare outputs")
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="plx-startup-"))
    if not become_subreaper():
        print("note: not a subreaper (not Linux?): a background writer's CPU is not counted", file=sys.stderr)
    exe = Path(sys.executable).parent / "plx"
    prefix = [str(exe)] if exe.exists() else [sys.executable, "-m", "plxtools"]
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(REPO / "plxtools")]
                   + ([str(Path(args.baseline) / "plxtools")] if args.baseline else []),
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        if args.identical:
            base = [sys.executable, "-c", BASELINE_RUNNER, args.baseline] if args.baseline else None
            raise SystemExit(identical(prefix, tmp, base))
        runners = [Runner("plx", prefix, tmp)]
        if args.baseline:
            runners.append(Runner("base", [sys.executable, "-c", BASELINE_RUNNER, args.baseline], tmp))
        for r in runners:  # the program and the result are cached before the warm rows
            r.cached_lint()
            r.cached_fmt()
        pass_env = dict(os.environ)
        rows: dict[tuple[str, str], list[tuple[float, float]]] = {}
        writer_cpu: dict[str, list[float]] = {}
        loads = []
        for _ in range(args.runs):
            loads.append(os.getloadavg()[0])
            rows.setdefault(("python -c pass", ""), []).append(run([sys.executable, "-c", "pass"], pass_env))
            for r in runners:
                before = children_cpu()
                got = r.cold()
                # every child of this process is waited for: the total minus the command's own CPU
                # is what any background writer used
                writer_cpu.setdefault(r.name, []).append(max(0.0, children_cpu() - before - got[1]))
                rows.setdefault(("lint cold (empty cache), one file", r.name), []).append(got)
                rows.setdefault(("lint warm, no result cache", r.name), []).append(r.warm_no_result())
                rows.setdefault(("lint, unchanged file, result cache only", r.name), []).append(
                    r.cached_lint(replay=False))
                rows.setdefault(("lint, unchanged file, replayed run", r.name), []).append(r.cached_lint())
                rows.setdefault(("fmt --check, unchanged file, cache only", r.name), []).append(
                    r.cached_fmt(replay=False))
                rows.setdefault(("fmt --check, unchanged file, replayed run", r.name), []).append(r.cached_fmt())
        print(f"{ONE.relative_to(REPO)}, medians of {args.runs}, load average {min(loads):.2f} to "
              f"{max(loads):.2f} on {os.cpu_count()} cores, {time.strftime('%Y-%m-%d %H:%M')}")
        print(f"{'row':45} {'who':5} {'wall ms':>8} {'CPU ms':>8}")
        for (what, who), got in rows.items():
            wall = statistics.median(g[0] for g in got) * 1000
            cpu = statistics.median(g[1] for g in got) * 1000
            print(f"{what:45} {who:5} {wall:8.0f} {cpu:8.0f}")
        for who, cpus in writer_cpu.items():
            print(f"{'  cold: background cache writer, CPU':45} {who:5} {'':8} {statistics.median(cpus) * 1000:8.0f}")
        print(json.dumps({"load": loads}), file=sys.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
