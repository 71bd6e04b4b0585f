"""The checks that stand between the formatter and the user's file.

Before anything is written, the output is parsed again: it must mean the same as the input (the
same layout-free tree, the same comments in the same order), formatting it once more must
change nothing, and when the file has `# plx: ignore` comments (the only thing that makes lint
results depend on layout) `plx lint` must report the same, suppressions applied. black does
the same with `--safe`; here it cannot be turned off.
"""

from __future__ import annotations

import re
from dataclasses import replace

from plxtools.syntax import ast
from plxtools.rules import registry

_DIGITS = re.compile(r"\d+")
_SUPPRESSION = re.compile(r"#\s*plx:\s*ignore")


def comment_texts(tree: ast.File) -> list[str]:
    # trailing whitespace is layout: the formatter removes it from comments too
    return [c.text.rstrip() for c in tree.comments]


def same_meaning(before: ast.File, after: ast.File) -> str | None:
    """None when both trees mean the same, else a short reason."""
    if after.has_errors:
        first = next(d for d in after.diagnostics if d.severity.value == "error")
        line = first.span.start.line + 1
        return f"the output does not parse (line {line}: {first.code} {first.message})"
    if ast.structure(before.statements) != ast.structure(after.statements):
        return "the output's syntax tree differs from the input's"
    if comment_texts(before) != comment_texts(after):
        return "the output's comments differ from the input's"
    return None


def _lint_signature(tree: ast.File) -> list[tuple[str, str, str, str]]:
    """What `plx lint` reports for a tree (suppressions applied), without positions."""
    from pathlib import Path

    from plxtools.config import Config, config_for
    from plxtools.rules.analysis import analyse_tree

    # what the formatter fixes by design (indentation, tabs): left out on both sides of the comparison
    layout_codes = (registry.MISALIGNED_INDENTATION, registry.TAB_INDENTATION)
    cfg = config_for(Path(tree.path)) if tree.path else Config()
    cfg = replace(cfg, ignore=list(cfg.ignore) + list(layout_codes))
    # messages may quote line numbers ("first defined at line 3"), which blank lines shift
    return sorted((d.code, d.severity.value, _DIGITS.sub("#", d.message), d.message) for d in analyse_tree(tree, cfg)
                  if d.code not in layout_codes)  # (syntax codes are never configured away)


def same_lint_results(before: ast.File, after: ast.File) -> str | None:
    """None when lint reports the same for both texts; only computed when suppressions exist."""
    if "plx:" not in before.text or not any(_SUPPRESSION.search(c.text) for c in before.comments):
        return None  # same tree, no suppression: the same diagnostics
    old, new = _lint_signature(before), _lint_signature(after)
    if [k[:3] for k in old] == [k[:3] for k in new]:
        return None
    gone = [f"{c} {m}" for c, s, n, m in old if (c, s, n) not in {k[:3] for k in new}]
    came = [f"{c} {m}" for c, s, n, m in new if (c, s, n) not in {k[:3] for k in old}]
    what = f"it would report {came[0]}" if came else f"it would no longer report {gone[0]}"
    return f"formatting would change what a `# plx: ignore` comment covers ({what})"
