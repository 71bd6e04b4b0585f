"""SARIF as GitHub code scanning ingests it: every rule a result points at is described in
tool.driver.rules with the text GitHub shows beside an alert (its validation rules GH2012 and the
SARIF2012 "provide rule properties" family check these fields), and links to its documentation page."""

from __future__ import annotations

import json
import re
from pathlib import Path

from plxtools import DOCS_BASE_URL
from tests.conftest import REPO, plx_here

BROKEN = """Scene is Physics3D.System:
    b is Physics3D.Bodies.RigidBdy
    c is Physics3D.Bodies.RigidBody:
        inertia.mas: 3
    d is
"""


def _sarif(tmp_path: Path) -> dict:
    f = tmp_path / "broken.openplx"
    f.write_text(BROKEN, encoding="utf-8")
    r = plx_here("lint", "--output-format", "sarif", "broken.openplx", cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    return json.loads(r.stdout)


def test_every_rule_has_the_text_and_links_github_shows(tmp_path):
    doc = _sarif(tmp_path)
    run = doc["runs"][0]
    rules = run["tool"]["driver"]["rules"]
    results = run["results"]
    codes = {r["ruleId"] for r in results}
    assert len(codes) >= 2, codes
    assert [r["id"] for r in rules] == sorted(codes)  # each rule a result uses, once
    index = {r["id"]: i for i, r in enumerate(rules)}
    for rule in rules:
        code = rule["id"]
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", rule["name"]) and rule["name"] != code
        assert rule["shortDescription"]["text"].strip()
        full = rule["fullDescription"]["text"]
        assert full.startswith(rule["shortDescription"]["text"]) and len(full) > len(rule["shortDescription"]["text"])
        assert rule["help"]["text"].strip() and rule["help"]["markdown"].startswith(f"# {code} {rule['name']}")
        assert "## Why it matters" in rule["help"]["markdown"]
        assert rule["helpUri"] == f"{DOCS_BASE_URL}rules/{code}/"
        assert rule["defaultConfiguration"]["level"] in ("error", "warning", "note")
        page = REPO / "docs" / "rules" / f"{code}.md"  # the page the link names is built from this file
        assert page.is_file(), page
        assert rule["shortDescription"]["text"] in page.read_text(encoding="utf-8")
    for res in results:
        assert res["ruleId"] in index and res["message"]["text"]
        region = res["locations"][0]["physicalLocation"]["region"]
        assert region["startLine"] >= 1 and region["startColumn"] >= 1
        artifact = res["locations"][0]["physicalLocation"]["artifactLocation"]
        assert artifact == {"uri": "broken.openplx", "uriBaseId": "%SRCROOT%"}


def test_help_text_points_at_the_documentation_site_not_repository_paths():
    r = plx_here("--help")
    assert DOCS_BASE_URL in r.stdout and "docs/getting-started.md" not in r.stdout, r.stdout
    for cmd in ("view", "check", "cache"):
        r = plx_here(cmd, "--help") if cmd != "cache" else plx_here("--help")
        assert not re.search(r"\bdocs/[a-z-]+\.md\b", r.stdout), (cmd, r.stdout)
    assert f"{DOCS_BASE_URL}view/" in plx_here("view", "--help").stdout
