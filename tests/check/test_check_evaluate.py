"""Instantiation and evaluation: paths, which assignment wins, late defaults, references, errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from check_helpers import CASES, EXAMPLE


@pytest.fixture
def evaluate(ws):
    """evaluate(fc, "a.b.c") -> value, using a new evaluator over the same object tree."""
    from plxtools.check.evaluate import Evaluator
    from plxtools.check.instance import Builder

    trees: dict = {}

    def run(fc, path: str, errors: list | None = None):
        if id(fc) not in trees:  # one object tree per checked file, so identities can be compared
            b = Builder(ws.program)
            root = b.root(fc.assembly.root.model)
            sink: list = []
            trees[id(fc)] = (fc, root, Evaluator(ws.program, b, fc.rep.unit, lambda *a: sink.append(a)), sink)
        _fc, root, ev, sink = trees[id(fc)]
        del sink[:]
        try:
            return ev.get(root, path)
        finally:
            if errors is not None:
                errors.extend(sink)

    return run


def test_boxtruck_objects_have_dotted_paths_and_values(check_file, evaluate):
    fc = check_file(EXAMPLE)
    paths = [o.path for o in fc.assembly.owned]
    for p in ("box_truck", "box_truck.chassis", "box_truck.front_left_wheel.connector", "box_truck.front_left_hinge",
              "box_truck.own_parts", "ground.geometry", "tire_contact.friction"):
        assert p in paths
    assert evaluate(fc, "box_truck.chassis.hub_offset") == pytest.approx([3.3 * 0.31, 1.7 * 0.44, 1.44 * 0.48])
    assert evaluate(fc, "box_truck.chassis.front_right_hub.position") == pytest.approx(
        [-3.3 * 0.31, 1.7 * 0.44, -1.44 * 0.48])
    assert evaluate(fc, "box_truck.front_left_wheel.inertia.mass") == 10.0
    assert evaluate(fc, "box_truck.front_left_motor.max_effort") == math.inf  # Math.INF, a global
    assert evaluate(fc, "tire_contact.friction.coefficient") == 1.0  # the `becomes` block
    assert evaluate(fc, "tire_contact.friction.normal_force") == 1000.0
    t = evaluate(fc, "box_truck.chassis.kinematics.local_transform")
    assert t.position == pytest.approx([0, 0, 1.1]) and t.rotation == pytest.approx([0, 0, 0, 1])


def test_references_are_shared_objects_not_copies(check_file, evaluate):
    fc = check_file(EXAMPLE)
    hinge = evaluate(fc, "box_truck.front_left_hinge.connectors")
    motor = evaluate(fc, "box_truck.front_left_motor.connectors")  # connectors: front_left_hinge.connectors
    assert [c.path for c in hinge] == ["box_truck.chassis.front_left_hub", "box_truck.front_left_wheel.connector"]
    assert all(a is b for a, b in zip(hinge, motor))
    m1 = evaluate(fc, "tire_contact.material_1")
    assert m1.singleton and m1.path == "TireMaterial"  # a const model is one instance
    assert evaluate(fc, "box_truck.front_left_wheel.geometry.material") is m1
    g = evaluate(fc, "box_truck.no_self_collision.group1")
    assert g is evaluate(fc, "box_truck.no_self_collision.group2") and g.path == "box_truck.own_parts"
    src = evaluate(fc, "box_truck.front_left_hinge.angle_output.source")  # `source: this` in the bundle
    assert src.path == "box_truck.front_left_hinge"


def test_late_default_normal_follows_an_overridden_main_axis(check_file, evaluate):
    fc = check_file(CASES / "late_default.openplx")
    # normal = main_axis.get_orthogonal_unit_vector(), evaluated on the final object: X -> Y
    assert evaluate(fc, "arm.top.main_axis") == pytest.approx([1, 0, 0])
    assert evaluate(fc, "arm.top.normal") == pytest.approx([0, 1, 0])
    assert evaluate(fc, "pivot.normal") == pytest.approx([0, 0, 1])  # given explicitly
    assert evaluate(fc, "arm.top.position") == pytest.approx([0, 0, 0.5])  # position.z in the model body


def test_which_assignment_wins(check_file, evaluate):
    fc = check_file(CASES / "precedence.openplx")
    assert evaluate(fc, "a.inertia.mass") == 10  # base body
    assert evaluate(fc, "b.inertia.mass") == 20  # model body over its trait
    assert evaluate(fc, "c.inertia.mass") == 40  # instance block over everything
    assert evaluate(fc, "d.inertia.mass") == 30  # trait over the base
    assert evaluate(fc, "a.label") == 1 and evaluate(fc, "b.label") == 3 and evaluate(fc, "d.label") == 3
    assert evaluate(fc, "e.geometry.radius") == 0.25 and evaluate(fc, "a.geometry.radius") == 0.5
    # value types: a whole value and a field assignment compete by order
    assert evaluate(fc, "e.kinematics.local_transform.position") == pytest.approx([1, 2, 5])
    assert evaluate(fc, "f.kinematics.local_transform.position") == pytest.approx([1, 2, 3])


def test_value_cycle_is_a_located_diagnostic_not_a_recursion_error(check_file, evaluate):
    fc = check_file(CASES / "cycle.openplx")
    # lint's M006 already names the ring on that line; our A006 on the same line is merged away
    assert [(d.code, d.span.start.line + 1) for d in fc.diagnostics] == [("M006", 2)]
    errors: list = []
    with pytest.raises(Exception) as exc:
        evaluate(fc, "block.geometry.size", errors)
    assert type(exc.value).__name__ == "Unavailable"
    assert errors[0][0] == "A006" and "block.a -> block.b -> block.a" in errors[0][1]


def test_evaluation_errors_are_located(check_text):
    fc = check_text("""
Box is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    geometry is Physics3D.Geometries.Box:
        size: {1, 1, 1}
    c is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.Z_AXIS() / 0
        normal: Math.Vec3.X_AXIS()

Scene is Physics3D.System:
    box is Box
    other is Box:
        kinematics.local_transform.position.x: 3
    lock is Physics3D.Interactions.Lock:
        connectors: [box.c, other.c]
""")
    found = [(d.code, d.span.start.line + 1) for d in fc.diagnostics if d.code.startswith("A")]
    assert ("A003", 6) in found  # the division by zero, on the line that divides
    msg = next(d.message for d in fc.diagnostics if d.code == "A003")
    assert msg.startswith("box.c.main_axis") and "division by zero" in msg


def test_deep_chains_of_values_do_not_overflow(check_text):
    n = 400
    lines = [f"    v{i} is Real: v{i + 1} + 1" for i in range(n)] + [f"    v{n} is Real: 0"]
    text = "Ball is Physics3D.Bodies.RigidBody:\n" + "\n".join(lines) + """
    geometry is Physics3D.Geometries.Sphere:
        radius: v0 / 1000

Scene is Physics3D.System:
    ball is Ball
"""
    fc = check_text(text)
    assert not [d for d in fc.diagnostics if d.severity.value == "error"], [d.to_json() for d in fc.diagnostics]
    (ball,) = fc.scene.bodies
    assert ball.geoms[0].radius == pytest.approx(0.4)


def test_too_deep_chains_end_in_a_diagnostic(check_text):
    n = 2500
    lines = [f"    v{i} is Real: v{i + 1} + 1" for i in range(n)] + [f"    v{n} is Real: 0"]
    text = "Ball is Physics3D.Bodies.RigidBody:\n" + "\n".join(lines) + """
    geometry is Physics3D.Geometries.Sphere:
        radius: v0 / 1000

Scene is Physics3D.System:
    ball is Ball
"""
    fc = check_text(text)
    deep = [d for d in fc.diagnostics if d.code == "A006"]
    assert deep and "nest too deeply" in deep[0].message


def test_globals_const_models_and_math(check_text, evaluate):
    fc = check_text("""
half_pi is Real: Math.PI / 2

const Settings:
    scale is Real: 2

Thing is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {Settings.scale, Math.Functions.sqrt(4), Math.Functions.cos(half_pi) + 1}
    tilted is Physics3D.Interactions.MateConnector:
        main_axis: Math.Quat.angle_axis(half_pi, Math.Vec3.Y_AXIS()).rotate(Math.Vec3.Z_AXIS())
    turned is Math.AffineTransform: Math.AffineTransform.from_axes({0, 0, 1}, {0, 1, 0}, {1, 2, 3})

Scene is Physics3D.System:
    thing is Thing
""")
    assert evaluate(fc, "thing.geometry.size") == pytest.approx([2, 2, 1])
    assert evaluate(fc, "thing.tilted.main_axis") == pytest.approx([1, 0, 0], abs=1e-12)
    t = evaluate(fc, "thing.turned")
    assert t.position == pytest.approx([1, 2, 3])
    assert np.linalg.norm(t.rotation) == pytest.approx(1.0)


def test_instance_block_attributes_and_dotted_declarations(check_text, evaluate):
    fc = check_text("""
Plate is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {1, 1, 0.1}

Scene is Physics3D.System:
    plate is Plate:
        width is Real: 2.5
        geometry.size.x: plate.width
        geometry.size.y: width
    plate.extra is Physics3D.Interactions.MateConnector:
        position.z: 0.05
""")
    # expressions in an instance block are scoped to the outermost model (spec C.6): `plate.width`
    # reaches the new attribute, a bare `width` is an unknown name of Scene
    assert evaluate(fc, "plate.geometry.size.x") == 2.5
    assert evaluate(fc, "plate.extra.position") == pytest.approx([0, 0, 0.05])
    assert ("N003", 9) in [(d.code, d.span.start.line + 1) for d in fc.diagnostics]
    errors: list = []
    with pytest.raises(Exception):
        evaluate(fc, "plate.geometry.size.y", errors)
    assert errors[0][0] == "A003" and "unknown name 'width'" in errors[0][1]


def test_becomes_in_a_trait_specialises_the_hosts_attribute(check_text):
    fc = check_text("""
trait Rubber:
    geometry becomes Physics3D.Geometries.Cylinder:
        radius: 0.3
        height: 0.1

Wheel is Physics3D.Bodies.RigidBody:
    with Rubber
    geometry is Physics3D.Geometries.ContactGeometry

Scene is Physics3D.System:
    wheel is Wheel
""")
    (body,) = fc.scene.bodies
    assert [(g.kind, g.radius, g.height) for g in body.geoms] == [("cylinder", 0.3, 0.1)]
