"""The example models do what the docs say: clean ones are clean and simulate, broken ones show
exactly the diagnostics they name, and the snippets in the docs work."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from plxtools.rules.registry import get
from tests.conftest import REPO, run_plx

EXAMPLES = REPO / "examples"
TUTORIAL = sorted((EXAMPLES / "tutorial").glob("step*/boxtruck.openplx"))
LINT_ERRORS = sorted((EXAMPLES / "lint_errors").glob("*.openplx"))
SHOWS = re.compile(r"^# Shows: (.+)$", re.M)


def lint_json(*args: str) -> list[dict]:
    r = run_plx("lint", "--output-format", "json", *args)
    assert r.returncode in (0, 1), r.stderr
    return json.loads(r.stdout)


def test_tutorial_has_one_folder_per_step_with_the_tutorials_names():
    """Issue 32.8: the reader compares their boxtruck.openplx with the one of the step they are at."""
    assert [p.parent.name[:6] for p in TUTORIAL] == [f"step{n:02d}" for n in range(2, 12)]
    last = TUTORIAL[-1].read_text(encoding="utf-8")
    for name in ("BoxTruck is", "boxTruck is BoxTruck", "GroundPlane is", "front_left_drive_motor is",
                 "front_right_hinge_joint is", "chassis_wheels_collision_group is", "WheelGroundFrictionModel is"):
        assert name in last, name


def test_tutorial_steps_format_stable():
    r = run_plx("fmt", "--check", "examples/tutorial")
    assert r.returncode == 0, r.stdout + r.stderr


def test_tutorial_step11_scenario_and_script_pass():
    r = run_plx("test", "examples/tutorial/step11-controls")
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout + r.stderr
    r = subprocess.run([sys.executable, str(EXAMPLES / "tutorial" / "step11-controls" / "drive.py")],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "after up" in r.stdout and "after release" in r.stdout


def test_clean_examples_have_no_diagnostic_at_all():
    """Not even an info: the examples are what users copy."""
    diags = lint_json("examples/tutorial", "examples/user_bundle", "examples/boxtruck",
                      "--bundle-path", "examples/user_bundle")
    assert diags == [], [f"{d['file']}:{d['range']['start']['line']}: {d['code']} {d['message']}" for d in diags]


def test_user_bundle_lints_without_flags_thanks_to_its_plx_toml():
    assert lint_json("examples/user_bundle") == []
    r = run_plx("lint", "cart_scene.openplx", cwd=EXAMPLES / "user_bundle")
    assert r.returncode == 0 and "All checks passed" in r.stdout, r.stdout + r.stderr


def test_user_bundle_has_namespaces_and_a_dependency_on_another_user_bundle():
    machines = (EXAMPLES / "user_bundle" / "Machines" / "config.openplx").read_text()
    assert '"Parts@' in machines and '"Physics3D' in machines
    assert (EXAMPLES / "user_bundle" / "Parts" / "config.openplx").is_file()
    assert list((EXAMPLES / "user_bundle" / "Parts").glob("*/*.openplx")), "Parts needs namespace folders"


@pytest.mark.parametrize("path", LINT_ERRORS, ids=lambda p: p.name)
def test_lint_error_example_shows_what_it_says(path):
    m = SHOWS.search(path.read_text(encoding="utf-8"))
    assert m, f"{path.name} needs a '# Shows: CODE name, ...' line"
    claimed = {}
    for item in m.group(1).split(","):
        code, name = item.split()
        rule = get(code)
        assert rule is not None and rule.name == name, f"{path.name}: {code} is not {name}"
        claimed[code] = name
    reported = {d["code"] for d in lint_json(str(path.relative_to(REPO)))}
    assert reported == set(claimed), f"{path.name} claims {sorted(claimed)} but plx reports {sorted(reported)}"


def test_every_lint_error_example_is_listed_in_the_docs():
    page = (REPO / "docs" / "examples.md").read_text(encoding="utf-8")
    for path in LINT_ERRORS:
        assert f"`{path.name}`" in page, path.name


def test_examples_folder_lints_clean_with_its_config():
    r = run_plx("lint", "examples/")
    assert r.returncode == 0 and "All checks passed" in r.stdout, r.stdout + r.stderr


def test_clean_examples_simulate_and_drive():
    """Every scene simulates without an error; the trucks and the cart roll forward along +x."""
    files = [str(p.relative_to(REPO)) for p in TUTORIAL] + ["examples/user_bundle/cart_scene.openplx"]
    r = run_plx("check", "--simulate", "--output-format", "json", *files)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr
    doc = json.loads(r.stdout)
    assert [d for d in doc["diagnostics"] if d["severity"] == "error"] == []
    sim = doc["simulation"]
    assert set(sim) == set(files)

    def moved_x(file, body):
        b = sim[file]["bodies"][body]
        return b["final"]["position"][0] - b["initial"]["position"][0]

    def height(file, body):
        return sim[file]["bodies"][body]["final"]["position"][2]

    step = {p.parent.name[:6]: str(p.relative_to(REPO)) for p in TUTORIAL}
    assert height(step["step03"], "chassis") < -10  # nothing to land on yet
    for n in ("step04", "step05", "step06"):
        assert abs(height(step[n], "chassis") - 0.77) < 0.05, n  # resting on the ground
    for n in ("step07", "step08"):
        assert abs(moved_x(step[n], "boxTruck.chassis")) < 0.05, n  # on its wheels, no motors yet
    for n in ("step09", "step10", "step11"):
        # equal speeds on mirrored hubs: the front wheels fight (A023) and slip at their target speed (velocity
        # constraints): the truck turns where it stands, its centre moving 0.25 m in 3 s (0.42 m on the plastic
        # contact of normal_restitution 0, steps 10 and 11; driving: 0.78 m)
        assert abs(moved_x(step[n], "boxTruck.chassis")) < 0.55, n
        assert abs(height(step[n], "boxTruck.chassis") - 1.0) < 0.05, n
    a023 = [d for d in doc["diagnostics"] if d["code"] == "A023"]
    assert {d["file"] for d in a023} == {step["step09"], step["step10"], step["step11"]}
    # 3 rad/s on 0.15 m wheels for 3 s: 1.35 m
    assert 1.1 < moved_x("examples/user_bundle/cart_scene.openplx", "cart.deck") < 1.5
    assert abs(height("examples/user_bundle/cart_scene.openplx", "cart.deck") - 0.3) < 0.05


# ---------------------------------------------------------------------- snippets in the docs

FENCE = re.compile(r"^```(?P<lang>[\w-]*)\n(?P<body>.*?)^```[ \t]*$", re.S | re.M)


def _blocks(page: str, lang: str) -> list[tuple[str, str]]:
    """(text before the block, block body) for every ```lang block of a page."""
    text = (REPO / "docs" / page).read_text(encoding="utf-8")
    return [(text[: m.start()], m.group("body")) for m in FENCE.finditer(text) if m.group("lang") == lang]


def test_configuration_examples_are_valid_config(tmp_path):
    from plxtools.config import parse_config

    import tomllib

    blocks = _blocks("configuration.md", "toml")
    assert len(blocks) >= 3
    for before, body in blocks:
        table = tomllib.loads(body)
        table = table.get("tool", {}).get("plx", table)
        parse_config(tmp_path / "plx.toml", table)  # raises on an unknown key or a bad value


def test_configuration_shows_the_real_examples_config():
    real = "\n".join(ln for ln in (EXAMPLES / "plx.toml").read_text().splitlines()
                     if ln.strip() and not ln.startswith("#"))
    shown = [body.strip() for _, body in _blocks("configuration.md", "toml")]
    assert real in shown


def test_suppression_example_lints_clean(tmp_path):
    (before, body), = [(b, s) for b, s in _blocks("configuration.md", "openplx") if b.rstrip().endswith("lints clean:")]
    f = tmp_path / "suppressions.openplx"
    f.write_text(body)
    r = run_plx("lint", str(f))
    assert r.returncode == 0 and "All checks passed" in r.stdout, r.stdout


def test_gitlab_code_quality_script_converts_real_output(tmp_path):
    (_, script), = _blocks("ci.md", "python")
    (tmp_path / "plx_codequality.py").write_text(script)
    lint = run_plx("lint", "--output-format", "json", "--exit-zero", *[str(p) for p in LINT_ERRORS])
    (tmp_path / "plx-lint.json").write_text(lint.stdout)
    r = subprocess.run([sys.executable, "plx_codequality.py", "plx-lint.json"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    report = json.loads(r.stdout)
    assert len(report) == len(json.loads(lint.stdout)) > 5
    for item in report:
        assert {"description", "check_name", "fingerprint", "severity", "location"} <= set(item)
        assert item["severity"] in {"info", "minor", "major", "critical", "blocker"}
        assert item["location"]["lines"]["begin"] >= 1
    assert len({i["fingerprint"] for i in report}) == len(report)
