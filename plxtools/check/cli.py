"""The `plx check` command body: files -> pipeline -> report.

Exit codes: 0 no error diagnostics; 1 error diagnostics (unless --exit-zero); 2 usage errors, a
requested artefact (--render / --export-mjcf) that could not be written, or an internal error.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from plxtools import runmode
from plxtools.diagnostics import Severity, printable


MAX_DURATION = 3600.0  # s of simulated time; a longer run is a usage error, not an hour-long job
DEFAULT_TIMEOUT = 300.0  # s of wall-clock time per file's simulation


def _artefact_path(template: str, index: int, count: int) -> Path:
    p = Path(template)
    if count <= 1:
        return p
    return p.with_name(f"{p.stem}-{index + 1}{p.suffix}")


class _UsageError(Exception):
    """A bad command line, path, configuration or bundle set: said on stderr, exit status 2."""


def run_check(args) -> int:
    try:
        timeout = _options(args)
        files, workspace = _inputs(args)
        note = workspace.bundle_set.announcement()
        if note and args.output_format == "text":
            print(f"plx check: {note}", file=sys.stderr)
        run = _Run(workspace, args.model, bool(args.simulate or args.render or args.export_mjcf),
                   bool(args.simulate), args.duration, bool(getattr(args, "trace", None)), timeout,
                   getattr(args, "integrator", None), getattr(args, "timestep", None))
        from plxtools.progress import Bar

        with Bar(len(files), "check --simulate" if run.simulate else "check",
                 output_format=args.output_format) as bar:
            report = _Streamed(args) if bar.on and _stdout_is_terminal() else None
            results, status = _check_files(files, args, run, bar, report)
    except _UsageError as exc:
        print(f"plx check: {exc}", file=sys.stderr)
        return 2
    status = max(status, _artefacts(args, results))
    diags = [d for fc in results for d in fc.diagnostics]
    if report is not None:
        from plxtools.check.output import render_summary

        render_summary(results, diags, sys.stdout)
    else:
        _report(args, results, diags)
    if status:
        return status
    has_error = any(d.severity == Severity.ERROR for d in diags)
    return 0 if (args.exit_zero or not has_error) else 1


def _options(args) -> float:
    """Check the numbers given on the command line (--duration, --timeout, --timestep, --fps and
    the --video target); --trace and --video imply --simulate.  Returns the timeout."""
    from plxtools import envpath

    if args.duration is not None and not (math.isfinite(args.duration) and 0 < args.duration <= MAX_DURATION):
        raise _UsageError(f"--duration must be a number of seconds in (0, {MAX_DURATION:g}]; got {args.duration:g}")
    envpath.show_values(getattr(args, "show_env", False))  # set before any worker process forks
    timeout = getattr(args, "timeout", None)
    if timeout is None:
        timeout = DEFAULT_TIMEOUT
    elif not (math.isfinite(timeout) and timeout > 0):
        raise _UsageError(f"--timeout must be a positive number of seconds; got {timeout:g}")
    timestep = getattr(args, "timestep", None)
    if timestep is not None and not (math.isfinite(timestep) and 1e-5 <= timestep <= 0.1):
        raise _UsageError(f"--timestep must be a number of seconds in [1e-5, 0.1]; got {timestep:g}")
    if getattr(args, "trace", None):
        args.simulate = True
    video = getattr(args, "video", None)
    if video:
        from plxtools.check.mujoco.video import VideoError, check_fps, check_target

        args.simulate = True
        try:
            check_target(video)
            check_fps(args.fps)
        except VideoError as exc:
            raise _UsageError(str(exc)) from None
    return timeout


def _inputs(args) -> tuple[list[Path], Any]:
    """The files to check and the workspace (bundles) they are checked in."""
    from plxtools.config import ConfigError
    from plxtools.discovery import UsageError, discover

    try:
        files = discover(args.paths)
    except (UsageError, ConfigError) as exc:
        raise _UsageError(str(exc)) from None
    try:
        from plxtools.model.workspace import workspace_for_cli

        workspace = workspace_for_cli(args.bundle_path, files, openplx_version=getattr(args, "openplx_version", None))
    except (UsageError, ConfigError, ValueError) as exc:
        raise _UsageError(str(exc)) from None
    return files, workspace


def _stdout_is_terminal() -> bool:
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):
        return False


class _Streamed:
    """On a terminal, each file's text report is printed as soon as the file is done (the summary
    of all of them at the end)."""

    def __init__(self, args):
        self.simulate = bool(args.simulate)

    def __call__(self, fc) -> None:
        from plxtools.check.output import render_text

        render_text([fc], list(fc.diagnostics), sys.stdout, simulate=self.simulate, summary=False)
        sys.stdout.flush()


def _check_files(files: list[Path], args, run: "_Run", bar=None, report=None) -> tuple[list, int]:
    """Every file's FileCheck, in order, by the pool of workers or one by one here; their messages
    go to stderr as each comes (and, with `report`, each file's report).  A file's broken
    configuration stops the run (_UsageError)."""
    from plxtools.config import ConfigError, config_for

    def done(entry: tuple, index: int) -> None:
        _say(entry[1])
        if report is not None:
            report(entry[0])
        if bar is not None:
            bar.advance(files[index + 1].name if index + 1 < len(files) else "")

    parallel = _in_parallel(files, args, run, done)
    if parallel is None:
        parallel = []
        for i, f in enumerate(files):
            try:
                cfg = config_for(f)
            except ConfigError as exc:
                raise _UsageError(str(exc)) from None
            parallel.append(_check_one((f, cfg), run))
            done(parallel[-1], i)
    return [fc for fc, _m, _st in parallel], max((st for _fc, _m, st in parallel), default=0)


def _say(messages: list[str]) -> None:
    for m in messages:
        sys.stderr.write(printable(m))


def _report(args, results: list, diags: list) -> None:
    """The report on stdout, in --output-format."""
    fmt = args.output_format
    if fmt == "json":
        from plxtools.check.output import document

        json.dump(document(results, diags, bool(args.simulate)), sys.stdout, indent=2, allow_nan=False,
                  default=_json_default)
        sys.stdout.write("\n")
    elif fmt in ("github", "sarif"):
        from plxtools.rules.reporters import render

        render(diags, fmt, sys.stdout, files_checked=len(results))
    else:
        from plxtools.check.output import render_text

        render_text(results, diags, sys.stdout, simulate=bool(args.simulate))


@dataclass
class _Run:
    """What every file's check needs (inherited by the pool's workers)."""

    workspace: Any
    model: str | None
    want_backend: bool
    simulate: bool
    duration: float
    record: bool
    timeout: float
    integrator: str | None = None  # --integrator (wins over the config's check.integrator)
    timestep: float | None = None  # --timestep (wins over check.timestep)


def _check_one(item: tuple, run: _Run, analysed=None) -> tuple:
    """(FileCheck, messages for stderr, status) of one file: what the serial loop and a worker of
    the pool do alike (``analysed``: its analysis, done already). An exception is a bug in plxtools:
    it is reported and the other files go on."""
    from plxtools.check.pipeline import Skip, analyse, blocking_reason, run_backend

    f, cfg = item
    start = time.perf_counter()  # --timeout covers the file's whole check, not only the step loop
    try:
        fc = analysed if analysed is not None else analyse(f, run.workspace, cfg, model=run.model)
        if run.want_backend and fc.scene is not None:
            reason = blocking_reason(fc)
            if reason is None:
                if run.timestep is not None:
                    fc.scene.timestep = run.timestep
                if run.integrator is not None:
                    fc.scene.integrator = run.integrator
                run_backend(fc, simulate=run.simulate, duration=run.duration, record=run.record,
                            timeout=run.timeout, deadline=start + run.timeout)
            else:
                fc.skip, fc.skip_detail = Skip.BLOCKED, reason
        return fc, [], 0
    except Exception as exc:  # a bug in plxtools: say so, go on with the other files
        if runmode.interrupted():  # Ctrl-C, turned into another error by native code (MuJoCo)
            raise KeyboardInterrupt from exc
        return _internal_error(f, f"{type(exc).__name__}: {exc}", str(exc),
                               traceback.format_exc() if os.environ.get("PLX_DEBUG") else "")


def _internal_error(f: Path, said: str, detail: str, trace: str = "") -> tuple:
    from plxtools.check.pipeline import FileCheck, Skip

    messages = [f"plx check: internal error while checking {f}: {said}\n"] + ([trace] if trace else [])
    return FileCheck(str(f), skip=Skip.INTERNAL, internal_error=detail), messages, 2


# `plx check` runs many files on all cores (a pool of forked worker processes, plxtools/workpool.py)
# when the work after the first file is estimated at PARALLEL_MIN_WORK_S CPU seconds or more.
# Measured on a BoxTruck (bench/check_bench.py --many): checking a file costs about CHECK_S once the
# bundle program is warm, simulating it about SIMULATE_S per simulated second (bigger scenes cost
# more: they only reach the pool sooner); the pool itself costs 0.05 to 0.3 s of CPU (fork,
# copy-on-write of the inherited heap, each worker's first MuJoCo compile, pickling the reports).
# So: from 9 files without --simulate, from 4 files with the default 3 s, from 3 files of 5 s.
CHECK_S = 0.04
SIMULATE_S = 0.025
PARALLEL_MIN_WORK_S = 0.3
_RUN: _Run | None = None


def _workers(args, files: list[Path], run: _Run) -> int:
    """How many worker processes check files[1:] while this one does files[0] (0: the serial loop
    does it all)."""
    from plxtools import workpool

    jobs = getattr(args, "jobs", 0) or 0
    if len(files) < 2 or jobs == 1 or args.render or args.export_mjcf or getattr(args, "video", None) \
            or run.record or not workpool.can_fork():
        return 0  # the artefacts are written from the compiled models, which stay in this process
    if jobs > 1:
        return min(jobs, len(files) - 1)
    per_file = CHECK_S + (SIMULATE_S * (run.duration or 0.0) if run.simulate else 0.0)
    if workpool.cores() < 2 or per_file * (len(files) - 1) < PARALLEL_MIN_WORK_S:
        return 0
    return min(workpool.cores(), len(files) - 1)


def _in_parallel(files: list[Path], args, run: _Run, done=None) -> list | None:
    """Every file's (FileCheck, messages, status) in file order, computed by a pool of workers, or
    None when the serial loop is to do it (too little work, an artefact to write, a broken config:
    the loop then reports it where a serial run does)."""
    from plxtools.config import ConfigError, config_for

    workers = _workers(args, files, run)
    if not workers:
        return None
    try:
        items = [(f, config_for(f)) for f in files]
    except ConfigError:
        return None
    from plxtools import workpool
    from plxtools.check.pipeline import analyse

    global _RUN
    _RUN = run
    first: list = []
    try:
        # the first file is analysed here, before the fork, and numpy and MuJoCo imported: the workers
        # inherit them and what the analysis computed on the bundle program (member tables, evaluated
        # values); this process then runs the first file's backend while the workers check the rest
        try:
            fc = analyse(items[0][0], run.workspace, items[0][1], model=run.model)
        except Exception:  # a bug: _check_one meets it again and reports it as the serial loop does
            fc = None
        if run.want_backend:
            try:  # mujoco_backend imports mujoco only when it first compiles
                import mujoco  # noqa: F401

                import plxtools.check.mujoco.backend  # noqa: F401
            except ImportError:  # reported per file, as in the serial loop
                pass

        def meanwhile() -> None:
            first.append(_check_one(items[0], run, fc))
            if done is not None:
                done(first[0], 0)

        rest = workpool.map_ordered(_pool_item, items[1:], workers=workers,
                                    on_death=lambda item, why: _internal_error(item[0], why, why),
                                    meanwhile=meanwhile,
                                    on_result=None if done is None else lambda i, entry: done(entry, i + 1))
    finally:
        _RUN = None
    return [*first, *rest]


def _pool_item(item: tuple) -> tuple:
    """In a worker: one file, reduced to what the reports need (the rest does not pickle)."""
    fc, messages, status = _check_one(item, _RUN)
    return fc.for_report(), messages, status


def _json_default(o):
    try:
        import numpy as np

        if isinstance(o, np.generic):
            return o.item()
        if isinstance(o, np.ndarray):
            return o.tolist()
    except ImportError:  # pragma: no cover
        pass
    return str(o)


def _artefacts(args, results) -> int:
    status = 0
    targets = [fc for fc in results if fc.scene is not None]
    for kind, template in (("render", args.render), ("export", args.export_mjcf),
                           ("trace", getattr(args, "trace", None)), ("video", getattr(args, "video", None))):
        if not template:
            continue
        if not targets:
            print(f"plx check: nothing to {'render' if kind == 'render' else 'export'}: no file was assembled",
                  file=sys.stderr)
            status = 2
            continue
        for i, fc in enumerate(targets):
            out = _artefact_path(template, i, len(targets))
            if kind == "trace":
                status = max(status, _write_trace(fc, out))
                continue
            if kind == "video":
                status = max(status, _write_video(fc, out, args))
                continue
            if fc.compiled is None or not fc.compiled.ok:
                why = fc.skipped if fc.compiled is None and fc.skipped else "the scene did not compile to MuJoCo"
                print(f"plx check: {fc.path}: cannot write {out}: {why}", file=sys.stderr)
                status = 2
                continue
            try:
                if kind == "export":
                    from plxtools.check.mujoco.backend import ExportError, export_mjcf

                    try:
                        export_mjcf(fc.compiled, str(out))
                    except ExportError as exc:
                        _report_note(fc, exc.note)
                        print(f"plx check: {fc.path}: did not write {out}: MuJoCo cannot load it back "
                              f"(see {exc.note.code})", file=sys.stderr)
                        status = 2
                else:
                    from plxtools.check.mujoco.backend import RenderUnavailable, render_png

                    try:
                        render_png(fc.compiled, str(out))
                    except RenderUnavailable as exc:
                        print(f"plx check: cannot render {out}: {exc}", file=sys.stderr)
                        status = 2
            except OSError as exc:
                from plxtools.fileio import WriteError

                why = exc.strerror or str(exc)
                print(f"plx check: {why if isinstance(exc, WriteError) else f'cannot write {out}: {why}'}",
                      file=sys.stderr)
                status = 2
    return status


def _write_video(fc, out: Path, args) -> int:
    """Record the file's scene again from its initial state, offscreen, for --duration seconds."""
    from plxtools.check.mujoco.video import VideoError, record

    if fc.simulation is None or fc.compiled is None or not fc.compiled.ok:
        why = fc.skipped or "the scene was not simulated"
        print(f"plx check: {fc.path}: cannot write {out}: {why}", file=sys.stderr)
        return 2
    try:
        record(fc.compiled, str(out), args.duration, fps=args.fps, camera=getattr(args, "video_camera", "follow"))
    except VideoError as exc:
        print(f"plx check: cannot write {out}: {exc}", file=sys.stderr)
        return 2
    return 0


def _write_trace(fc, out: Path) -> int:
    from plxtools.check.trace_file import TraceWriteError, write_trace

    sim = fc.simulation
    if sim is None or sim.trace is None:
        why = fc.skipped or "the scene was not simulated"
        print(f"plx check: {fc.path}: cannot write {out}: {why}", file=sys.stderr)
        return 2
    try:
        write_trace(sim.trace, out)
    except TraceWriteError as exc:  # the message names the file and what happened
        print(f"plx check: {exc}", file=sys.stderr)
        return 2
    return 0


def _report_note(fc, note) -> None:
    """A located diagnostic for a backend note met after the check (an export that does not reload)."""
    from plxtools.check.pipeline import add_backend_notes, refresh

    add_backend_notes(fc.rep, fc.tree, [note])
    refresh(fc)
