"""The `plx migrate --to VERSION PATH...` command: per file, the version it was written for, the
rewrite, and the write (or the diff, or the check)."""

from __future__ import annotations

import sys

from plxtools.config import ConfigError, config_for
from plxtools.discovery import UsageError, discover


def _say(text: str) -> None:
    print(text, file=sys.stderr)


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _left_for_a_person(path, fm, to_v: str) -> None:
    """What the migration could not do, located, with the help that says what changed."""
    shown = fm.left[:20]
    for d in shown:
        line, col = d.span.start.line + 1, d.span.start.column + 1
        _say(f"  {path}:{line}:{col}: {d.code} {d.message}" + (f"\n    help: {d.help}" if d.help else ""))
    if len(fm.left) > len(shown):
        _say(f"  ... and {len(fm.left) - len(shown)} more (plx lint --openplx-version {to_v} {path})")


class _Failed(Exception):
    """A user-facing failure (bad version, config, unreadable file): `plx migrate: <message>`, exit 2."""


class _Tally:
    """What the run did, for the closing line and the exit code."""

    def __init__(self):
        self.changed = self.refused = self.edits = self.partial = 0


def run_migrate(args) -> int:
    from plxtools.model.apiindex import UnknownVersion, check_version

    try:
        to_v = check_version(args.to)
        from_flag = check_version(args.from_version) if args.from_version else None
        files = discover(args.paths)
    except (UnknownVersion, UsageError, ConfigError, ValueError) as exc:
        _say(f"plx migrate: {exc}")
        return 2
    tally = _Tally()
    plans: dict[str, object] = {}
    try:
        for f in files:
            _migrate_file(f, args, from_flag, to_v, plans, tally)
    except _Failed as exc:
        _say(f"plx migrate: {exc}")
        return 2
    return _summary(args, tally, len(files))


def _inputs(f, from_flag: str | None, to_v: str):
    """A file's config, the version it was written for, its bytes and text, and the workspaces of
    both versions (raises `_Failed`)."""
    from plxtools.model.apiindex import UnknownVersion
    from plxtools.model.versions import BundleSetError, resolve_bundle_set
    from plxtools.model.workspace import workspace_for_set

    try:
        cfg = config_for(f)
        from_v = from_flag if from_flag is not None else _written_for(f)
        _forward_only(f, from_v, to_v)
        data = f.read_bytes()
        text = data.decode("utf-8-sig")
        from_ws = workspace_for_set(resolve_bundle_set([f], [], from_v))
        to_ws = workspace_for_set(resolve_bundle_set([f], [], to_v))
    except (UsageError, ConfigError, BundleSetError, UnknownVersion, ValueError) as exc:
        raise _Failed(exc) from exc
    except (OSError, UnicodeDecodeError) as exc:
        raise _Failed(f"{f}: cannot read it: {getattr(exc, 'strerror', None) or exc}") from exc
    return cfg, from_v, data, text, from_ws, to_ws


def _written_for(f) -> str:
    """The version the file is linted with today: config, a bundle's pin, else the installed one."""
    from plxtools.model.versions import BundleSetError, resolve_bundle_set

    from_v = resolve_bundle_set([f], [], None).official_version
    if from_v is None:
        raise BundleSetError(f"{f}: cannot tell which OpenPLX version it was written for; pass --from")
    return from_v


def _forward_only(f, from_v: str, to_v: str) -> None:
    from plxtools.model.apiindex import version_key

    if version_key(from_v) > version_key(to_v):
        raise UsageError(f"{f}: written for {from_v}, which is newer than --to {to_v} "
                         "(plx migrate only moves forward)")


def _migrate_file(f, args, from_flag: str | None, to_v: str, plans: dict, tally: _Tally) -> None:
    """Migrate one file (or show or check what would change) and say what happened."""
    from plxtools.migrate.rewrite import migrate_text, plan

    cfg, from_v, data, text, from_ws, to_ws = _inputs(f, from_flag, to_v)
    key = f"{from_v}->{to_v}"
    if key not in plans:
        plans[key] = plan(from_v, to_v)
    fm = migrate_text(f, text, plans[key], cfg, from_ws, to_ws)
    if fm.refused:
        tally.refused += 1
        _say(f"{f}: not migrated from {from_v} to {to_v}: {fm.refused}")
        _left_for_a_person(f, fm, to_v)
        return
    for note in fm.notes:
        _say(f"{f}: {note}")
    if fm.errors_after > fm.errors_before:
        tally.partial += 1  # the safe rewrites (if any) are applied; the rest is listed below
    if fm.changed:
        tally.changed += 1
        tally.edits += fm.edits
        _write(f, args, fm, data, f"{from_v} -> {to_v}", _remaining(fm, from_v))
    _left_for_a_person(f, fm, to_v)


def _remaining(fm, from_v: str) -> str:
    """`; N errors left for a person` (and how many the file had before) or nothing."""
    if not fm.errors_after:
        return ""
    remain = f"; {_plural(fm.errors_after, 'error')} left for a person"
    if fm.errors_after > fm.errors_before:
        remain += f" (under {from_v}: {fm.errors_before})"
    return remain


def _write(f, args, fm, data: bytes, step: str, remain: str) -> None:
    """The migrated text: as a diff (--diff), announced (--check), or written in place."""
    from plxtools.fileio import unified_diff, write_atomic

    if args.diff:
        sys.stdout.write(unified_diff(str(f), fm.old_text, fm.new_text))
    elif args.check:
        _say(f"would migrate {f} ({_plural(fm.edits, 'change')}, {step}){remain}")
    else:
        try:
            write_atomic(f, fm.new_text, data.startswith(b"\xef\xbb\xbf"), expected=data)
        except OSError as exc:
            raise _Failed(f"{f}: {exc.strerror}") from exc
        _say(f"migrated {f} ({_plural(fm.edits, 'change')}, {step}){remain}")


def _summary(args, tally: _Tally, n_files: int) -> int:
    """The closing line; the exit code."""
    changed, refused, partial = tally.changed, tally.refused, tally.partial
    verb = "would migrate" if (args.check or args.diff) else "migrated"
    _say(f"{verb.capitalize()} {_plural(changed, 'file')} ({_plural(tally.edits, 'change')}); "
         f"{_plural(n_files - changed - refused, 'file')} unchanged"
         + (f"; {_plural(partial, 'file')} with errors left for a person" if partial else "")
         + (f"; {_plural(refused, 'file')} refused" if refused else "") + ".")
    if refused:
        return 2 if not changed else 1
    return 1 if (args.check and changed) or partial else 0


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="*", metavar="PATH", help="files or folders to migrate (with --to)")
    p.add_argument("--to", metavar="VERSION", help="the OpenPLX version to migrate the files to (e.g. 0.19.0)")
    p.add_argument("--from", dest="from_version", metavar="VERSION",
                   help="the version the files were written for (default: the version plx lints them with: "
                        "openplx-version in the config, a bundle's pin, else the installed bundles)")
    p.add_argument("--diff", action="store_true", help="print the changes as a unified diff; write nothing")
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 when a file would change")


def run(args) -> int:
    if args.explain:
        if args.to or args.paths:
            _say("plx migrate: --explain cannot be combined with --to or paths")
            return 2
        from plxtools.migrate.explain import run_explain

        return run_explain(args.explain[0], args.explain[1], args.output_format)
    if not args.to or not args.paths:
        _say("plx migrate: give --to VERSION and the files or folders to migrate (or --explain FROM TO)")
        return 2
    return run_migrate(args)
