"""The `plx migrate --to VERSION PATH...` command: per file, the version it was written for, the
rewrite, and the write (or the diff, or the check)."""

from __future__ import annotations

import sys
from dataclasses import dataclass

from plxtools.config import ConfigError, config_for
from plxtools.discovery import UsageError, discover
from plxtools.bundles_cli import print_set
from plxtools.fileio import unified_diff, write_atomic
from plxtools.migrate import endpoints
from plxtools.migrate.endpoints import check_direction
from plxtools.migrate.endpoints import plan_between
from plxtools.migrate.rewrite import migrate_text
from plxtools.model.workspace import workspace_for_set


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


@dataclass
class _Setup:
    """Both ends of the run (one bundle set each, chosen as `plx lint` chooses it for these files),
    their workspaces and the plan between them."""

    src: object  # endpoints.End
    dst: object
    plan: object  # rewrite.Plan
    from_ws: object
    to_ws: object

    @property
    def step(self) -> str:
        return f"{self.src.label} -> {self.dst.label}"


def run_migrate(args) -> int:
    try:
        files = discover(args.paths)
        if getattr(args, "show_settings", False):
            return _show_settings(files, args)
        setup = _setup(files, args) if files else None
    except (UsageError, ConfigError, ValueError) as exc:
        _say(f"plx migrate: {exc}")
        return 2
    tally = _Tally()
    try:
        for f in files:
            _migrate_file(f, args, setup, tally)
    except _Failed as exc:
        _say(f"plx migrate: {exc}")
        return 2
    return _summary(args, tally, len(files))


def _ends(files, args, check: bool = True):
    """The source and target ends (raises EndpointError with what to pass)."""

    src = endpoints.source(files, args.from_version)
    dst = endpoints.target(files, args.to)
    if check:
        endpoints.check_direction(files, src, dst)
    return src, dst


def _setup(files, args) -> _Setup:
    """The ends, the plan between them (the stored index for two releases, else indexes built from
    the bundle folders) and a workspace per end."""

    src, dst = _ends(files, args)
    return _Setup(src, dst, plan_between(src, dst), workspace_for_set(src.bundle_set),
                  workspace_for_set(dst.bundle_set))


def _show_settings(files, args) -> int:
    """`plx migrate --show-settings`: the bundles of both ends and why (nothing is migrated)."""

    src, dst = _ends(files, args, check=False)
    for title, end in (("from", src), ("to", dst)):
        print(f"migrate {title}: {end.describe()}")
        print_set(end.bundle_set, indent="  ")
    check_direction(files, src, dst)  # shown first: the settings are what explains a refusal
    return 0


def _inputs(f):
    """A file's config, bytes and text (raises `_Failed`)."""
    try:
        cfg = config_for(f)
        data = f.read_bytes()
        text = data.decode("utf-8-sig")
    except (UsageError, ConfigError, ValueError) as exc:
        raise _Failed(exc) from exc
    except (OSError, UnicodeDecodeError) as exc:
        raise _Failed(f"{f}: cannot read it: {getattr(exc, 'strerror', None) or exc}") from exc
    return cfg, data, text


def _migrate_file(f, args, setup: _Setup, tally: _Tally) -> None:
    """Migrate one file (or show or check what would change) and say what happened."""

    cfg, data, text = _inputs(f)
    to_v = setup.dst.version
    fm = migrate_text(f, text, setup.plan, cfg, setup.from_ws, setup.to_ws)
    if fm.refused:
        tally.refused += 1
        _say(f"{f}: not migrated from {setup.src.label} to {setup.dst.label}: {fm.refused}")
        _left_for_a_person(f, fm, to_v)
        return
    for note in fm.notes:
        _say(f"{f}: {note}")
    if fm.errors_after > fm.errors_before:
        tally.partial += 1  # the safe rewrites (if any) are applied; the rest is listed below
    if fm.changed:
        tally.changed += 1
        tally.edits += fm.edits
        _write(f, args, fm, data, setup.step, _remaining(fm, setup.src.label))
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
    p.add_argument("--to", metavar="VERSION", help="the OpenPLX version to migrate the files to: a release (e.g. 0.19.0) or the version of "
                   "the AGX installation's bundles (e.g. 0.20.1)")
    p.add_argument("--from", dest="from_version", metavar="VERSION",
                   help="the version the files were written for (default: the bundles plx lints them with: "
                        "openplx-version in the config, a dependency's version, an AGX installation, else the "
                        "installed bundles)")
    p.add_argument("--diff", action="store_true", help="print the changes as a unified diff; write nothing")
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 when a file would change")
    p.add_argument("--show-settings", action="store_true",
                   help="print the bundles of both versions (AGX installation, OpenPLX version, why) and exit")


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
