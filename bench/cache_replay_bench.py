"""Issue 27: an unchanged one-file lint replays within ~1.3x of `python -c pass`, and a cold one is
no slower than before the one cache layer. flake8 on a one-file Python project is the peer.

    python bench/cache_replay_bench.py                       # medians of 11, interleaved
    python bench/cache_replay_bench.py --baseline DIR        # also another checkout (`git archive` of main)
    python bench/cache_replay_bench.py --flake8 PATH         # flake8 to compare with (default: on PATH)

Rows, each a whole process (wall and CPU = the child's user + system time):

- `python -c pass`: the interpreter's own start-up (same venv);
- flake8 on one small Python file (its own cache off: flake8 has none);
- replay: `plx lint FILE` again, nothing changed (the entry of the last identical run);
- result hit: the same with the whole-run entry removed (the per-file result cache answers);
- cold: `plx lint FILE` on an empty cache folder (parses the 465 bundle files); the bundle
  program's cache is written by a forked child after the output, waited for between runs.

The load average is printed beside the figures: on a shared machine wall times follow it; the
CPU column is steadier.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from startup_bench import BASELINE_RUNNER, ONE, Runner, become_subreaper, run, wait_for_writers  # noqa: E402

PY_FILE = "def area(w, h):\n    return w * h\n\n\nprint(area(2, 3))\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--baseline", type=Path, help="another plxtools checkout to compare with")
    ap.add_argument("--flake8", default=shutil.which("flake8"), help="the flake8 executable to compare with")
    args = ap.parse_args()
    become_subreaper()
    tmp = Path(tempfile.mkdtemp(prefix="plx-cache-bench-"))
    try:
        py = tmp / "area.py"
        py.write_text(PY_FILE)
        runners = [Runner("this", [sys.executable, "-m", "plxtools"], tmp)]
        if args.baseline:
            runners.append(Runner("baseline", [sys.executable, "-c", BASELINE_RUNNER, str(args.baseline)], tmp))
        env = dict(os.environ)
        rows: dict[str, list[tuple[float, float]]] = {}

        def add(name, got):
            rows.setdefault(name, []).append(got)

        for r in runners:  # fill each cache once
            r.cached_lint()
            wait_for_writers()
            r.cached_lint()
        for _ in range(args.runs):
            add("python -c pass", run([sys.executable, "-c", "pass"], env))
            if args.flake8:
                add("flake8 (one file)", run([args.flake8, "--exit-zero", str(py)], env))
            for r in runners:
                add(f"{r.name}: replay", r.cached_lint())
                add(f"{r.name}: result hit", r.cached_lint(replay=False))
                r.cached_lint()  # the whole-run entry back
            for r in runners:
                add(f"{r.name}: cold", r.cold())
        base_wall = statistics.median(w for w, _c in rows["python -c pass"])
        base_cpu = statistics.median(c for _w, c in rows["python -c pass"])
        print(f"one file: {ONE.name}; medians of {args.runs}; load average {os.getloadavg()[0]:.1f}")
        print(f"{'':28} {'wall ms':>9} {'x pass':>7} {'CPU ms':>9} {'x pass':>7}")
        for name, got in rows.items():
            w = statistics.median(x for x, _ in got)
            c = statistics.median(y for _, y in got)
            print(f"{name:28} {w * 1000:9.1f} {w / base_wall:7.2f} {c * 1000:9.1f} {c / base_cpu:7.2f}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
