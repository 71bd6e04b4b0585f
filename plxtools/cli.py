"""The `plx` command. Each subcommand imports only what it needs, so `plx fmt` starts fast.

Exit codes: 0 clean, 1 findings (error diagnostics, or files that would change), 2 usage or
internal error.
"""

from __future__ import annotations

import sys

from plxtools import DOCS_BASE_URL, __version__

OUTPUT_FORMATS = ("text", "json", "github", "sarif")


def _add_lint(sub) -> None:
    p = sub.add_parser(
        "lint",
        help="parse and type-check .openplx files against the OpenPLX bundles",
        description="Parse and type-check OpenPLX files (folders are searched for *.openplx) and "
        "report coded diagnostics. Exit 0 when there is no error-severity diagnostic, 1 when there "
        "is, 2 on usage or internal errors.",
    )
    p.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders (default: .); '-' lints stdin")
    p.add_argument("--stdin-filename", metavar="PATH",
                   help="the path of the file given on stdin (for config, bundles and messages)")
    p.add_argument("--output-format", choices=OUTPUT_FORMATS, default="text",
                   help="text (default), json, github (workflow annotations) or sarif (SARIF 2.1.0)")
    p.add_argument("--fix", action="store_true",
                   help="apply safe fixes in place (with '-': print the fixed text, diagnostics to stderr)")
    p.add_argument("--unsafe-fixes", action="store_true", help="with --fix or --diff, also apply unsafe fixes")
    p.add_argument("--diff", action="store_true",
                   help="print the fixes (safe ones; all with --unsafe-fixes) as a unified diff; write nothing (exit 0)")
    p.add_argument("--statistics", action="store_true", help="print a count per rule instead of each diagnostic")
    p.add_argument("--exit-zero", action="store_true", help="exit 0 even when errors are found")
    p.add_argument("--select", metavar="CODES", help="comma-separated codes or prefixes to enable (overrides config)")
    p.add_argument("--ignore", metavar="CODES", help="comma-separated codes or prefixes to disable (adds to config)")
    p.add_argument("--bundle-path", action="append", default=[], metavar="DIR",
                   help="a bundle folder, or a folder of bundle folders (repeatable); adds to bundle-path in the config")
    p.add_argument("--no-cache", action="store_true",
                   help="do not read or write plx's caches (the bundle program, and each unchanged file's results)")
    p.add_argument("-q", "--quiet", action="store_true", help="print diagnostics only, no summary line")
    _add_bundle_options(p)
    p.add_argument("--show-settings", action="store_true",
                   help="print the bundles in use (name, version, folder, why) and, when nothing pins the "
                        "OpenPLX version, the version inferred for each file that fits an older release, and exit")
    p.set_defaults(func=_run_lint)


def _add_rule(sub) -> None:
    p = sub.add_parser("rule", help="show the documentation of a rule, or list all rules",
                       description="Print a rule's documentation page (by code or name), or list every rule.")
    p.add_argument("code", nargs="?", metavar="CODE", help="rule code (e.g. S011) or name (e.g. invalid-syntax)")
    p.add_argument("--all", action="store_true",
                   help="list every rule: code, name, severity and summary (the default without CODE)")
    p.add_argument("--output-format", choices=("text", "json"), default="text", help="text or json")
    p.set_defaults(func=_run_rule)


def _add_fmt(sub) -> None:
    p = sub.add_parser("fmt", help="format .openplx files in the one canonical style",
                       description="Format OpenPLX files in place. Files with syntax errors are refused. "
                       "Exit 1 with --check when a file would change, 2 on errors.")
    p.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders (default: .); '-' formats stdin to stdout")
    p.add_argument("--check", action="store_true", help="do not write; exit 1 and list files that would change")
    p.add_argument("--diff", action="store_true", help="do not write; print a unified diff of the changes")
    p.add_argument("--stdin-filename", metavar="PATH",
                   help="the path of the file given on stdin (for config and messages)")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    p.add_argument("--no-cache", action="store_true",
                   help="do not read or write the cache of files already formatted (re-check every file)")
    p.set_defaults(func=_run_fmt)


def _add_check(sub) -> None:
    p = sub.add_parser("check", help="assemble a scene, check it, and optionally simulate it in MuJoCo",
                       description="Instantiate the root model of each file, assemble it as OpenPLX's SNAP "
                       "does, check the assembly, and with --simulate compile it to MuJoCo and run it. Exit 0 "
                       "when there is no error-severity diagnostic, 1 when there is, 2 on usage or internal "
                       "errors or when a --render/--export-mjcf file cannot be written.")
    p.add_argument("paths", nargs="+", metavar="PATH", help="files or folders")
    p.add_argument("--model", metavar="NAME", help="the model to load (default: the last model in the file)")
    p.add_argument("--simulate", action="store_true", help="compile to MuJoCo and run the scene")
    p.add_argument("--duration", type=float, default=3.0, metavar="SECONDS",
                   help="simulated time with --simulate (default 3.0)")
    p.add_argument("--output-format", choices=OUTPUT_FORMATS, default="text", help="text, json, github or sarif")
    p.add_argument("--render", metavar="FILE.png", help="save a picture of the assembled scene (offscreen)")
    p.add_argument("--export-mjcf", metavar="FILE.xml", help="write the compiled MuJoCo model")
    p.add_argument("--video", metavar="FILE.gif|FILE.mp4",
                   help=f"with --simulate, record the run offscreen, the camera following the bodies ({DOCS_BASE_URL}view/)")
    p.add_argument("--fps", type=float, default=25.0, metavar="N", help="frames per simulated second of --video (default 25)")
    p.add_argument("--video-camera", choices=("follow", "fixed"), default="follow",
                   help="--video's camera: follow the bodies (default) or stay where it framed them at the start")
    p.add_argument("--trace", metavar="FILE.csv",
                   help="write the simulated motion (every body's pose and velocity, every mate's coordinate, "
                   "every 0.01 s) as CSV; implies --simulate")
    p.add_argument("--timeout", type=float, default=None, metavar="SECONDS",
                   help="wall-clock limit of each file's whole check (default 300): the checks, the initial-overlap "
                   "check and the simulation; a run cut short is A109")
    p.add_argument("--integrator", choices=("auto", "implicitfast", "implicit", "rk4", "euler"), default=None,
                   help="MuJoCo integrator (default auto: rk4 for conservative, contact-free scenes, implicitfast "
                   "otherwise; config key check.integrator)")
    p.add_argument("--timestep", type=float, default=None, metavar="SECONDS",
                   help="simulation time step (default 0.002; a stiff spring may shorten it, A133; config key "
                   "check.timestep)")
    p.add_argument("--bundle-path", action="append", default=[], metavar="DIR",
                   help="a bundle folder, or a folder of bundle folders (repeatable); adds to bundle-path in the config")
    p.add_argument("--show-env", action="store_true",
                   help="let messages show what $\"{VAR}\" paths expand to (off: they show the expression, so "
                   "no environment value, such as a CI secret, reaches a log)")
    p.add_argument("--exit-zero", action="store_true", help="exit 0 even when errors are found")
    p.add_argument("-j", "--jobs", type=_jobs, default=0, metavar="N",
                   help="processes that check files at once: 'auto' (default: every core when the files' "
                   "estimated work pays for the workers' start), or a number (1: one file after the other)")
    _add_bundle_options(p)
    p.add_argument("--show-settings", action="store_true",
                   help="print the bundles in use (OpenPLX version, AGX installation, folder, why) and exit")
    p.set_defaults(func=_run_check)


def _jobs(text: str) -> int:
    try:
        if text.strip().lower() == "auto":
            return 0
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        import argparse

        raise argparse.ArgumentTypeError(f"expected 'auto' or a whole number >= 1, got {text!r}")
    return n


def _add_view(sub) -> None:
    p = sub.add_parser("view", help="open the scene in MuJoCo's viewer, reload it on save, drive it with keys",
                       description="Check and compile FILE as 'plx check' does and open it in MuJoCo's interactive "
                       "viewer. Saving the file (or anything it read) reloads it in the open window; 1 or F5 "
                       "reloads, E plays or pauses, G shows collision geometry instead of the visuals, R resets. "
                       "--web serves the same live scene to a browser page instead, linked to the editor. "
                       f"A file that does not load is reported and watched until it does. Keys and set-up: "
                       f"{DOCS_BASE_URL}view/")
    p.add_argument("path", metavar="FILE", help="the .openplx file")
    p.add_argument("--model", metavar="NAME", help="the model to show alone (default: the last model in the file)")
    p.add_argument("-p", "--paused", action="store_true", help="start paused (E plays)")
    p.add_argument("--controller", metavar="SCRIPT.py",
                   help="a Python script whose buildScene() binds keys with plxtools.view.KeyboardCallback")
    p.add_argument("--keys", metavar="KEYS.toml", help="a key-binding table: key -> input path -> value while held")
    p.add_argument("--web", action="store_true",
                   help="serve a live 3D preview page on 127.0.0.1 instead of opening a window (no display needed)")
    p.add_argument("--port", type=int, default=0, metavar="N", help="with --web, the port (default: a free one)")
    p.add_argument("--no-open", action="store_true", help="with --web, print the URL but open no browser")
    p.add_argument("--editor-command", metavar="CMD",
                   help="with --web, run CMD when a body, mate or connector is clicked; {file}, {line} and {column} "
                   "are replaced (for example 'code -g {file}:{line}:{column}')")
    p.add_argument("--bundle-path", action="append", default=[], metavar="DIR",
                   help="a bundle folder, or a folder of bundle folders (repeatable); adds to bundle-path in the config")
    _add_bundle_options(p)
    p.set_defaults(func=_run_view)


def _add_test(sub) -> None:
    p = sub.add_parser("test", help="run scenario files: drive a model's inputs, check its outputs",
                       description="Run scenario files (*.scenario.toml: inputs over time and expectations on "
                       "outputs and body poses) against their models in MuJoCo, and report like pytest. Exit 0 "
                       "when every scenario passes, 1 when one fails (an expectation, or a model that cannot be "
                       "simulated), 2 when a scenario file is invalid, on usage or internal errors.")
    p.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="scenario files or folders searched for *.scenario.toml (default: .)")
    p.add_argument("--output-format", choices=("text", "json", "github", "sarif", "junit"), default="text",
                   help="text (default), json, github (workflow annotations), sarif (SARIF 2.1.0) or junit (XML)")
    p.add_argument("--bundle-path", action="append", default=[], metavar="DIR",
                   help="a bundle folder, or a folder of bundle folders (repeatable); adds to bundle-path in the config")
    _add_bundle_options(p)
    p.set_defaults(func=_run_test)


def _add_bundle_options(p) -> None:
    p.add_argument("--openplx-version", metavar="VERSION",
                   help="lint against this openplx-bundles release (fetched into plx's cache on first use); "
                   "overrides openplx-version in the config")


def _add_bundles(sub) -> None:
    from plxtools.bundles_cli import add_parser

    add_parser(sub)


def _add_lsp(sub) -> None:
    p = sub.add_parser("lsp", help="run the language server over stdio",
                       description="Run the OpenPLX language server, speaking LSP over stdin/stdout.")
    p.add_argument("--stdio", action="store_true", help="accepted for editor compatibility (stdio is the default)")
    p.add_argument("--log-file", metavar="FILE", help="write the server's log to FILE")
    p.set_defaults(func=_run_lsp)


def _add_cache(sub) -> None:
    p = sub.add_parser("cache", help=f"show or empty plx's cache ({DOCS_BASE_URL}caching/)",
                       description="plx's cache: 'dir' prints its folder, 'info' what it holds, 'clean' empties it.")
    p.add_argument("action", choices=("dir", "info", "clean"))
    p.set_defaults(func=_run_cache)


def _run_cache(args) -> int:
    from plxtools.cache.command import run

    return run(args)


def _add_migrate(sub) -> None:
    p = sub.add_parser("migrate", help="move model files to another official OpenPLX version, or explain the changes",
                       description="Rewrite OpenPLX files for another official OpenPLX version: models that moved "
                       "or were renamed and renamed attributes, as plx's built-in API index of every version says. "
                       "A file is rewritten only when the result parses and lints with no more errors under the "
                       "new version than before. With --explain, print the API changes between two versions. "
                       "Exit 0 when done, 1 with --check when a file would change, when nothing was rewritten "
                       "while files still fail, or when some files were refused, 2 on usage errors or when "
                       "nothing could be migrated.")
    if isinstance(p, _Stub):
        return
    from plxtools.migrate.command import add_arguments

    add_arguments(p)
    p.add_argument("--explain", nargs=2, metavar=("FROM", "TO"),
                   help="print the changes from version FROM to version TO (e.g. 0.17.26 0.19.0)")
    p.add_argument("--output-format", choices=("text", "json"), default="text",
                   help="with --explain: text (default) or json")
    p.set_defaults(func=_run_migrate)


class _Stub:
    """A subcommand's parser that this run does not use: not built at all (nor the modules that
    define its options imported). Such a run names a known command first, so the others' names are
    needed neither to parse it nor for its messages (`plx lint --help` shows lint's options only)."""

    def __getattr__(self, name):
        return self._ignore

    def _ignore(self, *args, **kwargs):
        return self


class _Skip:
    def add_parser(self, name, **kwargs):
        return _Stub()


_COLUMNS: dict[tuple, int] = {}


def _terminal_columns() -> int:
    """shutil.get_terminal_size().columns without importing shutil (and bz2, lzma) at every start;
    asked once per run and $COLUMNS/$LINES (argparse makes a formatter for every option it adds)."""
    import os

    key = (os.environ.get("COLUMNS"), os.environ.get("LINES"))
    if key in _COLUMNS:
        return _COLUMNS[key]
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    try:
        lines = int(os.environ["LINES"])
    except (KeyError, ValueError):
        lines = 0
    if columns <= 0 or lines <= 0:
        try:
            size = os.get_terminal_size(sys.__stdout__.fileno())
        except (AttributeError, ValueError, OSError):
            size = os.terminal_size((80, 24))
        if columns <= 0:
            columns = size.columns or 80
    _COLUMNS[key] = columns
    return columns


_CLASSES: list = []


def _parser_class():
    """plx's ArgumentParser (help as wide as the terminal), made on first use: a replayed run
    (plxtools.runmemo) does not import argparse at all."""
    if not _CLASSES:
        import argparse

        class _Formatter(argparse.HelpFormatter):
            def __init__(self, prog, indent_increment=2, max_help_position=24, width=None):
                if width is None:
                    width = _terminal_columns() - 2
                super().__init__(prog, indent_increment, max_help_position, width)

        class _Parser(argparse.ArgumentParser):
            def __init__(self, *args, **kwargs):
                kwargs.setdefault("formatter_class", _Formatter)
                super().__init__(*args, **kwargs)

        _CLASSES.append(_Parser)
    return _CLASSES[0]


_COMMANDS = ("lint", "fmt", "check", "test", "lsp", "rule", "bundles", "migrate", "cache", "view")


def build_parser(only: str | None = None):
    """The whole command line (an argparse.ArgumentParser), or with `only`, that subcommand's
    options and the others' names."""
    _Parser = _parser_class()
    parser = _Parser(
        prog="plx",
        description="plxtools: lint, format, check and simulate OpenPLX models, and an editor language server.",
        epilog="Run 'plx COMMAND --help' for a command's options and 'plx rule CODE' to explain a diagnostic. "
        f"Docs: {DOCS_BASE_URL}",
    )
    parser.add_argument("--version", action="version", version=f"plx {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    stub = _Skip()
    for name, add in zip(_COMMANDS, (_add_lint, _add_fmt, _add_check, _add_test, _add_lsp, _add_rule,
                                     _add_bundles, _add_migrate, _add_cache, _add_view)):
        add(sub if only is None or only == name else stub)
    return parser


def _codes(s: str | None) -> list[str]:
    return [c.strip().upper() for c in s.split(",") if c.strip()] if s else []


def _run_lint(args) -> int:
    from plxtools.lint.cli import run_lint

    return run_lint(args)


def _run_rule(args) -> int:
    import json

    from plxtools.rules.registry import all_rules, get

    if args.all or not args.code:
        rules = all_rules()
        if args.output_format == "json":
            print(json.dumps([{"code": r.code, "name": r.name, "severity": r.severity.value,
                               "stage": r.stage, "fix": r.fix, "summary": r.summary} for r in rules], indent=2))
        else:
            for r in rules:
                print(f"{r.code:6} {r.name:34} {r.severity.value:8} {r.summary}")
        return 0
    r = get(args.code)
    if r is None:
        print(f"plx rule: unknown rule '{args.code}' (see 'plx rule --all')", file=sys.stderr)
        return 2
    if args.output_format == "json":
        print(json.dumps({"code": r.code, "name": r.name, "severity": r.severity.value, "page": r.page()}))
    else:
        print(r.page())
    return 0


def _run_migrate(args) -> int:
    from plxtools.migrate.command import run

    return run(args)


def _run_fmt(args) -> int:
    from plxtools.fmt.cli import run_fmt

    return run_fmt(args)


# The `sim` extra (pyproject.toml): what `plx check`, `plx test` and `plx view` compute with. A plain
# `pip install plxtools` has lint, fmt and the language server only.
SIM_EXTRA = "pip install 'plxtools[sim]'"


def _missing_sim(command: str, modules: tuple[str, ...]) -> int | None:
    """Exit status 2 with the extra to install when one of `modules` is not installed (looked up
    without importing it), else None."""
    from importlib.util import find_spec

    missing = []
    for name in modules:
        try:
            if find_spec(name) is None:
                missing.append(name)
        except (ImportError, ValueError):  # a broken or half-removed install
            missing.append(name)
    if not missing:
        return None
    print(f"plx {command}: needs {' and '.join(missing)}, which {'is' if len(missing) == 1 else 'are'} not "
          f"installed: this command comes with the simulation extra, {SIM_EXTRA}", file=sys.stderr)
    return 2


def _run_check(args) -> int:
    if getattr(args, "show_settings", False):
        from plxtools.bundles_cli import show_settings

        return show_settings("check", args)
    backend = args.simulate or args.render or args.export_mjcf or args.video or args.trace
    missing = _missing_sim("check", ("numpy", "mujoco") if backend else ("numpy",))
    if missing is not None:
        return missing
    from plxtools.check.cli import run_check

    return run_check(args)


def _run_view(args) -> int:
    missing = _missing_sim("view", ("numpy", "mujoco"))
    if missing is not None:
        return missing
    from plxtools.view.command import run_view

    return run_view(args)


def _run_test(args) -> int:
    missing = _missing_sim("test", ("numpy", "mujoco"))
    if missing is not None:
        return missing
    from plxtools.check.testrun import run_test

    return run_test(args)


def _run_lsp(args) -> int:
    from importlib.util import find_spec

    for name in ("pygls", "lsprotocol"):  # checked without importing them: quickstart answers first
        if find_spec(name) is None:
            print(f"plx lsp: the language server needs {name}, which is not installed", file=sys.stderr)
            return 2
    from plxtools.lsp.quickstart import start

    try:
        return start(args)
    except ImportError as exc:
        if (exc.name or "").startswith("plxtools"):
            raise  # our own code is never optional
        print(f"plx lsp: the language server needs {exc.name}, which is not installed: {exc}", file=sys.stderr)
        return 2


def main(argv: list[str] | None = None) -> int:
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 20000))
    words = sys.argv[1:] if argv is None else argv
    parser = build_parser(words[0] if words and words[0] in _COMMANDS else None)
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        return args.func(args)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0
    except ImportError as exc:
        if (exc.name or "").split(".")[0] not in ("numpy", "mujoco"):
            return _internal_error(args, exc)
        print(f"plx {args.command}: needs {exc.name}, which is not installed: {SIM_EXTRA}", file=sys.stderr)
        return 2
    except Exception as exc:
        return _internal_error(args, exc)


def _internal_error(args, exc: BaseException) -> int:
    """An internal error: said plainly, never a bare traceback (PLX_DEBUG=1 prints it)."""
    import traceback

    print(f"plx {args.command}: internal error: {type(exc).__name__}: {exc}", file=sys.stderr)
    print("This is a bug in plxtools; please report it with the input that caused it.", file=sys.stderr)
    if __import__("os").environ.get("PLX_DEBUG"):
        traceback.print_exc()
    return 2


def entry() -> None:
    """Console-script entry: run, flush, and skip the interpreter's teardown of large trees.

    Every file plxtools writes is written atomically and fsynced before this point, so leaving
    without freeing objects loses nothing; it saves ~0.2 s per run.
    """
    from plxtools import runmemo, runmode

    runmode.one_shot(sys.argv[1:2] != ["lsp"])  # the process ends after the command (the server lives on)
    code = runmemo.replay(sys.argv[1:])  # an unchanged one-file run: its output, nothing imported
    if code is None:
        runmode.watch_interrupts()  # (not before: `signal` and its enums cost a replay ~1-5 ms)
        token = runmemo.start(sys.argv[1:])
        code = main()
        runmemo.finish(token, code)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (BrokenPipeError, OSError, ValueError):  # ValueError: the server closed stdout itself
        pass
    import os

    os._exit(code)


if __name__ == "__main__":  # pragma: no cover
    entry()
