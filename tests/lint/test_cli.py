"""`plx lint` through the command line: formats, exit codes, config, suppressions, fixes."""

import json

from tests.conftest import REPO, plx_here

BROKEN = "Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mas: 10\n\nScene is Physics3D.System:\n    wheel is Wheel\n"


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_example_clean_exit_zero():
    r = plx_here("lint", "examples/")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "All checks passed" in r.stdout


def test_json_contract(tmp_path):
    p = write(tmp_path, "w.openplx", BROKEN)
    r = plx_here("lint", str(p), "--output-format", "json")
    assert r.returncode == 1
    items = json.loads(r.stdout)
    assert len(items) == 1
    d = items[0]
    assert d["code"] == "N002" and d["severity"] == "error" and d["file"] == str(p)
    assert d["range"] == {"start": {"line": 2, "column": 13}, "end": {"line": 2, "column": 16}}
    assert d["fix"]["applicability"] == "unsafe"


def test_github_and_sarif(tmp_path):
    p = write(tmp_path, "w.openplx", BROKEN)
    r = plx_here("lint", str(p), "--output-format", "github")
    assert r.stdout.startswith("::error file=") and "line=2,col=13" in r.stdout
    r = plx_here("lint", str(p), "--output-format", "sarif")
    doc = json.loads(r.stdout)
    assert doc["version"] == "2.1.0"
    res = doc["runs"][0]["results"][0]
    assert res["ruleId"] == "N002" and res["locations"][0]["physicalLocation"]["region"]["startLine"] == 2
    assert doc["runs"][0]["tool"]["driver"]["rules"][0]["name"] == "unknown-attribute"


def test_exit_zero_statistics_select_ignore(tmp_path):
    p = write(tmp_path, "w.openplx", BROKEN)
    assert plx_here("lint", str(p), "--exit-zero").returncode == 0
    r = plx_here("lint", str(p), "--statistics")
    assert "N002" in r.stdout and r.returncode == 1
    assert plx_here("lint", str(p), "--ignore", "N002").returncode == 0
    assert plx_here("lint", str(p), "--select", "T").returncode == 0


def test_config_closest_file_wins(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[tool.plx]\nignore = ["N002"]\n')
    sub = tmp_path / "models"
    sub.mkdir()
    write(sub, "w.openplx", BROKEN)
    assert plx_here("lint", str(sub)).returncode == 0
    (sub / "plx.toml").write_text('select = ["N"]\n')
    assert plx_here("lint", str(sub)).returncode == 1
    (sub / "plx.toml").write_text('per-file-ignores = {"w.openplx" = ["N002"]}\n')
    assert plx_here("lint", str(sub)).returncode == 0


def test_bad_config_is_a_usage_error(tmp_path):
    (tmp_path / "plx.toml").write_text("selec = [1]\n")
    write(tmp_path, "w.openplx", BROKEN)
    r = plx_here("lint", str(tmp_path))
    assert r.returncode == 2 and "unknown key" in r.stderr and "Traceback" not in r.stderr


def test_file_suppression_and_unused(tmp_path):
    p = write(tmp_path, "w.openplx", "# plx: ignore-file[N002]\n" + BROKEN)
    assert plx_here("lint", str(p)).returncode == 0
    p = write(tmp_path, "v.openplx", BROKEN.replace("mas: 10", "mass: 10  # plx: ignore[N002]"))
    r = plx_here("lint", str(p), "--output-format", "json")
    assert [d["code"] for d in json.loads(r.stdout)] == ["C002"]


def test_fix_and_unsafe_fixes(tmp_path):
    p = write(tmp_path, "w.openplx", BROKEN)
    r = plx_here("lint", str(p), "--fix")
    assert p.read_text() == BROKEN  # the rename is unsafe: not applied by --fix alone
    r = plx_here("lint", str(p), "--fix", "--unsafe-fixes")
    assert "inertia.mass: 10" in p.read_text() and r.returncode == 0


def test_diff_does_not_write(tmp_path):
    p = write(tmp_path, "w.openplx", BROKEN)
    r = plx_here("lint", str(p), "--diff", "--unsafe-fixes")
    assert "+    inertia.mass: 10" in r.stdout and p.read_text() == BROKEN


def test_rule_command():
    r = plx_here("rule", "N002")
    assert r.returncode == 0 and "# N002 unknown-attribute" in r.stdout and "## Example" in r.stdout
    r = plx_here("rule", "--all")
    assert "S011" in r.stdout and "M007" in r.stdout
    assert plx_here("rule", "X999").returncode == 2


def test_excluded_folder_named_explicitly_is_still_linted(tmp_path):
    (tmp_path / "plx.toml").write_text('exclude = ["broken"]\n')
    broken = tmp_path / "broken"
    broken.mkdir()
    write(broken, "w.openplx", BROKEN)
    write(tmp_path, "ok.openplx", "Scene is Physics3D.System\n")
    r = plx_here("lint", str(tmp_path))
    assert r.returncode == 0 and "1 file" in r.stdout  # walking the parent skips the excluded folder
    r = plx_here("lint", str(broken))
    assert r.returncode == 1 and "N002" in r.stdout  # naming it explicitly lints it
