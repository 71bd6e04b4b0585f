"""Every attribute the bundles declare on the objects the MuJoCo backend maps is classified
(plxtools/check/coverage.py), and a setting the backend cannot simulate is named (A040) on the line
that sets it, never dropped silently."""

from __future__ import annotations

from check_helpers import line_of

HEAD = """
Frame is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    bearing is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}

Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 1.0
    geometry is Physics3D.Geometries.Sphere:
        radius: 0.1
    hub is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}
"""


def test_every_bundle_attribute_of_a_mapped_type_is_classified(ws):
    from plxtools.check import coverage

    assert coverage.unclassified(ws.program) == []


def test_settings_the_backend_cannot_simulate_are_named_where_they_are_set(check_text, tmp_path):
    text = HEAD + """
Rig is Physics3D.System:
    frame is Frame
    wheel is Wheel
    axle is Physics3D.Interactions.Hinge:
        connectors: [frame.bearing, wheel.hub]
        flexibility becomes Physics3D.Interactions.Flexibility.LinearElasticHingeFlexibility
        friction becomes Physics.Interactions.Dissipation.DryConeFriction
    motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: axle.connectors
        zero_speed_as_spring: true
"""
    fc = check_text(text)
    path = tmp_path / "scene.openplx"
    got = {(d.code, d.span.start.line + 1, d.severity.value) for d in fc.diagnostics if d.code == "A040"}
    assert ("A040", line_of(path, "flexibility becomes"), "warning") in got
    assert ("A040", line_of(path, "friction becomes"), "warning") in got
    assert ("A040", line_of(path, "zero_speed_as_spring"), "warning") in got
    msgs = " ".join(d.message for d in fc.diagnostics if d.code == "A040")
    assert "simulated rigid" in msgs and "stiff damper" in msgs


def test_runtime_defaults_and_mapped_friction_are_not_reported(check_text):
    text = HEAD + """
Rig is Physics3D.System:
    frame is Frame
    wheel is Wheel
    axle is Physics3D.Interactions.Hinge:
        connectors: [frame.bearing, wheel.hub]
        friction becomes Physics.Interactions.Dissipation.ConstantLimitFriction:
            limit: 0.5
    spring is Physics3D.Interactions.TorsionSpring:
        connectors: axle.connectors
"""
    fc = check_text(text)
    assert not [d for d in fc.diagnostics if d.code == "A040"], [d.message for d in fc.diagnostics]
