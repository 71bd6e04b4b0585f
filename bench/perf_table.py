"""Issue 17's table in one command: every row with its peer beside it, on generated corpora.

    python bench/perf_table.py                 # the table, scaling to 100k lines (a few minutes)
    python bench/perf_table.py --max 1000000   # also 1M lines (one file and many files; ~10 min)
    python bench/perf_table.py --quick         # fewer runs, smaller sizes (a smoke test)
    python bench/perf_table.py --baseline DIR  # add plx columns for another checkout (e.g. the
                                               # commit before, unpacked with `git archive`)

Corpora (bench/corpus.py): lint-clean OpenPLX in one file or in files of 112 lines, and
flake8-clean Python of the same size for the peers; the official bundles (465 files) with
standard-library Python files of the same number of lines. Every figure is a whole process
(interpreter start included), CPU = the child's user + system time, peak = its max RSS; medians
of --runs, plx and peer interleaved. Peers that are not installed print 'peer not installed'
(`pip install flake8 black ruff` into the venv for the bench only).
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
import corpus  # noqa: E402
from _common import bundle_files, bundle_root, count_lines, python_corpus, table  # noqa: E402

REPO = Path(__file__).resolve().parent.parent


def peer(name: str) -> list[str] | None:
    p = Path(sys.executable).parent / name
    if p.exists():
        return [str(p)]
    found = shutil.which(name)
    return [found] if found else None


def run(cmd: list[str], env: dict | None = None, stdin: bytes | None = None) -> tuple[float, float, float]:
    """(wall s, CPU s, peak RSS MB) of one child process."""
    t = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            stdin=subprocess.PIPE if stdin is not None else subprocess.DEVNULL, cwd=REPO)
    if stdin is not None:
        proc.stdin.write(stdin)
        proc.stdin.close()
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t
    if proc.returncode not in (0, 1):
        raise SystemExit(f"failed ({proc.returncode}): {' '.join(cmd)}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024


def forget_results(env: dict | None) -> None:
    """Empty plx's per-file result caches and its replayed runs (not the bundle program's): a
    throughput run must check every file, not find it unchanged."""
    if env and env.get("PLX_CACHE_DIR"):
        for name in ("lint-results", "fmt-formatted", "runs"):
            shutil.rmtree(Path(env["PLX_CACHE_DIR"]) / "plxtools" / name, ignore_errors=True)


def medians(cmds: list[tuple[list[str], dict | None]], runs: int, keep_results: bool = False
            ) -> list[tuple[float, float, float]]:
    """Interleaved runs of several commands; per command the median wall, CPU and peak."""
    got: list[list[tuple[float, float, float]]] = [[] for _ in cmds]
    for _ in range(runs):
        for k, (cmd, env) in enumerate(cmds):
            if not keep_results:
                forget_results(env)
            got[k].append(run(cmd, env))
    return [tuple(statistics.median(x[i] for x in g) for i in range(3)) for g in got]


# runs `plx` from another checkout: the editable install's import hook would otherwise win over
# PYTHONPATH and run this checkout again
BASELINE_RUNNER = (
    "import sys; sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f)]; "
    "sys.path.insert(0, __import__('os').path.abspath(sys.argv[1])); del sys.argv[1]; sys.argv[0] = 'plx'; "
    "from plxtools.cli import entry; entry()"
)


class Bench:
    def __init__(self, args) -> None:
        self.args = args
        self.tmp = Path(tempfile.mkdtemp(prefix="plx-perf-"))
        self.env = dict(os.environ, PLX_CACHE_DIR=str(self.tmp / "cache"))
        # bytecode is cached, as for any installed tool (a sandbox may turn it off for everything)
        self.env.pop("PYTHONDONTWRITEBYTECODE", None)
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(REPO / "plxtools")]
                       + ([str(Path(args.baseline) / "plxtools")] if args.baseline else []),
                       env=self.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.plx = [sys.executable, "-m", "plxtools"]
        exe = Path(sys.executable).parent / "plx"
        if exe.exists():
            self.plx = [str(exe)]
        self.base_env = None
        if args.baseline:
            self.base_env = dict(self.env, PLX_CACHE_DIR=str(self.tmp / "cache-base"))
        self.rows: list[tuple] = []
        self.flake8, self.ruff, self.black = peer("flake8"), peer("ruff"), peer("black")

    def plx_cmds(self, *args: str) -> list[tuple[list[str], dict | None]]:
        cmds = [(self.plx + list(args), self.env)]
        if self.base_env is not None:
            # both checkouts through the same runner: the editable install's finder (about 20 ms per
            # start) would otherwise count against this checkout only
            cmds = [([sys.executable, "-c", BASELINE_RUNNER, str(REPO)] + list(args), self.env),
                    ([sys.executable, "-c", BASELINE_RUNNER, self.args.baseline] + list(args), self.base_env)]
        return cmds

    def row(self, what: str, plx_args: list[str], peers: list[tuple[str, list[str] | None]], measure: str,
            runs: int, lines: int | None = None, keep_results: bool = False) -> None:
        """One row: plx (and the baseline) and each peer, interleaved; `measure` is wall, cpu or peak.
        plx's per-file result caches are emptied before each run unless `keep_results`."""
        idx = {"wall": 0, "cpu": 1, "peak": 2}[measure]
        cmds = self.plx_cmds(*plx_args)
        live = [(n, c) for n, c in peers if c is not None]
        res = medians(cmds + [(c, self.env) for _, c in live], runs, keep_results)
        mine = res[0][idx]
        unit = "MB" if measure == "peak" else "s"
        fmt = (lambda v: f"{v:,.0f} MB") if measure == "peak" else (lambda v: f"{v:.3f} s")
        base = fmt(res[1][idx]) if self.base_env is not None else ""
        peer_txt, ratio_txt = [], []
        k = len(cmds)
        for n, c in peers:
            if c is None:
                peer_txt.append(f"{n}: peer not installed")
                continue
            v = res[k][idx]
            k += 1
            peer_txt.append(f"{n} {fmt(v)}")
            ratio_txt.append(f"{mine / v:.2f}" if v else "-")
        per_line = f"{lines / res[0][1]:,.0f}" if lines else ""
        self.rows.append((what, measure, fmt(mine), base, "; ".join(peer_txt) or "-", "; ".join(ratio_txt) or "-",
                          per_line))
        print(f"  {what} [{measure}, {unit}]: plx {fmt(mine)} {base} | {'; '.join(peer_txt)}", file=sys.stderr,
              flush=True)

    # ------------------------------------------------------------------ rows

    def warm(self) -> None:
        one = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
        for cmd, env in self.plx_cmds("lint", "--exit-zero", str(one)):
            run(cmd, env)

    def issue_rows(self) -> None:
        runs = self.args.runs
        files = bundle_files()
        n_b = count_lines(files)
        py_b = python_corpus(n_b)
        f8 = lambda paths: self.flake8 + ["--exit-zero", *map(str, paths)] if self.flake8 else None  # noqa: E731
        ruff_check = lambda paths: self.ruff + ["check", "--exit-zero", "--no-cache", "-q", *map(str, paths)] \
            if self.ruff else None  # noqa: E731
        self.row(f"lint, {len(files)} official bundle files ({n_b:,} lines)", ["lint", "--exit-zero", "-q",
                 str(bundle_root())], [(f"flake8 ({count_lines(py_b):,} stdlib lines)", f8(py_b))], "cpu", runs, n_b)
        many = corpus.openplx_files(self.tmp / "many10k", 10_000)
        corpus.python_files(self.tmp / "many10kpy", 10_000)
        n_m = count_lines(many)
        self.row(f"lint, {n_m:,} lines in {len(many)} files", ["lint", "--exit-zero", "-q", str(self.tmp / "many10k")],
                 [("flake8", f8([self.tmp / "many10kpy"])), ("ruff", ruff_check([self.tmp / "many10kpy"]))],
                 "cpu", runs, n_m)
        one = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
        one_py = self.tmp / "one117.py"
        one_py.write_text(corpus.python_file(117))
        self.row("lint, one 117-line file", ["lint", "--exit-zero", "-q", str(one)],
                 [("flake8", f8([one_py])), ("ruff", ruff_check([one_py]))], "cpu", runs * 2)
        self.row("lint, one 117-line file", ["lint", "--exit-zero", "-q", str(one)],
                 [("flake8", f8([one_py])), ("ruff", ruff_check([one_py]))], "wall", runs * 2)
        for measure in ("cpu", "wall"):
            self.row("lint, one unchanged 117-line file (result cache)", ["lint", "--exit-zero", "-q", str(one)],
                     [("flake8", f8([one_py])), ("ruff (its cache)", self.ruff + ["check", "--exit-zero", "-q",
                      "--cache-dir", str(self.tmp / "ruffcache"), str(one_py)] if self.ruff else None)],
                     measure, runs * 2, keep_results=True)
        self.row("fmt --check, one unchanged 117-line file (result cache)", ["fmt", "--check", "-q", str(one)],
                 [("black (its cache)", self.black + ["--check", "-q", str(one_py)] if self.black else None),
                  ("ruff format (its cache)", self.ruff + ["format", "--check", "-q", "--cache-dir",
                   str(self.tmp / "ruffcache"), str(one_py)] if self.ruff else None)], "wall", runs * 2,
                 keep_results=True)
        self.row(f"lint, {n_m:,} lines in {len(many)} files, unchanged (result cache)",
                 ["lint", "--exit-zero", "-q", str(self.tmp / "many10k")],
                 [("flake8", f8([self.tmp / "many10kpy"])), ("ruff (its cache)", self.ruff + [
                     "check", "--exit-zero", "-q", "--cache-dir", str(self.tmp / "ruffcache"),
                     str(self.tmp / "many10kpy")] if self.ruff else None)], "cpu", runs, n_m, keep_results=True)
        self.row("lint, bundle corpus", ["lint", "--exit-zero", "-q", str(bundle_root())],
                 [("ruff check", ruff_check(py_b))], "wall", runs)
        self.cold_row(one, runs)
        self.row(f"fmt --check, bundle corpus ({n_b:,} lines)", ["fmt", "--check", "-q", str(bundle_root())],
                 [("black", self.black + ["--check", "-q", *map(str, py_b)] if self.black else None),
                  ("ruff format", self.ruff + ["format", "--check", "--no-cache", "-q", *map(str, py_b)]
                   if self.ruff else None)], "cpu", runs, n_b)
        self.row("fmt --check, one 117-line file", ["fmt", "--check", "-q", str(one)],
                 [("black", self.black + ["--check", "-q", str(one_py)] if self.black else None),
                  ("ruff format", self.ruff + ["format", "--check", "--no-cache", "-q", str(one_py)]
                   if self.ruff else None)], "wall", runs * 2)
        w = medians([([sys.executable, "-c", "pass"], None), ([sys.executable, "-S", "-c", "pass"], None)], runs * 2)
        self.rows.append(("python -c pass (python -S -c pass)", "wall", "", "", f"{w[0][0]:.3f} s ({w[1][0]:.3f} s)",
                          "", ""))

    def cold_row(self, one: Path, runs: int) -> None:
        """A first run (no plx cache at all) against a warm one, same file."""
        colds, warms = [], []
        for k in range(runs):
            env = dict(self.env, PLX_CACHE_DIR=str(self.tmp / f"cold{k}"))
            colds.append(run(self.plx + ["lint", "--exit-zero", "-q", str(one)], env)[0])
            forget_results(env)  # warm: the bundle program is cached, the file is checked again
            warms.append(run(self.plx + ["lint", "--exit-zero", "-q", str(one)], env)[0])
        c, w = statistics.median(colds), statistics.median(warms)
        self.rows.append(("lint cold (no cache) vs warm, one file", "wall", f"{c:.3f} s / {w:.3f} s", "", "-",
                          f"{c / w:.1f}", ""))
        print(f"  cold {c:.3f} s, warm {w:.3f} s", file=sys.stderr, flush=True)

    def scaling_rows(self) -> None:
        sizes = [s for s in (1_000, 10_000, 100_000, 1_000_000) if s <= self.args.max]
        for n in sizes:
            runs = 3 if n <= 10_000 else 1
            if self.args.quick:
                runs = 1
            src = self.tmp / f"one_{n}.openplx"
            src.write_text(corpus.openplx_file(n))
            py = self.tmp / f"one_{n}.py"
            py.write_text(corpus.python_file(n))
            lines = count_lines([src])
            f8 = self.flake8 + ["--exit-zero", str(py)] if self.flake8 else None
            rc = self.ruff + ["check", "--exit-zero", "--no-cache", "-q", str(py)] if self.ruff else None
            for measure in ("cpu", "peak"):
                self.row(f"lint, one file of {lines:,} lines", ["lint", "--exit-zero", "-q", str(src)],
                         [("flake8", f8), ("ruff", rc)] if n <= 100_000 or measure == "cpu" else [("ruff", rc)],
                         measure, runs, lines)
            self.row(f"fmt --check, one file of {lines:,} lines", ["fmt", "--check", "-q", str(src)],
                     [("black", self.black + ["--check", "-q", str(py)] if self.black else None),
                      ("ruff format", self.ruff + ["format", "--check", "--no-cache", "-q", str(py)]
                       if self.ruff else None)], "cpu", runs, lines)
            folder, pyfolder = self.tmp / f"many_{n}", self.tmp / f"many_{n}_py"
            many = corpus.openplx_files(folder, n)
            corpus.python_files(pyfolder, n)
            lines = count_lines(many)
            for measure in ("cpu", "peak"):
                self.row(f"lint, {lines:,} lines in {len(many):,} files", ["lint", "--exit-zero", "-q", str(folder)],
                         [("flake8", self.flake8 + ["--exit-zero", str(pyfolder)] if self.flake8 else None),
                          ("ruff", self.ruff + ["check", "--exit-zero", "--no-cache", "-q", str(pyfolder)]
                           if self.ruff else None)], measure, runs, lines)
            src.unlink()
            py.unlink()
            shutil.rmtree(folder)
            shutil.rmtree(pyfolder)

    def lsp_row(self) -> None:
        """Start of `plx lsp` to the `initialize` reply (median), no peer."""
        init = {"jsonrpc": "2.0", "id": 1, "method": "initialize",
                "params": {"processId": None, "rootUri": REPO.as_uri(), "capabilities": {}}}
        body = json.dumps(init).encode()
        frame = b"Content-Length: %d\r\n\r\n" % len(body) + body
        times = []
        for _ in range(self.args.runs * 2):
            t = time.perf_counter()
            proc = subprocess.Popen(self.plx + ["lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                    stderr=subprocess.DEVNULL, env=self.env, cwd=REPO)
            proc.stdin.write(frame)
            proc.stdin.flush()
            header = proc.stdout.readline()
            times.append(time.perf_counter() - t)
            proc.kill()
            proc.wait()
            if not header.startswith(b"Content-Length"):
                raise SystemExit("plx lsp gave no reply to initialize")
        self.rows.append(("plx lsp: start to initialize reply", "wall", f"{statistics.median(times):.3f} s", "", "-",
                          "", ""))
        print(f"  lsp initialize {statistics.median(times):.3f} s", file=sys.stderr, flush=True)

    def simulate_rows(self) -> None:
        """`plx check --simulate` against bare MuJoCo stepping the exported model (whole processes)."""
        try:
            import mujoco  # noqa: F401
        except ImportError:
            self.rows.append(("check --simulate", "wall", "", "", "mujoco not installed", "", ""))
            return
        truck = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
        many = self.tmp / "trucks100.openplx"
        many.write_text(trucks(100))
        floor = ("import sys, mujoco\nm = mujoco.MjModel.from_xml_path(sys.argv[1])\nd = mujoco.MjData(m)\n"
                 "mujoco.mj_resetDataKeyframe(m, d, 0) if m.nkey else None\n"
                 "mujoco.mj_step(m, d, nstep=int(sys.argv[2]))\n")
        script = self.tmp / "floor.py"
        script.write_text(floor)
        for src, n, dur in ((truck, 1, 5.0), (truck, 1, 60.0), (many, 100, 10.0)):
            xml = self.tmp / f"{src.stem}.xml"
            run(self.plx + ["check", str(src), "--export-mjcf", str(xml)], self.env)
            steps = int(round(dur / 0.002))
            runs = self.args.runs if dur * n <= 60 else 1
            self.row(f"check --simulate, {n} truck{'s' if n > 1 else ''} for {dur:g} s",
                     ["check", str(src), "--simulate", "--duration", str(dur)],
                     [("bare MuJoCo (python + import + load + step)", [sys.executable, str(script), str(xml),
                                                                       str(steps)])], "wall", runs)


def trucks(n: int) -> str:
    """The BoxTruck example with `n` trucks in a grid on a larger plate."""
    src = (REPO / "examples" / "boxtruck" / "boxtruck.openplx").read_text()
    head = src[:src.index("Scene is Physics3D.System:")]
    head = head.replace("            x: 100\n            y: 100\n", "            x: 200\n            y: 200\n", 1)
    rows = []
    for k in range(n):
        x, y = (k % 10) * 6.0 - 27, (k // 10) * 5.0 - 22.5
        rows.append(f"    truck{k} is BoxTruck:\n        chassis.kinematics.local_transform.position.x: {x}\n"
                    f"        chassis.kinematics.local_transform.position.y: {y}\n")
    return head + "Scene is Physics3D.System:\n" + "".join(rows) + "    ground is GroundPlate\n" \
        "    tire_contact is TireOnPlate\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5, help="runs per small measurement (median)")
    ap.add_argument("--max", type=int, default=100_000, help="largest corpus in lines (1000000 for 1M)")
    ap.add_argument("--quick", action="store_true", help="1 run per size up to 10k lines")
    ap.add_argument("--baseline", metavar="DIR", help="a plxtools checkout to run as the 'before' column")
    ap.add_argument("--only", choices=("issue", "scaling", "lsp", "simulate"), action="append",
                    help="run only these groups (repeatable)")
    args = ap.parse_args()
    if args.quick:
        args.runs, args.max = 1, min(args.max, 10_000)
    b = Bench(args)
    groups = args.only or ["issue", "scaling", "lsp", "simulate"]
    try:
        b.warm()
        if "issue" in groups:
            b.issue_rows()
        if "scaling" in groups:
            b.scaling_rows()
        if "lsp" in groups:
            b.lsp_row()
        if "simulate" in groups:
            b.simulate_rows()
    finally:
        shutil.rmtree(b.tmp, ignore_errors=True)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"Measured {datetime.date.today().isoformat()} on {platform.machine()} {platform.system()}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}, load average {load:.1f} at the end; "
          f"medians of {args.runs} (big sizes: 1 run)")
    headers = ("what", "measure", "plx", "baseline" if args.baseline else "", "peer", "plx / peer", "lines per CPU-s")
    print(table(b.rows, headers))


if __name__ == "__main__":
    main()
