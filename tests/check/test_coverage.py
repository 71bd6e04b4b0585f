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


SLIDER = """
const BoxMaterial is Physics.Geometries.Material:
    unique_name: "cov_box"
    density: 1000

const FloorMaterial is Physics.Geometries.Material:
    unique_name: "cov_floor"
    density: 1000

Floor is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    geometry is Physics3D.Geometries.Box:
        size: {8, 8, 0.2}
        material: FloorMaterial

Block is Physics3D.Bodies.RigidBody:
    inertia.mass: 1.0
    geometry is Physics3D.Geometries.Box:
        size: {0.2, 0.2, 0.2}
        material: BoxMaterial

Sliding is Physics3D.System:
    floor is Floor:
        kinematics.local_transform.position.z: -0.1
    block is Block:
        kinematics.local_transform.position.z: 0.1
    contact is Physics.Interactions.SurfaceContact.Model:
        material_1: BoxMaterial
        material_2: FloorMaterial
        normal_restitution: 0.0
        tangential_restitution: TANGENTIAL
        friction becomes Physics.Interactions.Dissipation.DryConeFriction TRAIT:
            coefficient: 0.4
"""

# a value of each attribute type a bundle trait declares, in the scene above
_VALUES = {"Real": "0.5", "Int": "1", "Bool": "true", "Math.Vec3": "{1, 0, 0}",
           "Physics3D.Geometries.ContactGeometry": "block.geometry", "Physics3D.Bodies.Body": "block",
           "Physics.Geometries.Material": "BoxMaterial"}


def _trait_lines(program, trait) -> list[str]:
    out = []
    for name, mem in program.all_members(trait).items():
        if mem.value is not None:
            continue  # has a default
        ty = program.member_type(mem)
        key = "Real" if ty.model is None else ty.model.qname
        if getattr(ty, "array", False):
            out.append(f"            {name}: []")
            continue
        assert key in _VALUES, f"no test value for {trait.qname}.{name} of type {key}: add one"
        out.append(f"            {name}: {_VALUES[key]}")
    return out


def test_every_bundle_trait_on_a_mapped_object_is_simulated_or_refused_where_it_is_given(check_text, ws, tmp_path):
    """Each official trait that can sit on an object the backend maps, given to a contact's friction
    model (with a value for each attribute it requires): an A040 names it on the line that gives
    it, unless the tables map every attribute it adds.  Fails for a new trait that would be ignored."""
    from plxtools.check import coverage

    traits = [t for t in coverage.official_traits(ws.program) if not t.qname.startswith(coverage._NOT_ON_MAPPED)]
    assert len(traits) >= 6  # the oriented friction family, surface viscosity, material override
    for trait in traits:
        text = SLIDER.replace("TANGENTIAL", "0.0").replace("TRAIT", f"with {trait.qname}")
        text = text.rstrip("\n") + "\n" + "\n".join(_trait_lines(ws.program, trait)) + "\n"
        fc = check_text(text)
        path = tmp_path / "scene.openplx"
        errors = [d.message for d in fc.diagnostics if d.severity.value == "error"]
        assert not errors, (trait.qname, errors)
        own = {n for n, m in ws.program.all_members(trait).items() if m.owner is trait}
        mapped = all(coverage.TRAITS.get(trait.qname, {}).get(n) == coverage.MAPPED for n in own)
        hits = [d for d in fc.diagnostics if d.code == "A040" and trait.name in d.message]
        if mapped:
            assert not hits, trait.qname
        else:
            assert hits, f"{trait.qname} is neither simulated nor refused: {[d.message for d in fc.diagnostics]}"
            assert hits[0].span.start.line + 1 == line_of(path, "friction becomes"), trait.qname


def test_oriented_friction_and_tangential_restitution_are_refused_by_name(check_text, tmp_path):
    text = SLIDER.replace("TANGENTIAL", "0.3").replace(
        "TRAIT", "with Physics3D.Interactions.SurfaceContact.Traits.BodyOrientedFriction")
    text += "            primary_direction: {0, 1, 0}\n            secondary_coefficient: 0.1\n" \
            "            reference_body: block\n"
    fc = check_text(text)
    path = tmp_path / "scene.openplx"
    got = {(d.span.start.line + 1, d.message) for d in fc.diagnostics if d.code == "A040"}
    lines = {line for line, _ in got}
    assert line_of(path, "friction becomes") in lines and line_of(path, "tangential_restitution") in lines
    msgs = " ".join(m for _, m in got)
    assert "BodyOrientedFriction" in msgs and "secondary_coefficient" in msgs and "isotropic" in msgs
    assert "tangential_restitution 0.3" in msgs


def test_a_material_override_trait_on_a_body_is_refused(check_text, tmp_path):
    text = SLIDER.replace("TANGENTIAL", "0.0").replace("TRAIT", "").replace(
        "    block is Block:\n", "    block is Block with Physics.GeometryMaterialOverrideTrait:\n"
        "        material_override: FloorMaterial\n")
    fc = check_text(text)
    msgs = [d.message for d in fc.diagnostics if d.code == "A040"]
    assert any("GeometryMaterialOverrideTrait" in m and "keeps its own material" in m for m in msgs), msgs
