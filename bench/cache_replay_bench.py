"""Start-up and throughput against their peers, each goal of issue 44 in one run (issue 27's replay
figures too): flake8 7 for linting, `python -c pass` of the same interpreter for a replay, plx with
caching disabled (`--no-cache`) for the price of the verified cache.

    python bench/cache_replay_bench.py                    # builds a wheel into a temporary venv (~1 min)
    python bench/cache_replay_bench.py --wheel-venv DIR   # re-use (or create) that venv for the wheel rows
    python bench/cache_replay_bench.py --runs 11 --line-runs 3 --skip-lines

Each figure is a whole process's CPU time (user + system, from the kernel's accounting of the
child), both sides run in turn (A B A B ...), the ratio taken pair by pair and its median printed:
on a shared machine the pairs move together. plxtools is byte-compiled first (in the checkout
and in the wheel's venv), since PYTHONDONTWRITEBYTECODE may be set.

- one small file: examples/boxtruck/boxtruck.openplx (116 lines, with the examples' plx.toml and
  user bundles), copied to a temporary folder; the peer is flake8 on a 96-line Python file;
  - cold: an empty cache folder (parses the 465 official bundle files). The bundle program's
    entry is written afterwards by a forked child, after the output: its CPU is printed on its own
    line and is not part of the figure (the run's caller does not wait for it);
  - one-line edit: the program is cached, the file's last line changed before each run;
  - replay: nothing changed; `plx` of a wheel installed into a venv (not editable: the editable
    finder makes every start of that interpreter dearer) against that venv's `python -c pass`;
- the verified cache's price: cold and one-line-edit runs against the same run with `--no-cache`
  (which neither reads nor writes an entry: an edit then parses the bundles again, so the edit
  ratio shows what the cache saves rather than what it costs);
- per line: lines per CPU-second of `plx lint` (the program cached, no result entries) against
  flake8's on Python of about the same size: the 465 official bundle files (flake8: standard-library
  files), a 10k-line project of 112-line files and one 100k-line file (bench/corpus.py for both).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import corpus  # noqa: E402
from _common import bundle_files, bundle_root, count_lines, python_corpus  # noqa: E402
from startup_bench import ONE, REPO, become_subreaper, children_cpu, run, wait_for_writers  # noqa: E402


def env_for(cache: Path | None = None) -> dict:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    if cache is not None:
        env["PLX_CACHE_DIR"] = str(cache)
    return env


def cpu(cmd: list[str], env: dict, cwd: Path | None = None) -> float:
    """CPU seconds of one run of `cmd` (its own; a forked cache writer is reaped, not counted)."""
    return run(cmd, env)[1]


class Pair:
    """A figure against its peer: CPU medians of both and the median of the pair-by-pair ratio."""

    def __init__(self, name: str, peer: str, goal: float | None = None, per_line: tuple | None = None) -> None:
        self.name, self.peer, self.goal, self.per_line = name, peer, goal, per_line
        self.a: list[float] = []
        self.b: list[float] = []

    def add(self, a: float, b: float) -> None:
        self.a.append(a)
        self.b.append(b)

    def ratio(self) -> float:
        if self.per_line:  # lines per CPU-second: plx's over the peer's
            na, nb = self.per_line
            return statistics.median((na / a) / (nb / b) for a, b in zip(self.a, self.b))
        return statistics.median(a / b for a, b in zip(self.a, self.b))

    def row(self) -> str:
        r = self.ratio()
        if self.goal is None:
            verdict = ""
        elif self.per_line:
            verdict = f">= {self.goal:.2f}x  {'met' if r >= self.goal else 'NOT met'}"
        else:
            verdict = f"<= {self.goal:.2f}x  {'met' if r <= self.goal else 'NOT met'}"
        return (f"{self.name:44} {statistics.median(self.a) * 1000:8.1f} {self.peer:34} "
                f"{statistics.median(self.b) * 1000:8.1f} {r:7.2f}x  {verdict}")


def wheel_venv(where: Path) -> Path:
    """A venv holding plxtools as users install it: a wheel built from this checkout, its
    dependencies from the configured index, everything byte-compiled. Returns its bin folder."""
    bin_ = where / "bin"
    if not (bin_ / "python").exists():
        subprocess.run([sys.executable, "-m", "venv", str(where)], check=True)
    whl = where / "wheel"
    shutil.rmtree(whl, ignore_errors=True)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(whl), str(REPO)], check=True)
    wheel = next(whl.glob("plxtools-*.whl"))
    subprocess.run([str(bin_ / "python"), "-m", "pip", "install", "-q", "--force-reinstall", "--no-deps", str(wheel)],
                   check=True)
    subprocess.run([str(bin_ / "python"), "-m", "pip", "install", "-q", str(wheel)], check=True)  # its dependencies
    env = env_for()
    env.pop("PYTHONPATH", None)
    site = subprocess.run([str(bin_ / "python"), "-c", "import plxtools, os; print(os.path.dirname(plxtools.__file__))"],
                          check=True, capture_output=True, text=True, env=env, cwd=where).stdout.strip()
    if "site-packages" not in site:
        raise SystemExit(f"the wheel venv imports plxtools from {site}, not its site-packages")
    subprocess.run([str(bin_ / "python"), "-m", "compileall", "-q", site], check=True)
    return bin_


def one_file_rows(args, tmp: Path, flake8: str, wheel_bin: Path | None) -> list[Pair]:
    proj = tmp / "examples"
    shutil.copytree(REPO / "examples", proj)
    one = proj / ONE.relative_to(REPO / "examples")
    original = one.read_text()
    py = tmp / "small.py"
    py.write_text(corpus.python_file(103))
    plx = [sys.executable, "-m", "plxtools"]
    exe = Path(sys.executable).parent / "plx"
    if exe.exists():
        plx = [str(exe)]
    lint = ["lint", "-q", "--exit-zero", str(one)]
    f8 = [flake8, "--exit-zero", str(py)]
    warm = tmp / "warm"
    n = [0]

    def cold(extra=()):
        n[0] += 1
        return cpu(plx + lint[:1] + list(extra) + lint[1:], env_for(tmp / f"cold-{n[0]}"), proj)

    def edit(extra=()):
        n[0] += 1
        one.write_text(original + f"# edit {n[0]}\n")
        return cpu(plx + lint[:1] + list(extra) + lint[1:], env_for(warm), proj)

    cpu(plx + lint, env_for(warm), proj)
    wait_for_writers()
    rows = {k: v for k, v in {
        "cold": Pair("cold, one file (empty cache)", "flake8, 96-line file", 1.2),
        "edit": Pair("one-line edit (program cached)", "flake8, 96-line file", 1.0),
        "replay": Pair("replay, wheel install", "python -c pass (same venv)", 1.8) if wheel_bin else None,
        "replay-dev": Pair("replay, this checkout's venv", "python -c pass (same venv)"),
        "cold-nc": Pair("cold, one file, cache on", "the same, --no-cache", 1.05),
        "edit-nc": Pair("one-line edit, cache on", "the same, --no-cache", 1.05),
    }.items() if v is not None}
    writer: list[float] = []
    if wheel_bin:
        wplx = [str(wheel_bin / "plx"), *lint]
        wenv = env_for(tmp / "wheel-cache")
        wenv.pop("PYTHONPATH", None)  # the wheel's own plxtools, whatever this process is given
        for _ in range(2):  # the entry written, then replayed
            cpu(wplx, wenv, proj)
            wait_for_writers()
    for _ in range(args.runs):
        before = children_cpu()
        a = cold()
        wait_for_writers()
        writer.append(max(0.0, children_cpu() - before - a))
        rows["cold"].add(a, cpu(f8, env_for()))
        rows["edit"].add(edit(), cpu(f8, env_for()))
        if wheel_bin:
            one.write_text(original)
            cpu(wplx, wenv, proj)  # (after an edit: the entry of this content again)
            rows["replay"].add(cpu(wplx, wenv, proj), cpu([str(wheel_bin / "python"), "-c", "pass"], wenv))
        one.write_text(original)
        cpu(plx + lint, env_for(warm), proj)
        rows["replay-dev"].add(cpu(plx + lint, env_for(warm), proj), cpu([sys.executable, "-c", "pass"], env_for()))
        a = cold()
        wait_for_writers()
        rows["cold-nc"].add(a, cold(["--no-cache"]))
        rows["edit-nc"].add(edit(), edit(["--no-cache"]))
    one.write_text(original)
    print(f"  cold: the forked writer of the program's entry, after the output: {statistics.median(writer) * 1000:.0f} ms CPU"
          " (not counted above)")
    return list(rows.values())


def per_line_rows(args, tmp: Path, flake8: str) -> list[Pair]:
    plx = [sys.executable, "-m", "plxtools"]
    cache = tmp / "lines-cache"

    def plx_cpu(target: Path) -> float:
        for name in ("results", "replays"):  # every file checked, the bundle program from its entry
            shutil.rmtree(cache / "plxtools" / name, ignore_errors=True)
        return cpu(plx + ["lint", "-q", "--exit-zero", str(target)], env_for(cache))

    big_plx, big_py = tmp / "big" / "model.openplx", tmp / "big" / "model.py"
    big_plx.parent.mkdir()
    big_plx.write_text(corpus.openplx_file(100_000))
    big_py.write_text(corpus.python_file(100_000))
    proj_plx = corpus.openplx_files(tmp / "proj-plx", 10_000)
    proj_py = corpus.python_files(tmp / "proj-py", 10_000)
    bundles = bundle_files()
    stdlib = python_corpus(count_lines(bundles))
    cases = [
        ("465 official bundle files", bundle_root(), count_lines(bundles), f"flake8, {len(stdlib)} stdlib files",
         stdlib, count_lines(stdlib)),
        (f"10k-line project ({len(proj_plx)} files)", tmp / "proj-plx", count_lines(proj_plx),
         f"flake8, {len(proj_py)} files", [tmp / "proj-py"], count_lines(proj_py)),
        ("one 100k-line file", big_plx, count_lines([big_plx]), "flake8, one file", [big_py], count_lines([big_py])),
    ]
    plx_cpu(big_plx.parent)  # the bundle program cached
    wait_for_writers()
    rows = []
    for name, target, n_plx, peer, py, n_py in cases:
        row = Pair(f"per line: {name} ({n_plx:,})", f"{peer} ({n_py:,})", 2.0, per_line=(n_plx, n_py))
        for _ in range(args.line_runs):
            row.add(plx_cpu(target), cpu([flake8, "--exit-zero", *map(str, py)], env_for()))
        rows.append(row)
    return rows


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=9, help="pairs per one-file figure")
    ap.add_argument("--line-runs", type=int, default=3, help="pairs per per-line figure")
    ap.add_argument("--wheel-venv", type=Path, help="the venv for the wheel rows (created when missing)")
    ap.add_argument("--skip-wheel", action="store_true")
    ap.add_argument("--skip-lines", action="store_true")
    ap.add_argument("--flake8", default=shutil.which("flake8"), help="the flake8 executable to compare with")
    args = ap.parse_args()
    if not args.flake8:
        raise SystemExit("flake8 is the peer: pip install flake8 (or give --flake8)")
    become_subreaper()
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(REPO / "plxtools")], check=True)
    tmp = Path(tempfile.mkdtemp(prefix="plx-goals-"))
    load = [os.getloadavg()[0]]
    try:
        wheel_bin = None
        if not args.skip_wheel:
            wheel_bin = wheel_venv(args.wheel_venv or tmp / "wheel-venv")
        print(f"CPU ms, medians; ratio = median of pair-by-pair ratios ({os.cpu_count()} cores, "
              f"Python {sys.version.split()[0]})")
        rows = one_file_rows(args, tmp, args.flake8, wheel_bin)
        load.append(os.getloadavg()[0])
        if not args.skip_lines:
            rows += per_line_rows(args, tmp, args.flake8)
        load.append(os.getloadavg()[0])
        print(f"{'figure':44} {'CPU ms':>8} {'peer':34} {'CPU ms':>8} {'ratio':>8}  goal")
        for r in rows:
            print(r.row())
        print("(per line: plx's lines per CPU-second over the peer's, so higher is better)")
        print(f"load average {min(load):.1f} to {max(load):.1f}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
