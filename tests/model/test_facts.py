"""The model's facts (plxtools/model/facts.py): what the checker finds, without codes or words, and
how they live on: pickled and compared by value, moved with their statement by the server's re-use."""

from __future__ import annotations

import pickle

from plxtools.diagnostics import Pos, Span
from plxtools.model import facts
from plxtools.model.workspace import Workspace
from plxtools.syntax import parse_text


def span(a: int, b: int, line: int = 0) -> Span:
    return Span(Pos(a, line, a), Pos(b, line, b))


def test_a_fact_pickles_and_compares_by_value():
    f = facts.NotAValue(span(3, 9), facts.Named("model", "Scene.Wheel", "Wheel"), True, span(0, 2))
    assert pickle.loads(pickle.dumps(f)) == f
    assert f != facts.NotAValue(span(3, 9), facts.Named("model", "Scene.Wheel", "Wheel"), False, span(0, 2))


def test_moving_a_fact_moves_every_place_in_it_or_gives_it_up():
    f = facts.NotAValue(span(30, 35, 3), facts.Named("model", "W", "W"), False, span(0, 5))
    shifted = f.moved(lambda s: Span(Pos(s.start.offset + 10, s.start.line + 1, s.start.column),
                                     Pos(s.end.offset + 10, s.end.line + 1, s.end.column)))
    assert (shifted.span.start.offset, shifted.declared_at.start.offset) == (40, 10)
    assert shifted.what == f.what
    # the declaration's place is in text that changed: the fact must be found again
    assert f.moved(lambda s: None if s.start.offset == 0 else s) is None
    assert f.moved(lambda s: s) is f  # nothing moved: the same fact, shared


def test_the_model_records_facts_and_no_diagnostic_for_them():
    text = ("Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n"
            "A is Physics3D.Bodies.RigidBody:\n    n is Int: 2.5\n    w is Wheel: Wheel\n    m is Real: n.x\n")
    fa = Workspace().analyse(parse_text(text, "/tmp/plx-facts-tests/a.openplx"))
    kinds = [type(f) for f in fa.facts]
    assert kinds == [facts.RealForInt, facts.NotAValue, facts.NoMemberOnValue]
    assert not fa.diagnostics  # the model writes no code: the rule modules report the facts
    not_a_value = fa.facts[1]
    assert not_a_value.what == facts.Named("model", "Wheel", "Wheel") and not not_a_value.argument
    assert not_a_value.declared_at.start.offset == 0  # where `const` would go
