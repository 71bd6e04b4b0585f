"""The generated docs (rule pages, CLI help blocks, changelog copy) match the code they come from.

When this fails, run `python -m plxtools.docgen` and commit the result.
"""

from __future__ import annotations

from plxtools import docgen as gen
from plxtools.rules.registry import all_rules
from tests.conftest import REPO, run_plx

DOCS = REPO / "docs"
HINT = "generated docs are stale: run `python -m plxtools.docgen`"


def test_rule_pages_regenerate_identically(tmp_path):
    out = tmp_path / "docs"
    gen.write(out, REPO)
    fresh = sorted(p.name for p in (out / "rules").glob("*.md"))
    committed = sorted(p.name for p in (DOCS / "rules").glob("*.md"))
    assert fresh == committed, HINT
    for name in fresh:
        assert (out / "rules" / name).read_text(encoding="utf-8") == (DOCS / "rules" / name).read_text(
            encoding="utf-8"), f"docs/rules/{name}: {HINT}"


def test_nothing_generated_is_stale():
    assert gen.differences(DOCS, REPO) == [], HINT


def test_one_page_per_rule_and_the_index_links_them_all():
    index = (DOCS / "rules" / "index.md").read_text(encoding="utf-8")
    for r in all_rules():
        assert (DOCS / "rules" / f"{r.code}.md").is_file()
        assert f"[{r.code}]({r.code}.md)" in index


def test_rule_page_starts_with_what_plx_rule_prints():
    r = run_plx("rule", "N002")
    assert r.returncode == 0
    page = (DOCS / "rules" / "N002.md").read_text(encoding="utf-8")
    assert r.stdout.strip() in page


def test_cli_reference_shows_the_real_help():
    """Each `plx CMD --help` block in docs/cli.md is what the program prints at 100 columns."""
    blocks = gen.help_blocks((DOCS / "cli.md").read_text(encoding="utf-8"))
    texts = gen.help_texts()
    assert set(blocks) == set(texts), "docs/cli.md needs one help block per command"
    for cmd, text in texts.items():
        assert blocks[cmd] == text.rstrip() + "\n", f"plx {cmd} --help: {HINT}"
    r = run_plx("--help", env={"COLUMNS": str(gen.HELP_WIDTH)})
    assert r.stdout == texts["plx"]


def test_every_option_is_explained_in_the_cli_reference():
    """Beyond the help blocks, the hand-written notes mention every option of every command."""
    import argparse

    from plxtools.cli import build_parser

    prose = gen._HELP_BLOCK.sub("", (DOCS / "cli.md").read_text(encoding="utf-8"))
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    missing = []
    for name, parser in sub.choices.items():
        assert f"## plx {name}" in prose
        for action in parser._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            longest = max(action.option_strings, key=len) if action.option_strings else None
            if longest and f"`{longest}" not in prose:
                missing.append(f"plx {name} {longest}")
    assert missing == []


def test_changelog_page_is_the_changelog():
    page = (DOCS / "changelog.md").read_text(encoding="utf-8")
    assert page.endswith((REPO / "CHANGELOG.md").read_text(encoding="utf-8"))
