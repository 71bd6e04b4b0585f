"""`plx migrate --explain` through the real command line, and docs/migration.md staying current."""

import json

from plxtools.migrate import docs
from plxtools.model.apichanges import changes, summary
from tests.conftest import run_plx


def test_explain_text_groups_the_changes():
    r = run_plx("migrate", "--explain", "0.17.26", "0.19.0")
    assert r.returncode == 0, r.stderr
    out = r.stdout
    moved = out.index("Moved models")
    assert out.index("Physics3D.Charges.Box -> Physics3D.Geometries.Box  [0.18.11]") > moved
    assert "Physics.Interactions.Interaction.charges -> connectors  [0.18.11] (table)" in out
    counts = summary(changes("0.17.26", "0.19.0"))
    assert f"{counts['automatic']} automatic, {counts['table']} from the reviewed table" in out


def test_explain_json_is_the_change_list():
    r = run_plx("migrate", "--explain", "0.18.10", "0.19.0", "--output-format", "json")
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    expected = changes("0.18.10", "0.19.0")
    assert data["from"] == "0.18.10" and data["to"] == "0.19.0"
    assert len(data["changes"]) == len(expected) and data["counts"] == summary(expected)
    box = next(c for c in data["changes"] if c["model"] == "Physics3D.Charges.Box")
    assert box["kind"] == "model-moved" and box["new"] == "Physics3D.Geometries.Box" and box["handling"] == "automatic"


def test_bad_versions_exit_2_with_one_line():
    for args in (("0.17.99", "0.19.0"), ("0.19.0", "0.17.26"), ("latest", "0.19.0")):
        r = run_plx("migrate", "--explain", *args)
        assert r.returncode == 2
        assert r.stdout == "" and "Traceback" not in r.stderr
        assert r.stderr.startswith("plx migrate: ") and r.stderr.count("\n") == 1


def test_migration_page_is_current():
    assert docs.PAGE.read_text(encoding="utf-8") == docs.page(), "run `python -m plxtools.migrate.docs`"
