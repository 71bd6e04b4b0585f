"""The language server's check re-uses the last version's findings for unchanged statements
(model/reuse.py). After every edit of a random editing session, what it reports must be exactly
what a fresh check of the same text reports: the diagnostics (with help, fixes, related), and
every occurrence (span, kind and the symbol it names), each naming a symbol of the current
version, never one of an older version."""

from __future__ import annotations

import random
import re
import sys
from pathlib import Path

import pytest

from plxtools.ide import AnalysisHost
from plxtools.rules import registry
from tests.conftest import campaign_size
from plxtools.model.symbols import GlobalSym, MemberSym, MethodSym, ModelSym

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "bench"))
from lsp_bench import openplx_text  # noqa: E402

SNIPPETS = ["x", "1", ".", ":", " ", "\n", "\n    ", "is ", " is Wheel0", "densty", "radius: 0.3\n", "Mat0",
            "Physics3D.Bodies.RigidBody", "#", "\"", "becomes ", "{1, 2, 3}", "\t", "fn f() -> Real\n"]


def _edit(rng: random.Random, text: str) -> str:
    lines = text.split("\n")
    op = rng.randrange(12)
    n = rng.randrange(len(lines))
    if op == 0 and len(text) > 2:  # delete a few characters
        i = rng.randrange(len(text) - 1)
        return text[:i] + text[i + rng.randint(1, 3):]
    if op == 1:  # type a snippet
        i = rng.randrange(len(text) + 1)
        return text[:i] + rng.choice(SNIPPETS) + text[i:]
    if op == 2 and len(lines) > 1:  # delete a line
        return "\n".join(lines[:n] + lines[n + 1:])
    if op == 3:  # duplicate a line
        return "\n".join(lines[:n + 1] + [lines[n]] + lines[n + 1:])
    if op == 4:  # rename a name defined at the top, at one place or everywhere
        tops = [ln.split(" ", 1)[0] for ln in lines if ln[:1].isalpha() and " is " in ln]
        if tops:
            old = rng.choice(tops)
            new = old + rng.choice(["X", "", "0"])
            return text.replace(old, new) if rng.random() < 0.5 else text.replace(old, new, 1)
    if op == 5:  # move a line elsewhere
        ln = lines.pop(n)
        lines.insert(rng.randrange(len(lines) + 1), ln)
        return "\n".join(lines)
    if op == 6:  # change a number
        for k in range(n, n + len(lines)):
            ln = lines[k % len(lines)]
            digits = [i for i, c in enumerate(ln) if c.isdigit()]
            if digits:
                i = rng.choice(digits)
                lines[k % len(lines)] = ln[:i] + str(rng.randrange(10)) + ln[i + 1:]
                return "\n".join(lines)
    if op == 7:  # misspell one use of a word (an attribute, a model, a value's name)
        words = [(m.start(), m.end()) for m in re.finditer(r"[A-Za-z_][A-Za-z0-9_]*", text)]
        if words:
            a, b = rng.choice(words)
            return text[:a] + text[a:b] + rng.choice(["X", "_", "s"]) + text[b:]
    if op == 9:  # give a top-level model another base: a model of the file, or a bundle type
        tops = [k for k, ln in enumerate(lines) if ln[:1].isalpha() and " is " in ln]
        names = [lines[k].split(" ", 1)[0] for k in tops]
        if tops:
            k = rng.choice(tops)
            head, _, rest = lines[k].partition(" is ")
            tail = rest[rest.index(":"):] if ":" in rest else ""
            lines[k] = f"{head} is {rng.choice(names + ['Physics3D.Bodies.RigidBody', 'Physics3D.System'])}{tail}"
            return "\n".join(lines)
    if op == 10:  # delete an attribute declared in a model (and what is below it)
        decls = [k for k, ln in enumerate(lines) if ln.startswith("    ") and not ln.startswith("     ")
                 and " is " in ln]
        if decls:
            k = rng.choice(decls)
            end = k + 1
            while end < len(lines) and lines[end].startswith("        "):
                end += 1
            return "\n".join(lines[:k] + lines[end:])
    if op == 11:  # add or remove an import (re-use is then off: an import reads other files)
        if lines and lines[0].startswith("import "):
            return "\n".join(lines[1:])
        return "\n".join([f'import "{rng.choice(["missing.openplx", "other.openplx"])}"'] + lines)
    # a blank line somewhere
    return "\n".join(lines[:n] + [""] + lines[n:])


def _describe(target) -> tuple:
    stmt = getattr(target, "stmt", None)
    span = tuple(stmt.span) if stmt is not None else None
    return (type(target).__name__, getattr(target, "qname", None) or getattr(target, "name", None), span)


def _home(target):
    if isinstance(target, (ModelSym, GlobalSym)):
        return target.unit
    if isinstance(target, (MemberSym, MethodSym)):
        return target.owner.unit
    return None


def _findings(st) -> tuple[list, list]:
    diags = [(d.to_json(), d.help, [(f, tuple(s), m) for f, s, m in d.related]) for d in st.diagnostics]
    occs = sorted((tuple(o.span), o.kind, _describe(o.target)) for o in st.occurrences)
    return diags, occs


def _fresh_findings(tmp_path, path: str, text: str, version: int) -> tuple[list, list]:
    """What a check of `text` from scratch, in a host of its own, finds."""
    ref = AnalysisHost(root=str(tmp_path))
    ref.open_document(path, text, version)
    return _findings(ref.state(path))


def _session(tmp_path, text: str, seed: int, steps: int) -> int:
    path = str(tmp_path / "session.openplx")
    host = AnalysisHost(root=str(tmp_path))
    ref = AnalysisHost(root=str(tmp_path))
    rng = random.Random(seed)
    host.open_document(path, text, 1)
    re_used = 0
    for version in range(2, steps + 2):
        text = _edit(rng, text)
        host.update_document(path, text, version)
        st = host.state(path)
        ref.close_document(path)
        ref.open_document(path, text, version)
        want = ref.state(path)
        got = _findings(st)
        assert got[0] == _findings(want)[0], f"seed {seed}, version {version}: diagnostics differ"
        assert got[1] == _findings(want)[1], f"seed {seed}, version {version}: occurrences differ"
        for o in st.occurrences:
            home = _home(o.target)
            if home is not None and home.path == path:
                assert home is st.unit, f"seed {seed}, version {version}: an occurrence names an old symbol"
        plan = st.analysis.plan
        re_used += len(plan.reused) if plan is not None else 0
    return re_used


def _sources() -> list[tuple[str, str]]:
    files = [REPO / "examples" / "boxtruck" / "boxtruck.openplx", *sorted((REPO / "examples" / "broken").glob("*.openplx")),
             *sorted((REPO / "examples" / "lint_errors").glob("*.openplx")),
             # the case files of the rule modules: each has findings the incremental rules must keep right
             *(REPO / "tests" / "cases" / "rules" / f"{code}.openplx" for code in registry.RULES
               if registry.RULES[code].module is not None
               and (REPO / "tests" / "cases" / "rules" / f"{code}.openplx").exists())]
    out = [("generated", openplx_text(160))]
    out += [(f.name, f.read_text(encoding="utf-8")) for f in files]
    return out


@pytest.mark.parametrize("name,text", _sources(), ids=[n for n, _ in _sources()])
def test_an_editing_session_reports_what_a_fresh_check_reports(tmp_path, name, text):
    (tmp_path / "other.openplx").write_text("Other is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2\n")
    re_used = sum(_session(tmp_path, text, seed, 12) for seed in range(campaign_size(9)))
    if not any(line.startswith("import ") for line in text.splitlines()):
        # the sessions did exercise re-use, not only fresh checks (a file with imports is checked
        # afresh on every edit, model/reuse.py: the comparison above is what it tests)
        assert re_used > 0


def test_statements_far_from_an_edit_are_not_checked_again(tmp_path):
    text = openplx_text(400)
    path = str(tmp_path / "far.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    host.state(path)
    new = text.replace("density: 1003", "densty: 1003", 1)
    host.update_document(path, new, 2)
    st = host.state(path)
    plan = st.analysis.plan
    n = len(st.tree.statements)
    # the material, the wheel using it, its truck and the scene that names every truck
    assert len(plan.dirty) == 4, sorted(plan.dirty)
    assert len(plan.reused) == n - 4
    assert [d.code for d in st.diagnostics] == ["N002"]


def test_a_missing_value_moves_with_its_statement(tmp_path):
    text = openplx_text(200).replace("        radius: 0.26\n", "", 1)
    path = str(tmp_path / "moved.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    before = [d for d in host.state(path).diagnostics if d.code == "M007"]
    assert before, "the generated scene misses one radius"
    for version, new in enumerate(["# a note\n# and another\n\n" + text, "# a note\n" + text], start=2):
        host.update_document(path, new, version)
        st = host.state(path)
        assert _findings(st) == _fresh_findings(tmp_path, path, new, version)
        after = [d for d in st.diagnostics if d.code == "M007"]
        shift = new.count("\n") - text.count("\n")
        assert [(d.message, d.span.start.line - shift) for d in after] == [(d.message, d.span.start.line) for d in before]
        assert st.analysis.plan.reused  # re-used, not checked again


def test_the_server_parses_ahead_without_losing_the_typed_line_view(tmp_path):
    text = openplx_text(120)
    path = str(tmp_path / "ahead.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    host.state(path)
    lines = text.split("\n")
    n = next(k for k, ln in enumerate(lines) if "inertia.mass" in ln)
    new = "\n".join(lines[:n + 1] + ["    inertia."] + lines[n + 1:])
    host.update_document(path, new, 2)
    assert host.parse_ahead(path) is True
    assert host.parse_ahead(path) is False  # parsed already: the analysis is what is left
    view = host.line_view(path, n + 1)
    assert view is not None and view.text == "    inertia."
    assert _findings(host.state(path)) == _fresh_findings(tmp_path, path, new, 2)


def test_a_suggestion_follows_the_names_defined_elsewhere(tmp_path):
    text = ("Chassis is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n\n"
            "Scene is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody:\n        inertia.mass: chassis\n")
    path = str(tmp_path / "suggest.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    assert any("'Chassis'" in (d.help or "") for d in host.state(path).diagnostics)
    new = text.replace("Chassis is", "ChassisX is", 1)  # the statement naming 'chassis' is unchanged
    host.update_document(path, new, 2)
    st = host.state(path)
    assert _findings(st) == _fresh_findings(tmp_path, path, new, 2)
    assert any("'ChassisX'" in (d.help or "") for d in st.diagnostics)


def test_the_rules_judge_again_only_what_read_the_edited_statement(tmp_path):
    """An edit of a material re-judges the material and the wheel that reads it; the truck and the
    scene name them (the model's plan checks them again) but read nothing that changed."""
    from plxtools.rules import incremental

    text = openplx_text(400)
    path = str(tmp_path / "rules.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    host.state(path)
    judged: list = []
    real = incremental._to_judge

    def spy(*args):
        got = real(*args)
        judged.append(got)
        return got

    incremental._to_judge = spy
    try:
        for version, new in enumerate([text.replace("density: 1003", "densty: 1003", 1), text,
                                       text.replace("density: 1003", "density: 1004", 1)], start=2):
            host.update_document(path, new, version)
            st = host.state(path)
            assert _findings(st) == _fresh_findings(tmp_path, path, new, version)
    finally:
        incremental._to_judge = real
    tree = st.tree
    scene = next(i for i, s in enumerate(tree.statements) if s.path.parts[0].name == "Scene")
    assert len(st.analysis.plan.dirty) >= 4 and scene in st.analysis.plan.dirty
    # the first edit's statements were judged with the whole file (no reads of their own yet);
    # from the second edit on, only the material and its wheel
    assert [len(j) for j in judged[1:]] == [2, 2] and all(scene not in j for j in judged[1:])
