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
CATALOG = PACKAGE / "rules" / "catalog"  # the documentation of the rules not in the module form
LITERAL = re.compile(r"""["']([A-Z]\d{3})["']""")

# ---------------------------------------------------------------- one place for every code
# A code is written as a string only in plxtools/rules/registry.py (issue 38). Layers above `rules`
# name a code by its registry constant (`registry.MISSING_VALUE`); a rule module never names its
# code (the engine stamps it). The layers below `rules` cannot import the registry: they record
# facts (plxtools/model/facts.py) that rule modules report. The findings below still make their
# diagnostics where they are found, with their code: this list may only shrink (a pair that is
# gone must leave it), and any other code string anywhere in plxtools fails.
REGISTRY = PACKAGE / "rules" / "registry.py"
NOT_MOVED_YET: dict[str, set[str]] = {
    "plxtools/syntax/lexer.py": {"S003", "S004", "S005", "S006", "S007", "S008", "S009"},
    "plxtools/syntax/parser.py": {"S010", "S011", "S012", "S013", "S014", "S015", "S016"},
    "plxtools/syntax/source.py": {"E001", "S001", "S002"},
}


def code_constants() -> dict[str, str]:
    """code -> its constant in the registry, generated from the registry module itself."""
    from plxtools.rules import registry

    return {getattr(registry, n): n for n in dir(registry)
            if n.isupper() and isinstance(getattr(registry, n), str) and LITERAL.fullmatch(f'"{getattr(registry, n)}"')}


def written_codes(path: Path) -> list[tuple[int, str]]:
    text = path.read_text(encoding="utf-8")
    return [(text.count("\n", 0, m.start()) + 1, m.group(1)) for m in LITERAL.finditer(text)]


def test_a_code_is_written_only_in_the_registry():
    constants = code_constants()
    without = sorted(r.code for r in all_rules() if r.module is None and r.code not in constants)
    assert not without, f"codes of the older form without their constant in the registry: {without}"
    offenders, still = [], defaultdict(set)
    for path in sorted(PACKAGE.rglob("*.py")):
        if path == REGISTRY:
            continue
        where = path.relative_to(ROOT).as_posix()
        for line, code in written_codes(path):
            if code in NOT_MOVED_YET.get(where, ()):
                still[where].add(code)
                continue
            hint = f"registry.{constants[code]}" if code in constants else "register it in rules/registry.py"
            offenders.append(f"{where}:{line}: '{code}' -> use {hint} (below rules: record a fact)")
    assert not offenders, ("rule codes written outside plxtools/rules/registry.py (name each through the "
                           "registry):\n  " + "\n  ".join(offenders))
    moved = {where: sorted(codes - still[where]) for where, codes in NOT_MOVED_YET.items() if codes - still[where]}
    assert not moved, f"no longer written there; take them off NOT_MOVED_YET: {moved}"


def test_every_registered_code_is_raised_somewhere():
    """A code's constant is used outside the registry and the docs catalogue, or the code is made by
    a rule module, or (below rules) written where its finding is made."""
    constants = code_constants()
    used: set[str] = set()
    for path in PACKAGE.rglob("*.py"):
        if path == REGISTRY or CATALOG in path.parents:
            continue
        text = path.read_text(encoding="utf-8")
        used.update(n for n in re.findall(r"\b([A-Z][A-Z0-9_]+)\b", text) if n in constants.values())
        if path.relative_to(ROOT).as_posix() in NOT_MOVED_YET:
            used.update(constants[c] for _line, c in written_codes(path) if c in constants)
    missing = sorted(r.code for r in all_rules() if r.module is None and constants.get(r.code) not in used)
    assert not missing, f"registered codes that nothing raises (no use of their registry constant): {missing}"


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
