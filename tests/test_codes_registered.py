"""Every code the code base can emit is a registered rule with a docs page (issue 11)."""

from __future__ import annotations

import re
from pathlib import Path

from plxtools.rules.registry import all_rules

PKG = Path(__file__).resolve().parents[1] / "plxtools"
CODE = re.compile(r"""["']([A-Z]\d{3})["']""")


def test_every_code_in_the_source_is_registered():
    known = {r.code for r in all_rules()}
    found: dict[str, set[str]] = {}
    for p in PKG.rglob("*.py"):
        for m in CODE.finditer(p.read_text(encoding="utf-8")):
            found.setdefault(m.group(1), set()).add(str(p.relative_to(PKG)))
    assert len(found) > 50  # the scan sees the codes (it would pass vacuously otherwise)
    missing = {c: sorted(v) for c, v in found.items() if c not in known}
    assert not missing, f"codes emitted but not registered: {missing}"


def test_every_registered_code_has_a_docs_page():
    docs = PKG.parent / "docs" / "rules"
    assert [r.code for r in all_rules() if not (docs / f"{r.code}.md").is_file()] == []
