"""The documentation site builds with `mkdocs build --strict`: no broken link, anchor or nav entry."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import REPO


def test_mkdocs_build_strict(tmp_path):
    pytest.importorskip("mkdocs", reason="mkdocs is not installed (pip install -e '.[docs]')")
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
                       cwd=REPO, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    site = tmp_path / "site"
    for page in ("index.html", "getting-started/index.html", "cli/index.html", "rules/index.html",
                 "rules/N002/index.html", "changelog/index.html"):
        assert (site / page).is_file(), page


def test_nav_lists_every_top_level_page():
    """A page under docs/ that is not in the nav is easy to miss; only the generated rule pages may be."""
    yaml = pytest.importorskip("yaml", reason="PyYAML comes with mkdocs (pip install -e '.[docs]')")
    config = yaml.safe_load((REPO / "mkdocs.yml").read_text(encoding="utf-8"))

    def pages(nav):
        for item in nav:
            value = next(iter(item.values())) if isinstance(item, dict) else item
            if isinstance(value, list):
                yield from pages(value)
            else:
                yield value

    in_nav = set(pages(config["nav"]))
    on_disk = {p.relative_to(REPO / "docs").as_posix() for p in (REPO / "docs").rglob("*.md")}
    assert on_disk - in_nav == {p for p in on_disk if p.startswith("rules/") and p != "rules/index.md"}
    assert in_nav - on_disk == set(), "the nav names pages that do not exist"
