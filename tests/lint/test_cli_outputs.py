"""The command line and output formats as a user meets them (issue 16): unknown rule codes,
stdin, severities in text, plurals, SARIF and GitHub paths, JSON keys, the docs link."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

from tests.conftest import REPO, plx_here

TYPO = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n    typo is Physics3D.Bodies.RigidBdy\n"
UNUSED = "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody  # plx: ignore[N002]\n"


def _write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def test_an_unknown_code_in_select_is_a_usage_error_with_a_suggestion(tmp_path):
    f = _write(tmp_path / "a.openplx", TYPO)
    r = plx_here("lint", "--select", "N0002", str(f))
    assert r.returncode == 2 and "'N0002'" in r.stderr and "did you mean 'N002'" in r.stderr, r.stderr
    assert r.stdout == ""  # nothing linted, so nothing claimed
    r = plx_here("lint", "--ignore", "XYZ9", str(f))
    assert r.returncode == 2 and "'XYZ9'" in r.stderr


def test_an_unknown_code_in_the_config_is_a_usage_error_naming_the_file_and_key(tmp_path):
    f = _write(tmp_path / "a.openplx", TYPO)
    cfg = _write(tmp_path / "plx.toml", 'select = ["N0002"]\n')
    r = plx_here("lint", str(f))
    assert r.returncode == 2 and f"{cfg}: select" in r.stderr and "did you mean 'N002'" in r.stderr, r.stderr
    _write(tmp_path / "plx.toml", '[per-file-ignores]\n"*.openplx" = ["C0001"]\n')
    r = plx_here("lint", str(f))
    assert r.returncode == 2 and "per-file-ignores" in r.stderr and "'C001'" in r.stderr, r.stderr


def test_valid_prefixes_and_all_are_accepted(tmp_path):
    f = _write(tmp_path / "a.openplx", TYPO)
    assert plx_here("lint", "--select", "N,T001,ALL", str(f)).returncode == 1


def test_lint_reads_stdin_with_the_given_filename(tmp_path):
    r = plx_here("lint", "-", "--stdin-filename", "models/scene.openplx", stdin=TYPO, cwd=tmp_path)
    assert r.returncode == 1
    assert r.stdout.startswith("models/scene.openplx:3:13: error N001 unknown type 'Physics3D.Bodies.RigidBdy'")


def test_lint_fix_on_stdin_prints_the_fixed_text(tmp_path):
    r = plx_here("lint", "-", "--fix", stdin=UNUSED, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout == "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n"
    assert "Fixed 1 problem in 1 file." in r.stderr


def test_text_lines_show_the_severity_and_plurals_are_right(tmp_path):
    f = _write(tmp_path / "a.openplx", UNUSED)
    r = plx_here("lint", str(f))
    assert f"{f}:2:38: warning C002 [*] unused suppression: suppressed code N002 matched" in r.stdout, r.stdout
    r = plx_here("lint", "--fix", str(f))
    assert "Fixed 1 problem in 1 file." in r.stdout and "(s)" not in r.stdout


def test_text_is_coloured_on_request_and_plain_with_no_color(tmp_path):
    f = _write(tmp_path / "a.openplx", TYPO)
    coloured = plx_here("lint", str(f), env={"NO_COLOR": "", "FORCE_COLOR": "1"})
    assert "\x1b[" in coloured.stdout and "error N001" in coloured.stdout
    assert "\x1b[" not in plx_here("lint", str(f)).stdout


def test_sarif_uris_survive_spaces_hashes_and_accents(tmp_path):
    f = _write(tmp_path / "my models" / "a b#é.openplx", TYPO)
    outside = _write(tmp_path.parent / f"{tmp_path.name}-outside.openplx", TYPO)
    r = plx_here("lint", "--output-format", "sarif", "my models", str(outside), cwd=tmp_path)
    run = json.loads(r.stdout)["runs"][0]
    base = run["originalUriBaseIds"]["%SRCROOT%"]["uri"]
    locs = [res["locations"][0]["physicalLocation"]["artifactLocation"] for res in run["results"]]
    inside = next(loc for loc in locs if loc.get("uriBaseId") == "%SRCROOT%")
    assert inside["uri"] == "my%20models/a%20b%23%C3%A9.openplx"
    assert base == tmp_path.resolve().as_uri() + "/"
    assert {"uri": outside.resolve().as_uri()} in locs
    assert f.exists()


def test_github_annotations_use_paths_from_the_repository_root(tmp_path):
    (tmp_path / ".git").mkdir()
    _write(tmp_path / "models" / "a.openplx", TYPO)
    r = plx_here("lint", "--output-format", "github", "a.openplx", cwd=tmp_path / "models")
    assert r.stdout.startswith("::error file=models/a.openplx,line=3,col=13"), r.stdout


def test_json_items_always_carry_help_and_fix(tmp_path):
    f = _write(tmp_path / "a.openplx", TYPO + "    Lower is Physics3D.Bodies.RigidBody\n")
    items = json.loads(plx_here("lint", "--output-format", "json", str(f)).stdout)
    assert items and all("help" in d and "fix" in d for d in items)
    assert any(d["help"] is None for d in items) or any(d["fix"] is None for d in items)


def test_rule_links_point_at_the_configured_docs_site():
    from plxtools import DOCS_BASE_URL
    from plxtools.rules.reporters import DOCS_URL

    urls = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["urls"]
    assert urls["Documentation"] == DOCS_BASE_URL and "invalid" not in DOCS_BASE_URL
    assert DOCS_URL.format(code="N002") == DOCS_BASE_URL + "rules/N002/"
    assert (REPO / "docs" / "rules" / "N002.md").is_file()  # mkdocs publishes it at rules/N002/
    out = subprocess.run([sys.executable, "-m", "plxtools", "lint", "--output-format", "sarif", "-"],
                         input=TYPO, capture_output=True, text=True, cwd=REPO)
    rules = json.loads(out.stdout)["runs"][0]["tool"]["driver"]["rules"]
    assert rules[0]["helpUri"] == DOCS_BASE_URL + "rules/N001/"
