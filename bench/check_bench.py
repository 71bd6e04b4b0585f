"""Benchmark: `plx check --simulate` next to bare MuJoCo stepping the model plx exports (issue 17,
goal 5).

    python bench/check_bench.py [--runs 5] [--cases 1x5,1x60,100x10] [--keep DIR] [--compare DIR]
                                [--baseline DIR]
    python bench/check_bench.py --many 8x5,4x5,8x0 [--runs 5] [--jobs 2]

For each case ``TRUCKSxSECONDS`` (1 is examples/boxtruck; N > 1 is that truck N times on a larger
plate, the scene bench/perf_table.py uses, written here as ``trucksN.openplx``), measured as
whole processes, interleaved, median of --runs:

1. ``plx check FILE --simulate --duration SECONDS --output-format json``: the whole tool (Python
   start, bundle loading, lint, instantiation, SNAP, checks, MuJoCo compile, the monitored run,
   report);
2. the peer: ``python -c`` importing MuJoCo, loading the MJCF that ``plx check --export-mjcf``
   wrote for the same scene and stepping it the same number of steps (``mj_step(nstep=...)``).

CPU seconds of each child (``wait4`` rusage: user + system) are the figure compared, because the
machine is shared; wall seconds are printed beside them.  Both run with bytecode caches (plxtools
is byte-compiled first, as an installed tool is).  Goal: plx within 2x of the peer.  The
JSON reports of the plx runs are kept in --keep DIR (``<case>.json``) for comparing two commits:
``--compare DIR`` checks them against the reports an earlier run kept there (everything but the
timings and file paths must be equal).  ``--baseline DIR`` adds the plx of another checkout (e.g.
``git archive`` of the commit before) as a third interleaved column, with its own cache folder.

``--many SCENESxSECONDS,...`` measures instead the worker pool on many scenes (issue 17, goal 5:
"compiling/stepping many scenes uses both cores"): SCENES BoxTruck variants (each drives its motors
at another speed), one folder, ``plx check --simulate --duration SECONDS`` (SECONDS 0: no
``--simulate``, the check alone) with ``--jobs 1`` (the serial loop, the peer) and with
``--jobs auto`` (or ``--jobs N``), interleaved; wall and CPU (the workers' included) of each, the
speed-up in wall time, and whether the JSON reports are identical but for timings.  The load
average is printed before and after: on a shared machine the second core may be busy.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
MODEL = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
sys.path.insert(0, str(Path(__file__).resolve().parent))

FLOOR_SCRIPT = """
import sys, mujoco
m = mujoco.MjModel.from_xml_path(sys.argv[1])
d = mujoco.MjData(m)
if m.nkey:
    mujoco.mj_resetDataKeyframe(m, d, 0)
mujoco.mj_step(m, d, nstep=int(sys.argv[2]))
print(d.time)
"""


# runs `plx` from another checkout: the editable install's import hook would otherwise win over
# PYTHONPATH and run this checkout again
BASELINE_RUNNER = (
    "import sys; sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f)]; "
    "sys.path.insert(0, __import__('os').path.abspath(sys.argv[1])); del sys.argv[1]; sys.argv[0] = 'plx'; "
    "from plxtools.cli import entry; entry()"
)


def plx_command() -> list[str]:
    exe = Path(sys.executable).parent / "plx"
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "plxtools"]


def interleaved(runs: int, *commands) -> list[tuple[list[float], list[float]]]:
    """(walls, CPUs) of each (command, env), run in turn `runs` times so machine load affects all alike."""
    got = [([], []) for _ in commands]
    for _ in range(runs):
        for (cmd, env), (walls, cpus) in zip(commands, got):
            w, c = child(cmd, env)
            walls.append(w)
            cpus.append(c)
    return got


def child(cmd: list[str], env: dict, out: Path | None = None) -> tuple[float, float]:
    """(wall s, CPU s) of one process; its stdout goes to ``out`` (or nowhere)."""
    t = time.perf_counter()
    with open(out, "wb") if out else open(os.devnull, "wb") as fh:
        p = subprocess.Popen(cmd, stdout=fh, stderr=subprocess.PIPE, env=env, cwd=REPO)
        _, status, ru = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        err = p.stderr.read().decode(errors="replace")
        p.stderr.close()
    wall = time.perf_counter() - t
    if p.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({p.returncode}):\n{err}")
    return wall, ru.ru_utime + ru.ru_stime


TIMINGS = {"wall_time_s", "compile_ms", "timings", "file"}  # and the path, a temporary folder


def _untimed(x):
    if isinstance(x, dict):
        return {k: _untimed(v) for k, v in x.items() if k not in TIMINGS}
    if isinstance(x, list):
        return [_untimed(v) for v in x]
    return x


def same_report(a: Path, b: Path) -> bool:
    return _untimed(json.loads(a.read_text())) == _untimed(json.loads(b.read_text()))


def scene_file(trucks: int, tmp: Path) -> Path:
    if trucks == 1:
        return MODEL
    from perf_table import trucks as many_trucks

    path = tmp / f"trucks{trucks}.openplx"
    path.write_text(many_trucks(trucks), encoding="utf-8")
    return path


def variants(n: int, tmp: Path) -> Path:
    """A folder of n BoxTruck variants: the same scene, the motors' target speeds scaled."""
    folder = tmp / f"scenes{n}"
    if folder.is_dir():
        return folder
    folder.mkdir()
    text = MODEL.read_text(encoding="utf-8")
    for i in range(n):
        scale = 1.0 + 0.25 * i
        v = text.replace("target_speed: 1\n", f"target_speed: {scale:g}\n")
        v = v.replace("target_speed: -1\n", f"target_speed: {-scale:g}\n")
        (folder / f"truck{i + 1:02}.openplx").write_text(v, encoding="utf-8")
    return folder


def many(args, runs: int, env: dict) -> int:
    try:
        cases = [(int(a), float(b)) for a, b in (c.lower().split("x") for c in args.many.split(","))]
    except ValueError:
        raise SystemExit(f"--many: expected SCENESxSECONDS,...; got {args.many!r}")
    plx = plx_command()
    load0 = os.getloadavg()
    rows = []
    med = statistics.median
    with tempfile.TemporaryDirectory() as tmp_s:
        tmp = Path(tmp_s)
        for n, seconds in cases:
            folder = variants(n, tmp)
            base = [*plx, "check", "--output-format", "json", str(folder)]
            if seconds > 0:
                base[2:2] = ["--simulate", "--duration", f"{seconds:g}"]
            serial, pool = base + ["--jobs", "1"], base + ["--jobs", args.jobs]
            a, b = tmp / "serial.json", tmp / "pool.json"
            child(serial, env, a)  # warm the caches
            child(pool, env, b)
            same = same_report(a, b)
            (sw, sc), (pw, pc) = interleaved(runs, (serial, env), (pool, env))
            rows.append((n, seconds, med(sw), med(sc), med(pw), med(pc), same))
            print(f"  {n} x {seconds:g} s: serial {med(sw):.3f} s wall / {med(sc):.3f} s CPU, "
                  f"pool {med(pw):.3f} s wall / {med(pc):.3f} s CPU", file=sys.stderr, flush=True)
    load1 = os.getloadavg()
    print(f"{time.strftime('%Y-%m-%d')}, {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load average {load0[0]:.1f} before, {load1[0]:.1f} after, Python {sys.version.split()[0]}; "
          f"median of {runs} interleaved runs; pool: --jobs {args.jobs}")
    print()
    # cores used = CPU / wall: what the run got of the machine (near 1 serial on an idle machine,
    # near 2 for the pool on 2 idle cores; less when other processes hold the cores)
    print("| scenes | simulated each | serial (--jobs 1) wall s | CPU s | cores used | pool wall s | CPU s "
          "| cores used | speed-up (wall) | reports identical |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for n, seconds, s_w, s_c, p_w, p_c, same in rows:
        what = f"{seconds:g} s" if seconds > 0 else "not simulated"
        print(f"| {n} | {what} | {s_w:.3f} | {s_c:.3f} | {s_c / s_w:.2f} | {p_w:.3f} | {p_c:.3f} | {p_c / p_w:.2f} "
              f"| {s_w / p_w:.2f}x | {'yes' if same else 'NO'} |")
    return 0 if all(r[-1] for r in rows) else 1


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5, help="runs per measurement (median reported; >= 3)")
    ap.add_argument("--cases", default="1x5,1x60,100x10",
                    help="comma-separated TRUCKSxSECONDS (default 1x5,1x60,100x10)")
    ap.add_argument("--keep", metavar="DIR", help="keep the JSON report of each case here")
    ap.add_argument("--baseline", metavar="DIR", help="a plxtools checkout to run as a 'before' column")
    ap.add_argument("--compare", metavar="DIR", help="compare the reports with those an earlier --keep wrote here")
    ap.add_argument("--many", metavar="SCENESxSECONDS,...",
                    help="measure the worker pool on many scenes instead (see above), e.g. 8x5,4x5,8x0")
    ap.add_argument("--jobs", default="auto", help="with --many: the pool's --jobs (default auto)")
    args = ap.parse_args()
    runs = max(3, args.runs)
    try:
        cases = [(int(a), float(b)) for a, b in (c.lower().split("x") for c in args.cases.split(","))]
    except ValueError:
        ap.error(f"--cases: expected TRUCKSxSECONDS,...; got {args.cases!r}")
    env = dict(os.environ, NO_COLOR="1")
    # bytecode is cached, as for any installed tool (a sandbox may turn it off for everything)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(REPO / "plxtools")]
                   + ([str(Path(args.baseline) / "plxtools")] if args.baseline else []), env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if args.many:
        return many(args, runs, env)
    plx = plx_command()
    base_env = None
    if args.baseline:
        base_env = dict(env, PLX_CACHE_DIR=str(Path(tempfile.gettempdir()) / "plx-check-bench-baseline-cache"))
    import mujoco

    keep = Path(args.keep) if args.keep else None
    if keep:
        keep.mkdir(parents=True, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as tmp_s:
        tmp = Path(tmp_s)
        for trucks, seconds in cases:
            src = scene_file(trucks, tmp)
            xml = tmp / f"{src.stem}.xml"
            subprocess.run([*plx, "check", "--export-mjcf", str(xml), str(src)], capture_output=True, env=env,
                           cwd=REPO)
            if not xml.is_file():
                raise SystemExit(f"export of {src} failed")
            steps = int(round(seconds / mujoco.MjModel.from_xml_path(str(xml)).opt.timestep))
            check = [*plx, "check", "--simulate", "--duration", f"{seconds:g}", "--output-format", "json", str(src)]
            floor = [sys.executable, "-c", FLOOR_SCRIPT, str(xml), str(steps)]
            report = (keep or tmp) / f"{trucks}x{seconds:g}.json"
            child(check, env, report)  # warm the caches; the report of this run is kept
            sim = next(iter(json.loads(report.read_text())["simulation"].values()))
            if args.compare:
                ref = Path(args.compare) / report.name
                verdict = ("identical" if same_report(ref, report) else "DIFFERENT") if ref.is_file() else "missing"
                print(f"  {report.name}: report {verdict} to {ref}", file=sys.stderr, flush=True)
            assert sim["steps"] == steps, (sim["steps"], steps)
            child(floor, env)
            base = None
            if base_env is not None:
                base = [sys.executable, "-c", BASELINE_RUNNER, args.baseline, *check[len(plx):]]
                child(base, base_env)
            timed = interleaved(runs, (check, env), (floor, env), *([(base, base_env)] if base else []))
            (c_wall, c_cpu), (f_wall, f_cpu) = timed[:2]
            b_cpu = timed[2][1] if base else []
            med = statistics.median
            rows.append((trucks, seconds, steps, med(c_cpu), med(f_cpu), med(c_wall), med(f_wall),
                         sim["wall_time_s"], med(b_cpu) if b_cpu else None))
            print(f"  {trucks} x {seconds:g} s: plx {med(c_cpu):.3f} s CPU, bare MuJoCo {med(f_cpu):.3f} s CPU"
                  + (f", baseline {med(b_cpu):.3f} s CPU" if b_cpu else ""), file=sys.stderr, flush=True)

    print(f"{time.strftime('%Y-%m-%d')}, {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.1f}, Python {sys.version.split()[0]}, MuJoCo {mujoco.__version__}; "
          f"median of {runs} interleaved runs")
    print()
    bl = " baseline CPU s (ratio) |" if args.baseline else ""
    print("| scene | simulated | plx check --simulate CPU s | bare MuJoCo CPU s (python + import + load + steps) "
          f"| ratio | goal <= 2x |{bl} wall s plx / bare | monitored loop in plx (warm-up run), wall s |")
    print("|---|---|---:|---:|---:|---|" + ("---:|" if args.baseline else "") + "---|---:|")
    for trucks, seconds, steps, c_cpu, f_cpu, c_wall, f_wall, loop, b_cpu in rows:
        ratio = c_cpu / f_cpu
        bc = f" {b_cpu:.3f} ({b_cpu / f_cpu:.2f}) |" if b_cpu is not None else ""
        print(f"| {trucks} truck{'s' if trucks > 1 else ''} | {seconds:g} s ({steps} steps) | {c_cpu:.3f} | "
              f"{f_cpu:.3f} | {ratio:.2f} | {'OK' if ratio <= 2 else 'MISSED'} |{bc} {c_wall:.3f} / {f_wall:.3f} | "
              f"{loop:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
