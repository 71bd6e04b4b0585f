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


BRICK = ".brick"  # the extension of model files before OpenPLX 0.15 (plxtools/migrate/brick.py)


class _Failed(Exception):
    """A user-facing failure (bad version, config, unreadable file): `plx migrate: <message>`, exit 2."""


class _Tally:
    """What the run did, for the closing line and the exit code."""

    def __init__(self):
        self.changed = self.refused = self.edits = self.partial = 0
        self.failing: list = []  # (file, errors left, the version it was migrated from) of files left with errors


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
        files = discover(args.paths, suffixes=(".openplx", BRICK))
        if getattr(args, "show_settings", False):
            return _show_settings(files, args)
        setups = _Setups(files, args) if files else None
    except (UsageError, ConfigError, ValueError, _Failed) as exc:
        _say(f"plx migrate: {exc}")
        return 2
    tally = _Tally()
    from plxtools.progress import Bar

    try:
        with Bar(len(files), "plx migrate") as bar:
            for f in files:
                bar.advance(f.name, by=0)
                _migrate_file(f, args, setups.for_file(f), tally)
                bar.advance()
    except _Failed as exc:
        _say(f"plx migrate: {exc}")
        return 2
    return _summary(args, tally, len(files), setups)


def _ends(files, args, check: bool = True):
    """The source and target ends (raises EndpointError with what to pass)."""

    paths = getattr(args, "bundle_path", None) or []
    src = endpoints.source(files, args.from_version, bundle_paths=paths)
    dst = endpoints.target(files, args.to, bundle_paths=paths)
    if check:
        endpoints.check_direction(files, src, dst)
    return src, dst


def _setup_of(src, dst) -> _Setup:
    """The plan between two ends (the stored index for two releases, else indexes built from the
    bundle folders) and a workspace per end."""
    from plxtools.migrate.endpoints import plan_between
    from plxtools.model.workspace import workspace_for_set

    return _Setup(src, dst, plan_between(src, dst), workspace_for_set(src.bundle_set),
                  workspace_for_set(dst.bundle_set))


class _Setups:
    """The run's ends; per file, the end it starts from. With no `--from` and nothing that pins a
    version (flag, config, dependency), a file whose content fits an older release better than the
    bundles in use is migrated from that release (model/written_for.py, lint's own inference)."""

    def __init__(self, files, args):
        from plxtools.migrate.endpoints import check_direction
        from plxtools.model.workspace import workspace_for_set

        self.args = args
        self.src, self.dst = _ends(files, args, check=False)
        self.src_ws = workspace_for_set(self.src.bundle_set)
        self.by_version: dict[str, _Setup] = {}
        self.of_file: dict = {}
        self.default: _Setup | None = None
        bricks = [f for f in files if f.suffix == BRICK]
        if bricks:  # read as the oldest release plx has, after OpenPLX's renames before it (migrate/brick.py)
            from plxtools.model.apiindex import version_key, versions

            first = versions()[0]
            if version_key(first) <= version_key(self.dst.version):
                brick_setup = self._release(bricks[0], first, "the oldest release plx has, for a .brick file "
                                            "(written before OpenPLX 0.15)")
                self.of_file.update({f: brick_setup for f in bricks})
        if args.from_version is None and not self.src.bundle_set.pinned:
            for f in files:  # all first: a release that cannot be loaded stops the run before any write
                if f.suffix != BRICK:
                    self.of_file[f] = self._inferred(f)
        rest = [f for f in files if self.of_file.get(f) is None]
        if rest:  # (a file taken as newer than --to is refused, with what to pass, before any write)
            check_direction(rest, self.src, self.dst)
            self.default = _setup_of(self.src, self.dst)

    def for_file(self, f) -> _Setup:
        return self.of_file.get(f) or self.default

    def _inferred(self, f) -> _Setup | None:
        found = infer_for(f, self.src_ws)
        version = found.newest_fit(self.dst.version) if found is not None else None
        if version is None:
            return None
        why = found.why(self.src.version).replace(f"OpenPLX {found.version}", f"OpenPLX {version}", 1)
        setup = self._release(f, version, f"the file's content: {why.split(': ', 1)[-1]}")
        _say(f"{f}: written for OpenPLX {version} ({why})")
        return setup

    def _release(self, f, version: str, why: str) -> _Setup:
        """The setup from a release the run chose for a file (not the user): loaded once per release."""
        from plxtools.migrate import endpoints

        if version not in self.by_version:
            try:
                src = endpoints.inferred([f], version, why, getattr(self.args, "bundle_path", None) or [])
            except ValueError as exc:
                raise _Failed(f"{f}: written for OpenPLX {version} ({why.split(':')[0]}), whose bundles plx cannot "
                              f"load: {exc}; pass --from VERSION to choose the version") from None
            self.by_version[version] = _setup_of(src, self.dst)
        return self.by_version[version]


def infer_for(f, ws):
    """The release a file's content says it was written for (None: the bundles in use fit it)."""
    from plxtools.model.written_for import infer_file

    return infer_file(ws, f)


def _show_settings(files, args) -> int:
    """`plx migrate --show-settings`: the bundles of both ends and why, and for each file whose
    content says it was written for another release, that release (nothing is migrated)."""
    from plxtools.bundles_cli import print_set

    from plxtools.migrate.endpoints import check_direction

    src, dst = _ends(files, args, check=False)
    for title, end in (("from", src), ("to", dst)):
        print(f"migrate {title}: {end.describe()}")
        print_set(end.bundle_set, indent="  ")
    rest = list(files)
    if args.from_version is None and not src.bundle_set.pinned:
        from plxtools.model.workspace import workspace_for_set

        ws = workspace_for_set(src.bundle_set)
        for f in files:
            found = infer_for(f, ws) if f.suffix != BRICK else None
            version = found.newest_fit(dst.version) if found is not None else None
            if version is not None:
                why = found.why(src.version).replace(f"OpenPLX {found.version}", f"OpenPLX {version}", 1)
                print(f"written for: {f}: OpenPLX {version} ({why})")
                rest.remove(f)
    if rest:
        check_direction(rest, src, dst)  # shown first: the settings are what explains a refusal
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

    if f.suffix == BRICK:
        _migrate_brick(f, args, setup, tally)
        return
    cfg, data, text = _inputs(f)
    to_v = setup.dst.version
    fm = migrate_text(f, text, setup.plan, cfg, setup.from_ws, setup.to_ws)
    if not fm.refused and fm.errors_after:
        tally.failing.append((f, fm.errors_after, setup.src.label))
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


def _migrate_brick(f, args, setup: _Setup, tally: _Tally) -> None:
    """A .brick file: OpenPLX's renames before 0.15, then the migration from the oldest release plx
    has; written as the .openplx file of the same name (the .brick file is renamed, then rewritten)."""
    from plxtools.fileio import unified_diff, write_atomic
    from plxtools.migrate.brick import pre_015_text
    from plxtools.migrate.rewrite import migrate_text

    new_path = f.with_suffix(".openplx")
    if new_path.exists():
        tally.refused += 1
        _say(f"{f}:1:1: not migrated: {new_path} already exists (a .brick file becomes the .openplx file of the "
             f"same name); move one of them away")
        return
    cfg, data, text = _inputs(f)
    pre, n_pre, notes = pre_015_text(str(new_path), text)
    fm = migrate_text(new_path, pre, setup.plan, cfg, setup.from_ws, setup.to_ws)
    if fm.refused:
        tally.refused += 1
        _say(f"{f}:1:1: not migrated (a .brick file, read as {setup.src.label}): {fm.refused}")
        return
    for note in notes + fm.notes:
        _say(f"{f}: {note}")
    new_text = fm.new_text if fm.new_text is not None else pre
    edits = n_pre + fm.edits + 1  # the extension is one change
    tally.changed += 1
    tally.edits += edits
    if fm.errors_after:
        tally.failing.append((new_path, fm.errors_after, setup.src.label))
    step = f"before 0.15 -> {setup.dst.label}, as {new_path.name}"
    remain = _remaining(fm, setup.src.label)
    if args.diff:
        diff = unified_diff(str(f), text, new_text) or f"--- a/{f}\n+++ b/{f}\n"  # (a rename alone: the headers)
        sys.stdout.write(diff.replace(f"+++ b/{f}", f"+++ b/{new_path}", 1))
    elif args.check:
        _say(f"would migrate {f} ({_plural(edits, 'change')}, {step}){remain}")
    else:
        try:
            f.rename(new_path)  # first the name: should the write fail, the file is whole under its new name
            write_atomic(new_path, new_text, data.startswith(b"\xef\xbb\xbf"), expected=data)
        except OSError as exc:
            raise _Failed(f"{f}: {exc.strerror or exc}") from exc
        _say(f"migrated {f} ({_plural(edits, 'change')}, {step}){remain}")
    _left_for_a_person(new_path, fm, setup.dst.version)


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


def _summary(args, tally: _Tally, n_files: int, setups: "_Setups | None" = None) -> int:
    """The closing line; the exit code (1 when nothing changed while files still fail: said why)."""
    changed, refused, partial = tally.changed, tally.refused, tally.partial
    verb = "would migrate" if (args.check or args.diff) else "migrated"
    _say(f"{verb.capitalize()} {_plural(changed, 'file')} ({_plural(tally.edits, 'change')}); "
         f"{_plural(n_files - changed - refused, 'file')} unchanged"
         + (f"; {_plural(partial, 'file')} with errors left for a person" if partial else "")
         + (f"; {_plural(refused, 'file')} refused" if refused else "") + ".")
    if refused:
        return 2 if not changed else 1
    if not changed and tally.failing and setups is not None:
        _nothing_done(tally, setups)
        return 1
    return 1 if (args.check and changed) or partial else 0


def _nothing_done(tally: _Tally, setups: _Setups) -> None:
    """Nothing was rewritten, yet files have errors under the target version: say why and what to pass."""
    dst = setups.dst.label
    f, n, frm = tally.failing[0]
    more = f" (and {len(tally.failing) - 1} more files)" if len(tally.failing) > 1 else ""
    if frm == dst:
        why = (f"the files were taken as written for {frm}, the version they are migrated to, so there was nothing to "
               f"rewrite; if they were written for an older OpenPLX, pass it: plx migrate --from VERSION --to {dst} "
               f"{f} (`plx migrate --explain VERSION {dst}` lists what changed)")
    else:
        why = (f"no rename or move between {frm} and {dst} applies to the files; what is left needs a person "
               f"(listed above), or they were written for another version: pass --from VERSION")
    _say(f"plx migrate: nothing was migrated, but {f}{more} still has {_plural(n, 'error')} under {dst}: {why}")


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="*", metavar="PATH",
                   help="files or folders to migrate (with --to): .openplx files, and .brick files of before 0.15")
    p.add_argument("--to", metavar="VERSION", help="the OpenPLX version to migrate the files to: a release (e.g. 0.19.0) or the version of "
                   "the AGX installation's bundles (e.g. 0.20.1)")
    p.add_argument("--from", dest="from_version", metavar="VERSION",
                   help="the version the files were written for (default: the bundles plx lints them with: "
                        "openplx-version in the config, a dependency's version, else the release each file's "
                        "content fits best (when it fits one better than the bundles in use), an AGX "
                        "installation, else the installed bundles)")
    p.add_argument("--diff", action="store_true", help="print the changes as a unified diff; write nothing")
    p.add_argument("--check", action="store_true", help="write nothing; exit 1 when a file would change")
    p.add_argument("--show-settings", action="store_true",
                   help="print the bundles of both versions (AGX installation, OpenPLX version, why), and the "
                        "version inferred for each file that fits an older release better, and exit")
    p.add_argument("--bundle-path", action="append", default=[], metavar="DIR",
                   help="a bundle folder, or a folder of bundle folders (repeatable); adds to bundle-path in the "
                        "config, for both versions")


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
