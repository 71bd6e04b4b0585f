"""The `plx lint` command body: options to runner to reporter."""

from __future__ import annotations

import sys
from collections import Counter

from plxtools.config import ConfigError, config_for
from plxtools.diagnostics import Severity
from plxtools.lint.runner import UsageError, discover, fixed_text, lint_file, unified_diff


def _codes(s: str | None) -> list[str]:
    return [c.strip().upper() for c in s.split(",") if c.strip()] if s else []


def run_lint(args) -> int:
    from plxtools.rules.reporters import render

    try:
        files = discover(args.paths)
    except (UsageError, ConfigError) as exc:
        print(f"plx lint: {exc}", file=sys.stderr)
        return 2
    from plxtools.model.workspace import workspace_for_cli

    try:
        workspace = workspace_for_cli(args.bundle_path, files, use_cache=not args.no_cache,
                                      openplx_version=getattr(args, "openplx_version", None))
    except (UsageError, ConfigError, ValueError) as exc:
        print(f"plx lint: {exc}", file=sys.stderr)
        return 2
    if getattr(args, "show_settings", False):
        from plxtools.bundles_cli import print_settings

        return print_settings(workspace)
    note = workspace.bundle_set.announcement()
    if note and not args.quiet and args.output_format == "text":
        print(f"plx lint: {note}", file=sys.stderr)
    all_diags = []
    fixed_files = 0
    fixes_applied = 0
    for f in files:
        try:
            cfg = config_for(f)
        except ConfigError as exc:
            print(f"plx lint: {exc}", file=sys.stderr)
            return 2
        if args.select:
            cfg.select = _codes(args.select)
        if args.ignore:
            cfg.ignore = cfg.ignore + _codes(args.ignore)
        result = lint_file(f, cfg, workspace)
        diags = result.diagnostics
        if (args.fix or args.diff) and result.tree is not None and not result.tree.has_errors_of_syntax():
            new_text, n = fixed_text(result.tree, diags, args.unsafe_fixes)
            if n:
                if args.diff:
                    sys.stdout.write(unified_diff(str(f), result.tree.text, new_text))
                else:
                    from plxtools.fileio import write_atomic

                    try:
                        write_atomic(f, new_text, result.tree.had_bom)
                    except OSError as exc:  # the user's file system, not a bug: say what happened
                        print(f"plx lint: {exc.strerror}", file=sys.stderr)
                        return 2
                    fixed_files += 1
                    fixes_applied += n
                    diags = lint_file(f, cfg, workspace).diagnostics
        all_diags.extend(diags)
    if args.diff:
        return 0
    if args.statistics:
        counts = Counter((d.code, d.severity.value) for d in all_diags)
        for (code, sev), n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])):
            print(f"{n:6}  {code:6} {sev}")
    elif args.output_format == "text" and args.quiet:
        from plxtools.rules.reporters import render_text

        render_text(all_diags, sys.stdout, summary=False)
    else:
        render(all_diags, args.output_format, sys.stdout, files_checked=len(files))
    if args.fix and fixes_applied and args.output_format == "text":
        print(f"Fixed {fixes_applied} problem(s) in {fixed_files} file(s).")
    has_error = any(d.severity == Severity.ERROR for d in all_diags)
    return 0 if (args.exit_zero or not has_error) else 1
