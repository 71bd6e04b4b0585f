"""`plx fmt PATH...`: format files in place, or check, or diff, or stdin to stdout.

Messages go to stderr in black's words (`reformatted X`, `would reformat X`, a summary line), so
the stdout of `plx fmt -` and `--diff` holds nothing but the text or the diff. Exit codes: 0 done
or nothing to change, 1 with --check when a file would change, 2 on refused files, internal
errors and usage errors. Only the syntax layer is imported: no mujoco, numpy, pygls or rich.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

from plxtools.diagnostics import printable
from plxtools.config import ConfigError, config_for
from plxtools.fileio import write_atomic
from plxtools.discovery import UsageError, discover
from plxtools.fileio import unified_diff


@dataclass(slots=True)
class _Tally:
    changed: int = 0
    unchanged: int = 0
    failed: int = 0


def _say(msg: str) -> None:
    print(printable(msg), file=sys.stderr)


def _excluded(path: Path) -> bool:
    cfg = config_for(path)
    return cfg.is_excluded(path, cfg.exclude + cfg.fmt_exclude)


def collect_files(paths: list[str]) -> list[Path]:
    """Files to format. Excludes apply to named files too, so pre-commit honours them."""
    out: list[Path] = []
    seen: set[Path] = set()
    for raw in paths:
        p = Path(raw)
        if p.is_file():
            found = [] if _excluded(p) else [p]
        else:
            found = discover([raw], use_exclude="fmt")
        for f in found:
            if f not in seen:
                seen.add(f)
                out.append(f)
    return out


def _report_refusal(name: str, result) -> None:
    if result.internal_error is not None:
        _say(f"{name}: internal error: {result.internal_error}; the file was left unchanged")
        _say("This is a bug in plxtools; please report it with the file.")
        return
    for d in result.diagnostics:
        _say(f"{name}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.severity.value} {d.code} {d.message}")
    _say(f"{name}: not formatted: it has syntax errors")


def _format_file(path: Path, args, tally: _Tally, formatted: bool = False) -> None:
    """Format one file; with `formatted`, plx's cache remembers the contents already in canonical
    form (by their digest and plxtools' code stamp), so an unchanged, formatted file is not parsed
    again. The bytes keyed are the bytes formatted (read once)."""
    from plxtools.cache import reads

    name = str(path)
    try:
        data = reads.read_bytes(path, config_for(path).max_file_bytes)
    except (OSError, ConfigError) as exc:
        _say(f"{name}: cannot read: {getattr(exc, 'strerror', None) or exc}")
        tally.failed += 1
        return
    key = None
    if formatted:
        from plxtools.cache import store
        from plxtools.cache.stamp import code_stamp

        key = store.new_hash(code_stamp().encode() + b"\0fmt\0" + data).hexdigest()
        if store.get("formatted", key) == b"1":  # formatted already, byte for byte: nothing to do
            tally.unchanged += 1
            return
    from plxtools.fmt.api import format_bytes

    result = format_bytes(data, name)
    if key is not None and result.text is not None and not result.changed:
        store.put("formatted", key, b"1")
    if result.text is None:
        _report_refusal(name, result)
        tally.failed += 1
        return
    if not result.changed:
        tally.unchanged += 1
        return
    tally.changed += 1
    if args.diff:
        old = data.decode("utf-8-sig")
        sys.stdout.write(unified_diff(name, old, result.text))
    if args.check or args.diff:
        if not args.quiet:
            _say(f"would reformat {name}")
        return
    try:
        write_atomic(path, result.text, result.had_bom, expected=data)
    except OSError as exc:
        _say(exc.strerror or f"{name}: cannot write: {exc}")
        tally.changed -= 1
        tally.failed += 1
        return
    if not args.quiet:
        _say(f"reformatted {name}")


def _plural(n: int) -> str:
    return f"{n} file{'' if n == 1 else 's'}"


def _summary(tally: _Tally, dry: bool) -> str:
    parts = []
    if dry:
        if tally.changed:
            parts.append(f"{_plural(tally.changed)} would be reformatted")
        if tally.unchanged:
            parts.append(f"{_plural(tally.unchanged)} would be left unchanged")
        if tally.failed:
            parts.append(f"{_plural(tally.failed)} would fail to reformat")
    else:
        if tally.changed:
            parts.append(f"{_plural(tally.changed)} reformatted")
        if tally.unchanged:
            parts.append(f"{_plural(tally.unchanged)} left unchanged")
        if tally.failed:
            parts.append(f"{_plural(tally.failed)} failed to reformat")
    return (", ".join(parts) or "No .openplx files found") + "."


def _exit_code(tally: _Tally, check: bool) -> int:
    if tally.failed:
        return 2
    return 1 if check and tally.changed else 0


def _run_stdin(args) -> int:
    from plxtools.cache import reads

    name = args.stdin_filename or "-"
    try:
        cfg = config_for(Path(args.stdin_filename)) if args.stdin_filename else config_for(Path.cwd() / "-")
        data = reads.read_stream(sys.stdin.buffer, cfg.max_file_bytes)
    except (OSError, ConfigError) as exc:
        _say(f"{name}: cannot read: {getattr(exc, 'strerror', None) or exc}")
        return 2
    if args.stdin_filename and _excluded(Path(args.stdin_filename)):
        if not (args.check or args.diff):
            sys.stdout.buffer.write(data)
        return 0
    from plxtools.fmt.api import format_bytes

    result = format_bytes(data, name)
    if result.text is None:
        _report_refusal(name, result)
        return 2
    if args.diff and result.changed:
        sys.stdout.write(unified_diff(name, data.decode("utf-8-sig"), result.text))
    if args.check or args.diff:
        if result.changed and not args.quiet:
            _say(f"would reformat {name}")
        return 1 if args.check and result.changed else 0
    sys.stdout.buffer.write((("\ufeff" if result.had_bom else "") + result.text).encode("utf-8"))
    return 0


def run_fmt(args) -> int:
    paths = list(args.paths or ["."])
    try:
        if "-" in paths:
            if len(paths) > 1:
                raise UsageError("'-' (stdin) cannot be combined with other paths")
            return _run_stdin(args)
        files = collect_files(paths)
    except (UsageError, ConfigError) as exc:
        _say(f"plx fmt: {exc}")
        return 2
    from plxtools.gcpolicy import command_collector, file_done

    tally = _Tally()
    formatted = not getattr(args, "no_cache", False)
    with command_collector():
        for path in files:
            _format_file(path, args, tally, formatted)
            file_done()
    if not args.quiet or tally.failed:
        _say(_summary(tally, args.check or args.diff))
    if formatted and tally.unchanged == len(files):
        from plxtools import runmemo

        runmemo.allow()  # every file is formatted, every read recorded: the same reads give the same answer
    return _exit_code(tally, args.check)
