"""docs/primer.md: its snippets, in order, are one model that `plx lint` and `plx check` pass, and
every rule it links to exists (so the page cannot teach what plx no longer says)."""

from __future__ import annotations

import re
from pathlib import Path

from plxtools.rules.registry import get
from tests.conftest import plx_here

PAGE = Path(__file__).resolve().parents[2] / "docs" / "primer.md"


def test_the_primer_snippets_are_one_clean_model(tmp_path):
    blocks = re.findall(r"```openplx\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
    f = tmp_path / "primer.openplx"
    f.write_text("\n".join(blocks), encoding="utf-8")
    r = plx_here("lint", str(f))
    assert r.returncode == 0 and "All checks passed" in r.stdout, r.stdout
    r = plx_here("check", str(f))
    assert r.returncode == 0 and " error " not in r.stdout and " warning " not in r.stdout, r.stdout


def test_every_linked_rule_exists():
    codes = re.findall(r"\(rules/([A-Z]\d{3})\.md\)", PAGE.read_text(encoding="utf-8"))
    assert len(codes) >= 15
    assert [c for c in codes if get(c) is None] == []
