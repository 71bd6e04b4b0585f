"""A case file and an expected snapshot for every registered rule code (issue 28, point 5).

`tests/cases/rules/<CODE>.openplx` is the smallest model that makes plx report CODE. Its first line
names the command that reports it (`# plx check --simulate --duration 0.5`; the file is appended);
`<CODE>.expected` is what that command prints, followed by its exit code. The case must report its
own code.

A code that needs more than one file (a bundle with its config.openplx, a scenario and its model,
a folder walk) is a folder case: `tests/cases/rules/<CODE>/` holds the files and a `case.txt` whose
first line names the whole command (`# plx lint --bundle-path . Shelf/config.openplx`: nothing is
appended), run inside the folder; its snapshot is `tests/cases/rules/<CODE>.expected` beside the
folder and the folder's path reads `<case>` in it. Scenario files there are named `*.toml`, not
`*.scenario.toml`, so that pytest's scenario plugin does not collect the failing ones as tests.

Every code of the registry has its own case here (`<CODE>.openplx`, `<CODE>_<what>.openplx` or a
folder `<CODE>/`): the guard below is generated from the registry and names each code that has none,
with the file to add and its first line.

After a deliberate change, regenerate with
`PLX_UPDATE_SNAPSHOTS=1 python -m pytest tests/test_rule_case_files.py` and review the diff.
"""

from __future__ import annotations

import os
import re
import shlex
from pathlib import Path

import pytest

from plxtools.rules.registry import all_rules
from plxtools.rules.registry import get as registry_rule
from tests.conftest import CASES, plx_here

RULE_CASES = CASES / "rules"
CASE_FILES = sorted(RULE_CASES.glob("*.openplx"))  # beside them: files a case imports (A042_machine.agx)
CASE_FOLDERS = sorted(p for p in RULE_CASES.iterdir() if p.is_dir())
FOLDER_COMMAND = "case.txt"  # in a folder case: its first line is the whole command
UPDATE = os.environ.get("PLX_UPDATE_SNAPSHOTS") == "1"
REPORTED = re.compile(r"^(?:\S+:)?\d+:\d+: (?:error|warning|info) ([A-Z]\d{3}) ", re.M)
# codes that no case file can show, each with the test that reports it instead
NOT_A_CASE = {
    "B000": "tests/ide/test_bundles_unavailable.py",  # the bundles are not installed at all
    "B006": "tests/bundles/test_dependency_pins.py",  # reported in a bundle's own config.openplx
    # an unreadable file: permissions cannot live in git, and a dangling link kept in tests/cases
    # would break the tests that read every case file (tests/syntax/test_fast_path.py)
    "E001": "tests/test_rule_case_files.py",  # test_an_unreadable_file_is_a_located_error below
    # a plane on a moving body: no bundle geometry becomes a plane, only a scene built through the API
    "A127": "tests/check/test_mujoco_backend.py",
}


def command_of(path: Path) -> list[str]:
    first = path.read_text(encoding="utf-8", errors="replace").splitlines()[0]
    assert first.startswith("# plx "), f"{path.name}: the first line must name the command"
    return shlex.split(first[len("# plx "):])


# what differs between two runs of the same case: the wall time a simulation or a `plx test` run
# took, the checkout's folder
WALL = re.compile(r"\d+(?:\.\d+)? s wall\)")
TEST_TIME = re.compile(r"^(\d+ (?:passed|failed|error).*) in \d+(?:\.\d+)?s$", re.M)


def snapshot(path: Path) -> str:
    if path.is_dir():  # a folder case: the command as written, run inside the folder
        assert (path / FOLDER_COMMAND).is_file(), f"{path.name}/: a folder case needs its {FOLDER_COMMAND}"
        r = plx_here(*command_of(path / FOLDER_COMMAND), cwd=path)
        here, shown = path, "<case>"
    else:
        r = plx_here(*command_of(path), path.name, cwd=path.parent)
        here, shown = path.parent, "<cases>"
    text = r.stdout + (("# stderr\n" + r.stderr) if r.stderr else "") + f"# exit code {r.returncode}\n"
    return TEST_TIME.sub(r"\1 in <t>s", WALL.sub("<t> s wall)", text.replace(str(here), shown)))


@pytest.mark.parametrize("path", CASE_FILES + CASE_FOLDERS, ids=lambda p: p.stem)
def test_rule_case(path: Path):
    got = snapshot(path)
    expected = path.parent / f"{path.stem}.expected"
    if UPDATE:
        expected.write_text(got, encoding="utf-8")
    assert got == expected.read_text(encoding="utf-8"), f"snapshot differs: {expected.name}"
    own = path.stem.split("_")[0]
    assert own in REPORTED.findall(got), f"{path.name} does not report {own}"


def codes_with_a_case() -> set[str]:
    """The codes that have a case file or folder of their own in tests/cases/rules/."""
    return {p.name.split(".")[0].split("_")[0] for p in [*CASE_FILES, *CASE_FOLDERS]}


# codes still without a case file (issue 28): this list may only shrink; a code that gets a case
# must leave it (the test below fails while it is still named here). The one left is unreachable from
# any input: the stepping loop ends early only on a blow-up (A101) or the time limit (A109), which
# both exclude A108, and otherwise runs round(duration / h) steps; it shows only where that rounding
# and float arithmetic meet (`--duration 1.157`: "simulated 1.156 of 1.157 s"), not the early stop
# the rule describes. It stays registered as a safety net.
WITHOUT_A_CASE_YET = set("""
A108
""".split())


def test_every_registered_code_has_a_case_file():
    registered = {r.code for r in all_rules()}
    have = codes_with_a_case()
    missing = registered - have - set(NOT_A_CASE) - WITHOUT_A_CASE_YET
    assert not missing, f"{len(missing)} registered code(s) without a case in tests/cases/rules/; for each, add " \
        "the smallest model that makes plx report it, with near misses that must stay silent:\n  " + "\n  ".join(
            f"{code} ({registry_rule(code).name}, stage {registry_rule(code).stage}): tests/cases/rules/{code}.openplx, "
            f"first line '# plx {'lint' if registry_rule(code).stage in ('lint', 'syntax') else 'check'}'"
            for code in sorted(missing))
    assert not WITHOUT_A_CASE_YET & have, "these codes have a case now: remove them from WITHOUT_A_CASE_YET"
    assert not set(NOT_A_CASE) & have, "these codes have a case now: remove them from NOT_A_CASE"
    assert WITHOUT_A_CASE_YET <= registered and set(NOT_A_CASE) <= registered
    assert have <= registered | {"README"}, f"case files for codes the registry does not have: {sorted(have - registered)}"
    for code, test in NOT_A_CASE.items():
        assert code in (Path(__file__).parents[1] / test).read_text(encoding="utf-8")


def test_an_unreadable_file_is_a_located_error(tmp_path):
    """E001, from both commands that read files: a link to a file that is gone, found by the walk,
    is one located error (not a traceback, not "All checks passed"), and the other files are still
    checked."""
    (tmp_path / "gone.openplx").symlink_to(tmp_path / "missing.openplx")
    (tmp_path / "fine.openplx").write_text("Scene is Physics3D.System:\n    a is Real: 1\n", encoding="utf-8")
    for command in ("lint", "check"):
        r = plx_here(command, ".", cwd=tmp_path)
        assert r.returncode == 1 and "Traceback" not in r.stdout + r.stderr, r.stdout + r.stderr
        errors = [ln for ln in r.stdout.splitlines() if " error " in ln]
        assert errors == ["gone.openplx:1:1: error E001 cannot read file: No such file or directory"], r.stdout
        assert "All checks passed" not in r.stdout
    assert "fine.openplx: Scene: 0 bodies" in r.stdout and "gone.openplx: not assembled: the file cannot be read" \
        in r.stdout, r.stdout  # check: the readable file is still assembled
