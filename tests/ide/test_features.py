"""Signature help, outline, workspace symbols, folding, links, semantic tokens, inlay hints, code actions,
formatting, and the host itself (untitled buffers, settings)."""

from __future__ import annotations

from plxtools.ide import (
    AnalysisHost,
    Settings,
    code_actions,
    document_links,
    document_symbols,
    fix_all,
    folding_ranges,
    format_document,
    inlay_hints,
    semantic_tokens,
    signature_help,
    workspace_symbols,
)
from plxtools.ide.formatting import FormattingRefused


def test_signature_help_marks_the_current_parameter(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    v is Math.Vec3: Math.Vec3.from_xyz(1, \n")
    res = signature_help(d.st, d.end_of("from_xyz(1, "))
    assert res.signatures[0].label == "static fn from_xyz(x: Real, y: Real, z: Real) -> Vec3"
    assert [p.label for p in res.signatures[0].parameters] == ["x: Real", "y: Real", "z: Real"]
    assert res.active_parameter == 1
    assert signature_help(d.st, d.at("is Math")) is None


def test_signature_help_on_instance_method(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    v is Math.Vec3\n    l is Real: v.cross(\n")
    res = signature_help(d.st, d.end_of("v.cross("))
    assert res.signatures[0].label == "fn cross(rhs: Vec3) -> Vec3" and res.active_parameter == 0


def test_document_symbols_are_hierarchical(example):
    syms = document_symbols(example.st.tree)
    names = [s.name for s in syms]
    assert names[:2] == ["TireMaterial", "PlateMaterial"] and "BoxTruck" in names
    truck = next(s for s in syms if s.name == "BoxTruck")
    assert truck.kind == "model" and truck.detail == "Physics3D.System"
    assert "front_left_hinge" in [c.name for c in truck.children]
    assert next(s for s in syms if s.name == "TireMaterial").kind == "const"


def test_workspace_symbols(example, host):
    got = workspace_symbols(host, "RigidBody")
    assert got[0].name == "RigidBody" and got[0].container == "Physics3D.Bodies"
    local = workspace_symbols(host, "BoxTruck")
    assert local[0].path == example.path


def test_folding_ranges(example):
    folds = folding_ranges(example.st.tree)
    assert any(f.kind == "comment" and f.start_line == 0 for f in folds)
    truck_line = example.text[: example.at("BoxTruck is")].count("\n")
    assert any(f.start_line == truck_line and f.end_line > truck_line + 10 for f in folds)


def test_document_links(scratch, tmp_path):
    (tmp_path / "mesh.obj").write_text("")
    d = scratch('A is Physics3D.Bodies.RigidBody:\n    .doc: "x"\n    p is String: @"mesh.obj"\n')
    links = document_links(d.st.tree, d.path)
    assert len(links) == 1 and links[0].target == str(tmp_path / "mesh.obj")
    assert d.text[links[0].span.start.offset:links[0].span.end.offset] == "mesh.obj"


def test_semantic_tokens_classify_names(example):
    toks = semantic_tokens(example.st)
    lines = example.text.split("\n")

    def tok_text(t):
        return lines[t.line][t.column:t.column + t.length]

    by_text = {}
    for t in toks:
        by_text.setdefault(tok_text(t), set()).add(t.type)
    assert "class" in by_text["RigidBody"] and "namespace" in by_text["Physics3D"]
    assert "property" in by_text["is_dynamic"] and "keyword" in by_text["is"]
    assert "number" in by_text["1000"] and "comment" in by_text["# A static plate to drive on."]
    # sorted, no overlaps
    for a, b in zip(toks, toks[1:]):
        assert (a.line, a.column + a.length) <= (b.line, b.column) or a.line < b.line


def test_inlay_hints(example):
    hints = inlay_hints(example.st, 0, len(example.text))
    labels = {(h.label, example.text[h.offset - 12:h.offset]) for h in hints}
    assert (": Real", "inertia.mass") in labels
    # the fields of a {...} literal
    at = example.at("main_axis: {0, -1, 0}", len("main_axis: {"))
    assert any(h.offset == at and h.label == "x:" for h in hints)


def test_code_actions_quick_fix_and_suppress(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    is_dynamc: false\n")
    st = d.st
    [diag] = [x for x in st.diagnostics if x.code == "N002"]
    acts = code_actions(st, diag.span.start.offset, diag.span.start.offset)
    titles = [a.title for a in acts]
    assert "Fix N002: replace with 'is_dynamic' (unsafe)" in titles
    sup = next(a for a in acts if a.title.startswith("Suppress N002"))
    [edit] = sup.edits[d.path]
    new = d.text[:edit.start] + edit.text + d.text[edit.end:]
    assert "is_dynamc: false  # plx: ignore[N002]\n" in new
    d.host.update_document(d.path, new, 2)
    assert not [x for x in d.host.state(d.path).diagnostics if x.code == "N002"]


def test_suppress_adds_code_to_existing_comment(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    is_dynamc: 3  # plx: ignore[T001]\n")
    st = d.st
    diag = next(x for x in st.diagnostics if x.code == "N002")
    sup = next(a for a in code_actions(st, diag.span.start.offset, diag.span.start.offset)
               if a.title.startswith("Suppress"))
    [edit] = sup.edits[d.path]
    assert d.text[:edit.start] + edit.text + d.text[edit.end:] == (
        "A is Physics3D.Bodies.RigidBody:\n    is_dynamc: 3  # plx: ignore[T001, N002]\n")


def test_fix_all_applies_safe_fixes(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    is_dynamic: false  # plx: ignore[T001]\n")
    action = fix_all(d.st)
    assert action is not None and action.kind == "source.fixAll"
    [edit] = action.edits[d.path]
    assert d.text[:edit.start] + edit.text + d.text[edit.end:] == (
        "A is Physics3D.Bodies.RigidBody:\n    is_dynamic: false\n")


def test_formatting_gives_small_edits(scratch):
    try:
        edits = format_document("A is Physics3D.Bodies.RigidBody:\n  is_dynamic:   false\n", "")
    except FormattingRefused as exc:  # pragma: no cover - while the formatter is being built
        raise AssertionError(str(exc)) from None
    assert len(edits) == 1 and edits[0].text == "    is_dynamic: false\n"


def test_formatting_refuses_syntax_errors():
    import pytest

    with pytest.raises(FormattingRefused, match="syntax errors"):
        format_document("A is :\n", "")


def test_untitled_buffer_and_settings():
    h = AnalysisHost(Settings(ignore=["C001"]))
    h.open_document("untitled:Untitled-1", "a_model is Physics3D.System:\n    is_dynamc: true\n", 1)
    st = h.state("untitled:Untitled-1")
    codes = [d.code for d in st.diagnostics]
    assert codes == ["N002"]  # C001 (naming) is ignored by the settings
    h.configure(Settings(select=["C"]))
    assert [d.code for d in h.state("untitled:Untitled-1").diagnostics] == ["C001"]


def test_bundle_path_setting(tmp_path):
    from tests.ide.conftest import write_bundle

    write_bundle(tmp_path / "bundles", "Shop", {"Tools/Hammer.openplx": "Hammer is Physics3D.Bodies.RigidBody\n"})
    scene = "Scene is Physics3D.System:\n    h is Shop.Tools.Hammer\n"
    path = str(tmp_path / "scene" / "scene.openplx")
    without = AnalysisHost()
    without.open_document(path, scene, 1)
    assert [d.code for d in without.state(path).diagnostics] == ["N001"]
    h = AnalysisHost(Settings(bundle_paths=[str(tmp_path / "bundles")]))
    h.open_document(path, scene, 1)
    assert [d.code for d in h.state(path).diagnostics] == []
