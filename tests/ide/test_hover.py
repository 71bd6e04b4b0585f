"""Hover: declared type, default and its origin, docs; types, dotted paths, expressions, rule codes."""

from __future__ import annotations

from plxtools.ide import hover


def test_hover_on_inherited_attribute_in_dotted_path(example):
    h = hover(example.st, example.at("inertia.mass: 10", len("inertia.") + 1))
    assert h is not None
    assert "`Real`" in h.markdown
    assert "default `0.0`" in h.markdown
    assert "inherited from `Physics3D.Bodies.Inertia`" in h.markdown
    # the span is the name under the cursor only
    assert example.text[h.span.start.offset:h.span.end.offset] == "mass"


def test_hover_on_first_part_of_dotted_path(example):
    h = hover(example.st, example.at("inertia.mass: 10", 2))
    assert "`Physics3D.Bodies.Inertia`" in h.markdown
    assert "inherited from `Physics3D.Bodies.RigidBody`" in h.markdown


def test_hover_on_type_name_shows_model_and_doc(example):
    h = hover(example.st, example.at("Physics3D.Bodies.RigidBody", len("Physics3D.Bodies.") + 3))
    assert "Physics3D.Bodies.RigidBody is Physics3D.Bodies.Body" in h.markdown
    assert "Physics3D/Bodies/RigidBody.openplx:1" in h.markdown
    assert "is_dynamic" in h.markdown  # from the model's .doc
    assert example.text[h.span.start.offset:h.span.end.offset] == "RigidBody"


def test_hover_on_namespace_part_of_a_type(example):
    h = hover(example.st, example.at("Physics3D.Bodies.RigidBody", len("Physics3D.") + 2))
    assert "*namespace*" in h.markdown and "RigidBody" in h.markdown


def test_hover_on_attribute_uses_owner_doc_line(example):
    h = hover(example.st, example.at("is_dynamic: false", 3))
    assert "`Bool`" in h.markdown and "default `true`" in h.markdown
    assert "indicates wheather the rigid body is dynamic" in h.markdown


def test_hover_deep_dotted_path(example):
    text = example.text
    at = text.index("kinematics.local_transform.position.z") + len("kinematics.local_transform.position.")
    h = hover(example.st, at)
    assert "`Real`" in h.markdown
    assert text[h.span.start.offset:h.span.end.offset] == "z"


def test_hover_reference_in_expression_shows_where_value_comes_from(example):
    at = example.at("geometry.size.x * 0.31", len("geometry.size."))
    h = hover(example.st, at)
    assert "`Real`" in h.markdown
    line = example.text[:example.text.index("x: 3.3")].count("\n") + 1
    # the value in force comes first, before the declaration and its default
    assert h.markdown.split("\n\n")[0] == f"**`x: 3.3`** · set at line {line} in `Chassis`"


def test_hover_on_const_model_reference(example):
    h = hover(example.st, example.at("material: TireMaterial", len("material: ") + 2))
    assert "const TireMaterial is Physics.Geometries.Material" in h.markdown
    assert "*const model*" in h.markdown


def test_hover_on_becomes_mentions_specialised_attribute(example):
    h = hover(example.st, example.at("friction becomes", 2))
    assert "specialises `friction`" in h.markdown


def test_hover_on_nothing(example):
    assert hover(example.st, 0) is None  # a comment


def test_hover_on_suppression_code_shows_rule_page(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    is_dynamic: 3  # plx: ignore[T001]\n")
    h = hover(d.st, d.at("T001", 1))
    assert h is not None and h.markdown.startswith("# T001")


def test_hover_in_official_bundle_file(host):
    import openplxbundles
    from pathlib import Path

    path = str(Path(openplxbundles.package_dir(), "Physics3D", "Bodies", "RigidBody.openplx").resolve())
    st = host.state(path)
    text = st.text
    h = hover(st, text.index("is_dynamic is Bool") + 2)
    assert "`Bool`" in h.markdown and "declared" in h.markdown


def test_hover_on_primitive_and_global(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    r is Real: Math.PI / 2\n")
    assert "*primitive type*" in hover(d.st, d.at("Real", 1)).markdown
    assert "PI is Real" in hover(d.st, d.at("PI", 1)).markdown
