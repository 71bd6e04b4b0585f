"""Completion on whole and half-typed lines: types after is/becomes/with, attributes, values, members."""

from __future__ import annotations

from plxtools.ide import complete, completion_documentation

WHEEL_LINE = "    inertia.mass: 10\n"


def labels(result) -> list[str]:
    return [i.label for i in sorted(result.items, key=lambda i: (i.sort_text or "", i.label))]


def edit(example, old: str, new: str, marker: str):
    """Replace text in the example buffer; return the offset right after `marker` in the new text."""
    text = example.text.replace(old, new, 1)
    example.host.update_document(example.path, text, 2)
    return text.index(marker) + len(marker)


def test_after_is_qualified_namespace_lists_geometries(example):
    marker = "geometry2 is Physics3D.Geometries."
    at = edit(example, WHEEL_LINE, WHEEL_LINE + f"    {marker}\n", marker)
    res = complete(example.st, at)
    got = labels(res)
    assert {"Box", "Cylinder", "Sphere", "Capsule"} <= set(got)
    assert res.replace_start == res.replace_end == at


def test_half_typed_name_after_qualifier(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    geometry2 is Physics3D.Geometries.Cyl\n", "Geometries.Cyl")
    res = complete(example.st, at)
    assert "Cylinder" in labels(res)
    assert res.replace_start == at - 3  # the typed part is replaced


def test_after_is_without_qualifier(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    extra is \n", "extra is ")
    got = labels(complete(example.st, at))
    assert {"Real", "Bool", "Wheel", "TireMaterial", "Physics3D", "Math"} <= set(got)


def test_after_with_lists_only_namespaces_holding_traits(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    with Physics3D.Signals.\n", "with Physics3D.Signals.")
    items = complete(example.st, at).items
    assert items and all(i.kind in ("trait", "namespace") for i in items)
    assert any(i.label == "Position3DOutputTrait" for i in items)


def test_after_becomes_lists_subtypes(scratch):
    d = scratch("B is Physics3D.Bodies.Body:\n    inertia becomes \n")
    items = complete(d.st, d.end_of("inertia becomes ")).items
    models = [i.label for i in items if i.kind == "model"]
    assert "Physics3D.Bodies.Inertia" in models
    assert "Physics.Bodies.Inertia" not in models  # the declared type itself is no specialisation
    assert all(d.st.program.is_subtype(i.key[1], d.st.program.lookup(["Physics", "Bodies", "Inertia"], d.st.unit))
               for i in items if i.kind == "model")


def test_empty_line_in_wheel_lists_unset_attributes(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    \n", WHEEL_LINE + "    ")
    res = complete(example.st, at)
    got = labels(res)
    assert "is_dynamic" in got and "kinematics" in got
    assert "geometry" not in got and "connector" not in got  # already declared in Wheel
    item = next(i for i in res.items if i.label == "is_dynamic")
    assert item.detail == "Bool = true" and item.insert_text == "is_dynamic: "
    doc = completion_documentation(example.st.program, item.key)
    assert "is_dynamic is Bool: true" in doc


def test_half_typed_attribute_name(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    is_dyn\n", "    is_dyn")
    res = complete(example.st, at)
    assert "is_dynamic" in labels(res)
    assert res.replace_start == at - len("is_dyn")


def test_dotted_path_at_statement_start(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    inertia.\n", WHEEL_LINE + "    inertia.")
    assert set(labels(complete(example.st, at))) == {"mass", "tensor"}


def test_nested_block_attributes(example):
    at = edit(example, "        radius: 0.26\n", "        radius: 0.26\n        \n", "        radius: 0.26\n        ")
    got = labels(complete(example.st, at))
    assert "height" not in got and "radius" not in got  # set in this block
    assert "material" not in got and "local_transform" in got


def test_value_bool_first(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    is_dynamic: \n", "    is_dynamic: ")
    got = labels(complete(example.st, at))
    assert got[:2] == ["false", "true"] or set(got[:3]) >= {"false", "true"}


def test_value_const_models_that_fit(example):
    at = edit(example, "        material: TireMaterial", "        material: ", "        material: ")
    res = complete(example.st, at)
    best = [i.label for i in res.items if (i.sort_text or "").startswith("0")]
    assert "TireMaterial" in best and "PlateMaterial" in best


def test_members_after_dot_in_expression(example):
    at = edit(example, "x: geometry.size.x * 0.31", "x: geometry.size.", "x: geometry.size.")
    got = labels(complete(example.st, at))
    assert got[:3] == ["x", "y", "z"] and "length" in got and "X_AXIS" not in got


def test_static_functions_after_type_name(example):
    at = edit(example, "x: geometry.size.x * 0.31", "x: Math.Vec3.", "x: Math.Vec3.")
    got = labels(complete(example.st, at))
    assert "from_xyz" in got and "X_AXIS" in got and "length" not in got


def test_namespace_members_in_expression(example):
    at = edit(example, "x: geometry.size.x * 0.31", "x: Math.", "x: Math.")
    got = set(labels(complete(example.st, at)))
    assert {"PI", "Functions", "Vec3"} <= got


def test_const_model_functions(example):
    at = edit(example, "x: geometry.size.x * 0.31", "x: Math.Functions.", "x: Math.Functions.")
    got = set(labels(complete(example.st, at)))
    assert {"sin", "cos", "sqrt"} <= got


def test_inside_brace_literal_expected_field(scratch):
    d = scratch("A is Physics3D.Bodies.RigidBody:\n    is_dynamic: \n    f is Math.Vec3: {1, \n")
    res = complete(d.st, d.end_of("{1, "))
    assert res.items  # names of the outer model and globals


def test_no_completion_in_comments_and_strings(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    # inertia.\n", "# inertia.")
    assert complete(example.st, at).items == []
    at = edit(example, 'unique_name: "plxtools_example_tire"', 'unique_name: "plx.', 'unique_name: "plx.')
    assert complete(example.st, at).items == []


def test_top_level_keywords(scratch):
    d = scratch("\n")
    got = labels(complete(d.st, 0))
    assert "trait" in got and "const" in got


def test_broken_header_still_gives_a_context(scratch):
    # the header does not parse (a stray '='), but the block below still knows its type
    d = scratch("A is Physics3D.Bodies.RigidBody: =\n    is_dyn\n")
    assert "is_dynamic" in labels(complete(d.st, d.end_of("is_dyn")))


def test_space_triggers_only_where_a_type_or_value_starts(example):
    at = edit(example, WHEEL_LINE, WHEEL_LINE + "    extra is \n", "extra is ")
    assert complete(example.st, at, trigger=" ").items
    at = edit(example, "    inertia.mass: 10\n", "    inertia.mass: 10 \n", "    inertia.mass: 10 ")
    assert complete(example.st, at, trigger=" ").items == []


def test_connectors_of_a_joint_list_the_connectors_first(scratch):
    """Issue 40.4: in `connectors: [`, the connectors on the bodies come first (they are one level
    down: `chassis.hub`), not the bodies, signals or vectors of the model."""
    d = scratch("Body is Physics3D.Bodies.RigidBody:\n"
                "    hub is Physics3D.Interactions.MateConnector\n"
                "    offset is Math.Vec3: {0, 0, 1}\n"
                "Joint is Physics3D.System:\n"
                "    a is Body\n"
                "    b is Body\n"
                "    h is Physics3D.Interactions.Hinge:\n"
                "        connectors: [\n")
    got = labels(complete(d.st, d.end_of("connectors: [")))
    assert got[:2] == ["a.hub", "b.hub"], got[:6]
    assert "a.offset" not in got
