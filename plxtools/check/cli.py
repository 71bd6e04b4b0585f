"""The `plx check` command body: files -> pipeline -> report.

Exit codes: 0 no error diagnostics; 1 error diagnostics (unless --exit-zero); 2 usage errors, a
requested artefact (--render / --export-mjcf) that could not be written, or an internal error.
"""

from __future__ import annotations

import json
import math
import os
import sys
import traceback
from pathlib import Path

from plxtools.diagnostics import Severity


MAX_DURATION = 3600.0  # s of simulated time; a longer run is a usage error, not an hour-long job
DEFAULT_TIMEOUT = 300.0  # s of wall-clock time per file's simulation


def _artefact_path(template: str, index: int, count: int) -> Path:
    p = Path(template)
    if count <= 1:
        return p
    return p.with_name(f"{p.stem}-{index + 1}{p.suffix}")


def run_check(args) -> int:
    from plxtools.check.pipeline import Skip, analyse, blocking_reason, run_backend
    from plxtools.config import ConfigError, config_for
    from plxtools.discovery import UsageError, discover

    if args.duration is not None and not (math.isfinite(args.duration) and 0 < args.duration <= MAX_DURATION):
        print(f"plx check: --duration must be a number of seconds in (0, {MAX_DURATION:g}]; got {args.duration:g}",
              file=sys.stderr)
        return 2
    timeout = getattr(args, "timeout", None)
    if timeout is None:
        timeout = DEFAULT_TIMEOUT
    elif not (math.isfinite(timeout) and timeout > 0):
        print(f"plx check: --timeout must be a positive number of seconds; got {timeout:g}", file=sys.stderr)
        return 2
    trace = getattr(args, "trace", None)
    if trace:
        args.simulate = True
    want_backend = bool(args.simulate or args.render or args.export_mjcf)
    try:
        files = discover(args.paths)
    except (UsageError, ConfigError) as exc:
        print(f"plx check: {exc}", file=sys.stderr)
        return 2
    try:
        from plxtools.model.workspace import workspace_for_cli

        workspace = workspace_for_cli(args.bundle_path, files, openplx_version=getattr(args, "openplx_version", None))
    except (UsageError, ConfigError, ValueError) as exc:
        print(f"plx check: {exc}", file=sys.stderr)
        return 2
    note = workspace.bundle_set.announcement()
    if note and args.output_format == "text":
        print(f"plx check: {note}", file=sys.stderr)
    results = []
    status = 0
    for f in files:
        try:
            cfg = config_for(f)
        except ConfigError as exc:
            print(f"plx check: {exc}", file=sys.stderr)
            return 2
        try:
            fc = analyse(f, workspace, cfg, model=args.model)
            if want_backend and fc.scene is not None:
                reason = blocking_reason(fc)
                if reason is None:
                    run_backend(fc, simulate=bool(args.simulate), duration=args.duration, record=bool(trace),
                                timeout=timeout)
                else:
                    fc.skip, fc.skip_detail = Skip.BLOCKED, reason
        except Exception as exc:  # a bug in plxtools: say so, go on with the other files
            print(f"plx check: internal error while checking {f}: {type(exc).__name__}: {exc}", file=sys.stderr)
            if os.environ.get("PLX_DEBUG"):
                traceback.print_exc()
            from plxtools.check.pipeline import FileCheck

            fc = FileCheck(str(f), skip=Skip.INTERNAL, internal_error=str(exc))
            status = 2
        results.append(fc)
    status = max(status, _artefacts(args, results))
    diags = [d for fc in results for d in fc.diagnostics]
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
    if status:
        return status
    has_error = any(d.severity == Severity.ERROR for d in diags)
    return 0 if (args.exit_zero or not has_error) else 1


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
                           ("trace", getattr(args, "trace", None))):
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
            if fc.compiled is None or not fc.compiled.ok:
                why = fc.skipped if fc.compiled is None and fc.skipped else "the scene did not compile to MuJoCo"
                print(f"plx check: {fc.path}: cannot write {out}: {why}", file=sys.stderr)
                status = 2
                continue
            try:
                if kind == "export":
                    from plxtools.check.mujoco_backend import ExportError, export_mjcf

                    try:
                        export_mjcf(fc.compiled, str(out))
                    except ExportError as exc:
                        _report_note(fc, exc.note)
                        print(f"plx check: {fc.path}: did not write {out}: MuJoCo cannot load it back "
                              f"(see {exc.note.code})", file=sys.stderr)
                        status = 2
                else:
                    from plxtools.check.mujoco_backend import RenderUnavailable, render_png

                    try:
                        render_png(fc.compiled, str(out))
                    except RenderUnavailable as exc:
                        print(f"plx check: cannot render {out}: {exc}", file=sys.stderr)
                        status = 2
            except OSError as exc:
                print(f"plx check: cannot write {out}: {exc.strerror or exc}", file=sys.stderr)
                status = 2
    return status


def _write_trace(fc, out: Path) -> int:
    from plxtools.check.trace_file import TraceWriteError, write_trace

    sim = fc.simulation
    if sim is None or sim.trace is None:
        why = fc.skipped or "the scene was not simulated"
        print(f"plx check: {fc.path}: cannot write {out}: {why}", file=sys.stderr)
        return 2
    try:
        write_trace(sim.trace, out)
    except TraceWriteError as exc:
        print(f"plx check: cannot write {out}: {exc}", file=sys.stderr)
        return 2
    return 0


def _report_note(fc, note) -> None:
    """A located diagnostic for a backend note met after the check (an export that does not reload)."""
    from plxtools.check.pipeline import add_backend_notes, refresh

    add_backend_notes(fc.rep, fc.tree, [note])
    refresh(fc)
