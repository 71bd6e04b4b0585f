"""The `plx lint` command body: options to runner to reporter."""

from __future__ import annotations

import os
import sys
from collections import Counter
from pathlib import Path

from plxtools.config import Config, ConfigError, config_for
from plxtools.diagnostics import Severity
from plxtools.discovery import UsageError, discover
from plxtools.fileio import unified_diff


def _codes(s: str | None) -> list[str]:
    return [c.strip().upper() for c in s.split(",") if c.strip()] if s else []


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _check_config_codes(cfg: Config, seen: set) -> None:
    """Every code or prefix a config file names must exist (raises ValueError)."""
    from plxtools.rules.registry import check_selectors

    if cfg.source is None or cfg.source in seen:
        return
    seen.add(cfg.source)
    for key, codes in (("select", cfg.select or []), ("ignore", cfg.ignore), ("extend-select", cfg.extend_select),
                       *((f"per-file-ignores.{k}", v) for k, v in cfg.per_file_ignores.items())):
        check_selectors(codes, f"{cfg.source}: {key}")


def run_lint(args) -> int:
    from plxtools.gcpolicy import command_collector

    with command_collector():
        return _run_lint(args)


class _Failed(Exception):
    """A user-facing failure (bad option, config or file system): `plx lint: <message>`, exit 2."""


_USER_ERRORS = (UsageError, ConfigError, ValueError)


def _run_lint(args) -> int:
    try:
        run = _LintRun(args)
        if getattr(args, "show_settings", False):
            from plxtools.bundles_cli import print_settings

            return _guarded(lambda: print_settings(run.workspace()) or _print_written_for(run))
        return run.run()
    except _Failed as exc:
        print(f"plx lint: {exc}", file=sys.stderr)
        return 2


def _print_written_for(run) -> int:
    """`--show-settings` on a tree nothing pins: each file whose content fits an older release better
    than the bundles in use, and that release (model/written_for.py; what `plx migrate` starts from)."""
    if run.bundle_set.pinned or run.stdin:
        return 0
    from plxtools.model.written_for import infer_file

    ws = run.workspace()
    for f in run.files:
        found = infer_file(ws, f)
        if found is not None:
            print(f"written for: {f}: OpenPLX {found.version} ({found.why(run.bundle_set.official_version)})")
    return 0


class _LintRun:
    """One `plx lint` run: options checked and files found (constructor), then each file linted
    (from the result cache, a worker, or here), fixed when asked, and everything reported."""

    def __init__(self, args):
        from plxtools.model.versions import resolve_bundle_set

        self.args = args
        paths = list(args.paths or ["."])
        self.stdin = "-" in paths
        self.files = _guarded(lambda: _files(args, paths, self.stdin))
        self.use_cache = not args.no_cache
        self.bundle_set = _guarded(lambda: resolve_bundle_set(self._targets(), args.bundle_path,
                                                              getattr(args, "openplx_version", None)))
        self._loaded: list = []
        self.results = None
        self.all_diags: list = []
        # the run may be replayed (plxtools.runmemo) when every file's result is in the result cache
        self.replayable = False
        self.fixed_files = 0
        self.fixes_applied = 0

    def _targets(self) -> list[Path]:
        """The files that choose the bundle set (with stdin: its --stdin-filename, when it exists)."""
        return [f for f in self.files if f.exists()] if self.stdin else list(self.files)

    def workspace(self):
        """The bundle program, loaded on first need: not at all when every file's result is cached."""
        if not self._loaded:
            from plxtools.model.workspace import workspace_for_set

            self._loaded.append(_guarded(lambda: workspace_for_set(self.bundle_set, self.use_cache)))
        return self._loaded[0]

    def run(self) -> int:
        args = self.args
        note = self.bundle_set.announcement()
        if note and not args.quiet and args.output_format == "text":
            print(f"plx lint: {note}", file=sys.stderr)
        self.results = self._result_cache()
        self.replayable = self.results is not None
        seen_configs: set = set()
        parallel: dict = {}
        if not self.stdin and not args.fix and not args.diff and len(self.files) >= PARALLEL_MIN_FILES \
                and _two_cores():
            parallel = _lint_in_parallel(self.files, args, self.results, self.workspace, self.bundle_set)
        for f in self.files:
            try:
                cfg = _config(f, self.stdin, args)
                _check_config_codes(cfg, seen_configs)
            except (ConfigError, ValueError) as exc:
                raise _Failed(exc) from exc
            if f in parallel:
                self.all_diags.extend(parallel[f])
                self.replayable = False
                continue
            self._lint_here(f, cfg)
        if args.diff:
            return 0
        return self._report()

    def _result_cache(self):
        """The result cache of this bundle set, or None when results are not kept for this run."""
        args = self.args
        if not self.use_cache or self.stdin or args.fix or args.diff:
            return None
        from plxtools.cache import records
        from plxtools.cache.stamp import code_stamp
        from plxtools.lint.resultcache import ResultCache

        bundle_set = self.bundle_set
        stamp = records.recorded_digest(records.set_key(code_stamp(), bundle_set.key(), bundle_set.official_version))
        if stamp is None:  # the set changed, or was never loaded with the cache on: load it to know
            stamp = self.workspace().read_digest
        return ResultCache(bundle_set, stamp)

    def _lint_here(self, f: Path, cfg: Config) -> None:
        """Lint one file in this process (or take its cached result), fixing it when asked."""
        from plxtools.cache import reads

        results = self.results
        data = None
        if not self.stdin:  # read once: the bytes keyed are the bytes linted
            try:
                data = reads.read_bytes(f, cfg.max_file_bytes)
            except OSError:
                pass  # lint_file reads again and reports why it cannot
        key = results.key(f, data, cfg) if results is not None and data is not None else None
        cached = results.get(key) if key is not None else None
        self.replayable = self.replayable and key is not None
        if cached is not None:
            self.all_diags.extend(cached)
            return
        from plxtools.gcpolicy import file_done
        from plxtools.lint.runner import lint_file

        ws = self.workspace()
        with reads.recording() as deps:  # what checking this file read besides its bytes
            result = _lint_stdin(f, cfg, ws) if self.stdin else lint_file(f, cfg, ws, data=data)
        diags = result.diagnostics
        if key is not None:
            results.put(key, deps, diags)
            self.replayable = self.replayable and results.stores(diags)
        if self.args.fix or self.args.diff:
            diags = self._fix(f, cfg, ws, result, diags)
        self.all_diags.extend(diags)
        if len(self.files) > 1:  # the last file's tree and symbols simply live until exit
            if result.tree is not None and result.tree.path:
                ws.forget_loose(result.tree.path)
            del result
            file_done()

    def _fix(self, f: Path, cfg: Config, ws, result, diags: list) -> list:
        """--fix or --diff on one linted file: the diagnostics that remain after it."""
        from plxtools.lint.runner import fixed_text, lint_file

        args = self.args
        fixable = result.tree is not None and not result.tree.has_errors_of_syntax()
        new_text, n = fixed_text(result.tree, diags, args.unsafe_fixes) if fixable else (None, 0)
        if self.stdin and args.fix:
            # like `plx fmt -`: the (fixed) text goes to stdout, the remaining diagnostics to stderr
            text = new_text if n else (result.tree.text if result.tree is not None else "")
            sys.stdout.write(text)
            if n:
                self._count_fixed(n)
                diags = _lint_text(str(f), text, cfg, ws).diagnostics
        elif n and args.diff:
            sys.stdout.write(unified_diff(str(f), result.tree.text, new_text))
        elif n:
            from plxtools.fileio import write_atomic

            try:
                write_atomic(f, new_text, result.tree.had_bom, expected=result.data)
            except OSError as exc:  # the user's file system, not a bug: say what happened
                raise _Failed(exc.strerror) from exc
            self._count_fixed(n)
            diags = lint_file(f, cfg, ws).diagnostics
        return diags

    def _count_fixed(self, n: int) -> None:
        self.fixes_applied += n
        self.fixed_files += 1

    def _report(self) -> int:
        """Print the diagnostics in the asked format; the exit code."""
        from plxtools.rules.reporters import render

        args, all_diags = self.args, self.all_diags
        out = sys.stderr if self.stdin and args.fix else sys.stdout
        if args.statistics:
            counts = Counter((d.code, d.severity.value) for d in all_diags)
            for (code, sev), n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])):
                print(f"{n:6}  {code:6} {sev}", file=out)
        elif args.output_format == "text" and args.quiet:
            from plxtools.rules.reporters import render_text

            render_text(all_diags, out, summary=False)
        else:
            render(all_diags, args.output_format, out, files_checked=len(self.files))
        if args.fix and self.fixes_applied and args.output_format == "text":
            print(f"Fixed {_plural(self.fixes_applied, 'problem')} in {_plural(self.fixed_files, 'file')}.", file=out)
        has_error = any(d.severity == Severity.ERROR for d in all_diags)
        if self.replayable:  # every read was recorded (plxtools.runmemo records the run if it may replay it)
            from plxtools import runmemo

            runmemo.allow()
        return 0 if (args.exit_zero or not has_error) else 1


def _guarded(compute):
    """`compute()`, its user errors (bad option, config, bundle set) turned into `_Failed`."""
    try:
        return compute()
    except _USER_ERRORS as exc:
        raise _Failed(exc) from exc


def _files(args, paths: list[str], stdin: bool) -> list[Path]:
    """The files a run lints, after checking the options that need no bundles (raises a user error)."""
    from plxtools.rules.registry import check_selectors

    check_selectors(_codes(args.select), "--select")
    check_selectors(_codes(args.ignore), "--ignore")
    if stdin and len(paths) > 1:
        raise UsageError("'-' (stdin) cannot be combined with other paths")
    if stdin and args.diff:
        raise UsageError("--diff cannot be used with '-' (stdin); use --fix to print the fixed text")
    name = getattr(args, "stdin_filename", None) or "-"
    return [Path(name)] if stdin else discover(paths)


def _config(f: Path, stdin: bool, args) -> Config:
    cfg = config_for(f if not stdin or f.name != "-" else Path(os.getcwd()) / "-")
    if args.select:
        cfg.select = _codes(args.select)
    if args.ignore:
        cfg.ignore = cfg.ignore + _codes(args.ignore)
    return cfg


# Many loose files are linted by a pool of worker processes (forked after the bundle program is
# loaded, so they share it), from this much work on: below it, starting the pool costs more than
# the second core gives back (see docs/benchmarks.md).
PARALLEL_MIN_FILES = 8
PARALLEL_MIN_BYTES = 256 * 1024
_WORKER_WORKSPACE = None


def _two_cores() -> bool:
    from plxtools import workpool

    return workpool.cores() > 1 and workpool.can_fork()


def _lint_in_parallel(files: list[Path], args, results, workspace, bundle_set) -> dict:
    """{file: diagnostics} for the files that are not cached, computed by worker processes, or {}
    when the run is too small, a file is in a bundle (files of a bundle see each other), or a
    config is broken (the ordinary loop then reports it where it did)."""
    from plxtools.lint.resultcache import _folder_in_bundle

    stop = {bundle_set.official_root.resolve()} if bundle_set.official_root is not None else set()
    todo = []
    size = 0
    folders: dict[Path, bool] = {}  # folder -> inside a bundle (each folder walked up once)
    try:
        for f in files:
            if f.name == "config.openplx":
                return {}
            folder = f.resolve().parent
            inside = folders.get(folder)
            if inside is None:
                inside = folders[folder] = _folder_in_bundle(folder, stop)
            if inside:
                return {}
            cfg = _config(f, False, args)
            from plxtools.cache import reads

            data = reads.read_bytes(f, cfg.max_file_bytes)  # read once: the bytes keyed are the bytes linted
            key = results.key(f, data, cfg) if results is not None else None
            if key is not None and results.get(key) is not None:
                continue
            todo.append((f, cfg, key, data))
            size += len(data)
    except (ConfigError, ValueError, OSError):
        return {}
    if len(todo) < PARALLEL_MIN_FILES or size < PARALLEL_MIN_BYTES:
        return {}
    from plxtools import workpool

    global _WORKER_WORKSPACE
    _WORKER_WORKSPACE = workspace()  # loaded once, here: the forked workers inherit it
    # the first file is linted here, before the fork: what it computes on the bundle program (bases,
    # member tables, types of bundle attributes) is then inherited, not computed again per worker
    done = [_lint_one((todo[0][0], todo[0][1], todo[0][3]))]
    rest = [(f, cfg, data) for f, cfg, _k, data in todo[1:]]
    # this process is one of the workers: it lints its share of the files while the forked ones lint
    # theirs, instead of waiting for them (one fork fewer: its start and the pages it would copy)
    cores = workpool.cores()
    mine = rest[:len(rest) // cores]
    own: list = []
    done += workpool.map_ordered(_lint_one, rest[len(mine):], workers=cores - 1,
                                 meanwhile=lambda: own.extend(_lint_one(item) for item in mine))
    done[1:1] = own
    out = {}
    for (f, _cfg, key, _data), (diags, deps) in zip(todo, done):
        out[f] = diags
        if key is not None:
            results.put(key, deps, diags)  # (a run with files linted in parallel is not replayed)
    return out


def _lint_one(item: tuple) -> tuple[list, list]:
    """A file's diagnostics and the reads its check made, as the ordinary loop computes them (in a
    worker, or before the fork)."""
    from plxtools.cache import reads
    from plxtools.gcpolicy import file_done
    from plxtools.lint.runner import lint_file

    f, cfg, data = item
    ws = _WORKER_WORKSPACE
    with reads.recording() as deps:
        result = lint_file(f, cfg, ws, data=data)
    diags = result.diagnostics
    if result.tree is not None and result.tree.path:
        ws.forget_loose(result.tree.path)
    del result
    file_done()
    return diags, deps


def _lint_stdin(name: Path, cfg: Config, workspace):
    from plxtools.cache import reads
    from plxtools.lint.runner import FileResult
    from plxtools.rules.analysis import analyse_tree
    from plxtools.syntax import parse_bytes
    from plxtools.syntax.source import unreadable

    try:
        data = reads.read_stream(sys.stdin.buffer, cfg.max_file_bytes)
    except OSError as exc:
        return FileResult(name, None, [unreadable(str(name), exc)])

    tree = parse_bytes(data, str(name))
    return FileResult(name, tree, analyse_tree(tree, cfg, workspace))


def _lint_text(name: str, text: str, cfg: Config, workspace):
    from plxtools.lint.runner import FileResult
    from plxtools.rules.analysis import analyse_tree
    from plxtools.syntax import parse_text

    tree = parse_text(text, name)
    return FileResult(Path(name), tree, analyse_tree(tree, cfg, workspace))
