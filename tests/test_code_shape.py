"""The shape issue 28 asks of the code: a home for each rule, no tangled function, a thin server.

Each list below names what does not have that shape yet. The lists may only shrink: a name that
gets fixed must leave its list (the tests fail while it is still named there), and anything new that
breaks a rule fails at once.
"""

from __future__ import annotations

import re
from collections import defaultdict
from pathlib import Path

import pytest

from plxtools.rules.registry import all_rules

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "plxtools"
CATALOG = PACKAGE / "rules" / "catalog"  # the rules' documentation: names every code once more
LITERAL = re.compile(r"""["']([A-Z]\d{3})["']""")

# ---------------------------------------------------------------- one home per code
# A code is written as a string in exactly one module: the one that raises it. Other modules that
# need to recognise it import that module's name for it, or ask the registry (`Rule.stage`).
NOT_ONE_HOME_YET = set("""

""".split())


def modules_naming_codes() -> dict[str, set[str]]:
    codes = {r.code for r in all_rules()}
    where: dict[str, set[str]] = defaultdict(set)
    for path in PACKAGE.rglob("*.py"):
        if CATALOG in path.parents:
            continue
        for code in LITERAL.findall(path.read_text(encoding="utf-8")):
            if code in codes:
                where[code].add(path.relative_to(ROOT).as_posix())
    return where


def test_each_code_is_written_in_one_module():
    where = modules_naming_codes()
    spread = {code: sorted(mods) for code, mods in where.items() if len(mods) > 1}
    new = {code: mods for code, mods in spread.items() if code not in NOT_ONE_HOME_YET}
    assert not new, f"codes written as a string in more than one module: {new}"
    fixed = sorted(NOT_ONE_HOME_YET - set(spread))
    assert not fixed, f"these codes have one home now; take them off NOT_ONE_HOME_YET: {fixed}"


def test_every_registered_code_is_raised_somewhere():
    where = modules_naming_codes()
    missing = sorted(r.code for r in all_rules() if r.code not in where)
    assert not missing, f"registered codes no module raises: {missing}"


# ---------------------------------------------------------------- complexity
LIMIT = 25
TOO_COMPLEX_YET = set("""

""".split())


def complexities() -> dict[str, int]:
    """Cyclomatic complexity (radon) of every function, method and nested function in plxtools."""
    radon = pytest.importorskip("radon.complexity")
    out: dict[str, int] = {}

    def walk(blocks, where: str) -> None:
        for block in blocks:
            name = getattr(block, "fullname", block.name)
            out[f"{where}:{name}"] = max(out.get(f"{where}:{name}", 0), block.complexity)
            walk(getattr(block, "closures", []), where)
            walk(getattr(block, "methods", []), where)

    for path in sorted(PACKAGE.rglob("*.py")):
        walk(radon.cc_visit(path.read_text(encoding="utf-8")), path.relative_to(ROOT).as_posix())
    return out


def test_no_function_above_complexity_limit():
    over = {name: cc for name, cc in complexities().items() if cc > LIMIT}
    new = {name: cc for name, cc in over.items() if name not in TOO_COMPLEX_YET}
    assert not new, f"functions above cyclomatic complexity {LIMIT}: {new}"
    fixed = sorted(TOO_COMPLEX_YET - set(over))
    assert not fixed, f"these are at or below {LIMIT} now; take them off TOO_COMPLEX_YET: {fixed}"


# ---------------------------------------------------------------- a thin server
LSP_LINES = 500
LSP_TOO_LONG_YET: set[str] = set()


def test_no_lsp_module_above_500_lines():
    long = {path.relative_to(ROOT).as_posix() for path in (PACKAGE / "lsp").rglob("*.py")
            if len(path.read_text(encoding="utf-8").splitlines()) > LSP_LINES}
    assert long <= LSP_TOO_LONG_YET, f"lsp modules above {LSP_LINES} lines: {sorted(long - LSP_TOO_LONG_YET)}"
    fixed = sorted(LSP_TOO_LONG_YET - long)
    assert not fixed, f"at or below {LSP_LINES} lines now; take them off LSP_TOO_LONG_YET: {fixed}"
