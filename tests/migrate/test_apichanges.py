"""Change lists between versions, checked against the index itself (not only against output strings)."""

import re

import pytest

from plxtools.model import apichanges
from plxtools.model.apichanges import AUTO, TABLE, Change, changes, diff, rename_table, step
from plxtools.model.apiindex import ApiIndex, load, versions, where_defined


def test_every_charges_model_is_moved_renamed_or_removed_at_0_18_11():
    old, new = load("0.18.10"), load("0.18.11")
    charges = [q for q in old.models if ".Charges." in q]
    assert len(charges) > 15
    cs = {c.model: c for c in step("0.18.10", "0.18.11") if c.kind.startswith("model-")}
    for q in charges:
        assert q not in new.models
        c = cs[q]
        assert c.kind in ("model-moved", "model-renamed", "model-removed")
        if c.kind != "model-removed":
            assert c.new in new.models and ".Charges." not in c.new
            if c.kind == "model-moved":
                assert c.new.rsplit(".", 1)[1] == q.rsplit(".", 1)[1] and c.handling == AUTO
        # no other step touches it: it lived in every version up to 0.18.10
        assert where_defined(q)[-1] == "0.18.10"
    assert cs["Physics3D.Charges.Box"].new == "Physics3D.Geometries.Box"


def test_charges_becomes_connectors_through_inheritance():
    cs = [c for c in step("0.18.10", "0.18.11") if c.kind == "attr-renamed"]
    base = next(c for c in cs if c.model == "Physics.Interactions.Interaction")
    assert (base.old, base.new, base.handling) == ("charges", "connectors", TABLE)
    follower = next(c for c in cs if c.model == "Physics3D.Interactions.Mate")
    assert follower.detail == "follows Physics.Interactions.Interaction.charges"
    # the new name really is an attribute of every interaction that had the old one
    old, new = load("0.18.10"), load("0.18.11")
    for q in old.models:
        if "charges" in old.all_attrs(q) and q in new.models:
            assert "connectors" in new.all_attrs(q), q


def test_composed_0_17_26_to_0_19_0():
    cs = changes("0.17.26", "0.19.0")
    box = next(c for c in cs if c.model == "Physics3D.Charges.Box")
    assert (box.kind, box.new, box.since) == ("model-moved", "Physics3D.Geometries.Box", "0.18.11")
    assert box.where == ["0.17.26 Physics3D/Charges/Box.openplx:1", "0.19.0 Physics3D/Geometries/Box.openplx:1"] or \
        box.where[1].startswith("0.18.11 Physics3D/Geometries/Box.openplx")
    # each endpoint of every rename or move exists in the version it names
    for c in cs:
        if c.kind in ("model-moved", "model-renamed"):
            assert c.old in load("0.17.26").models and c.new in load("0.19.0").models, c
    # something added after 0.17.26 and moved later is just "added" under its last name
    added = {c.model for c in cs if c.kind == "model-added"}
    assert "Vehicles.Suspensions.Suspension" in added
    assert not any(c.kind == "model-moved" and c.old.startswith("Vehicles.Wheels.Interactions") for c in cs)


def test_identical_versions_have_no_changes():
    assert load("0.18.11").models == load("0.19.0").models
    assert step("0.18.11", "0.19.0") == ()
    assert changes("0.19.0", "0.19.0") == []
    with pytest.raises(ValueError, match="forward only"):
        changes("0.19.0", "0.18.10")


def test_every_reviewed_rename_is_cited_correctly_and_used():
    allv = versions()
    for e in rename_table():
        prev = allv[allv.index(e.version) - 1]
        before, after = load(prev), load(e.version)
        for cite, idx in zip(e.evidence, (before, after)):
            m = re.fullmatch(r"(\S+) (\S+):(\d+)", cite)
            assert m and m.group(1) == idx.version, cite
            if e.kind == "model":
                rec = idx.models[e.old if idx is before else e.new]
                assert (rec["f"], rec["l"]) == (m.group(2), int(m.group(3))), cite
            else:
                name = e.old if idx is before else e.new
                rec = idx.models[e.model if idx is after else _old_name(e.model, prev, e.version)]
                assert rec["a"][name][2] == int(m.group(3)) and rec["f"] == m.group(2), cite
        if e.kind == "model":
            assert e.old in before.models and e.old not in after.models
        used = [c for c in step(prev, e.version) if c.handling == TABLE and c.new == e.new]
        assert used, f"table entry {e.old} -> {e.new} is never applied"


def _old_name(model: str, prev: str, v: str) -> str:
    for c in step(prev, v):
        if c.kind in ("model-moved", "model-renamed") and c.new == model:
            return c.old
    return model


def _index(version: str, models: dict) -> ApiIndex:
    return ApiIndex({"version": version, "models": models})


def test_rename_inferred_only_with_same_type_flags_and_doc():
    old = _index("9.0.0", {"A.M": {"k": "m", "f": "A/M.openplx", "l": 1,
                                   "a": {"speed": ["Real", "d", 2, "h1"]}}})
    new = _index("9.0.1", {"A.M": {"k": "m", "f": "A/M.openplx", "l": 1,
                                   "a": {"velocity": ["Real", "d", 2, "h1"]}}})
    cs = diff(old, new)
    assert [(c.kind, c.old, c.new, c.handling) for c in cs] == [("attr-renamed", "speed", "velocity", AUTO)]
    other_doc = _index("9.0.1", {"A.M": {"k": "m", "f": "A/M.openplx", "l": 1,
                                         "a": {"velocity": ["Real", "d", 2, "h2"]}}})
    kinds = sorted(c.kind for c in diff(old, other_doc))
    assert kinds == ["attr-added", "attr-removed"]
    no_doc_old = _index("9.0.0", {"A.M": {"k": "m", "f": "A/M.openplx", "l": 1, "a": {"speed": ["Real", "", 2, None]}}})
    no_doc_new = _index("9.0.1", {"A.M": {"k": "m", "f": "A/M.openplx", "l": 1, "a": {"velocity": ["Real", "", 2, None]}}})
    assert sorted(c.kind for c in diff(no_doc_old, no_doc_new)) == ["attr-added-required", "attr-removed"]


def test_rename_named_by_a_deprecation_note():
    old = _index("9.0.0", {"A.M": {"k": "m", "f": "f", "l": 1, "dep": {"speed": "deprecated, use velocity"},
                                   "a": {"speed": ["Real", "d", 2, None]}}})
    new = _index("9.0.1", {"A.M": {"k": "m", "f": "f", "l": 1,
                                   "a": {"velocity": ["Int", "d", 2, None], "other": ["Real", "d", 3, None]}}})
    renamed = [c for c in diff(old, new) if c.kind == "attr-renamed"]
    assert [(c.old, c.new) for c in renamed] == [("speed", "velocity")]
    assert renamed[0].detail.startswith("deprecation note")


def test_composition_chains_moves_and_drops_add_then_remove(monkeypatch):
    def fake_steps(a, b):
        return [("1", "2", (Change("model-moved", "2", "A.X", AUTO, old="A.X", new="B.X", where=["1 a:1", "2 b:1"]),
                            Change("model-added", "2", "T.Tmp", "info"),
                            Change("attr-renamed", "2", "A.X", AUTO, attr="p", old="p", new="q", where=["1 a:2", "2 b:2"]))),
                ("2", "3", (Change("model-renamed", "3", "B.X", TABLE, old="B.X", new="C.Y", where=["2 b:1", "3 c:1"]),
                            Change("model-removed", "3", "T.Tmp", "person"),
                            Change("attr-renamed", "3", "B.X", AUTO, attr="q", old="q", new="r", where=["2 b:2", "3 c:2"])))]
    monkeypatch.setattr(apichanges, "steps", fake_steps)
    cs = changes("1", "3")
    assert [(c.kind, c.old, c.new, c.handling) for c in cs] == [
        ("model-renamed", "A.X", "C.Y", TABLE), ("attr-renamed", "p", "r", AUTO)]
    assert cs[0].where == ["1 a:1", "3 c:1"] and cs[1].model == "A.X"
