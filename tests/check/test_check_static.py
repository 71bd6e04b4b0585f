"""Static assembly checks: each broken BoxTruck variant reports its code on its line; small cases
cover the other codes."""

from __future__ import annotations

import pytest

from check_helpers import BROKEN, CASES, EXAMPLE, line_of


def found(fc, prefix: str = "") -> list[tuple[str, int]]:
    return [(d.code, d.span.start.line + 1) for d in fc.diagnostics if d.code.startswith(prefix)]


# (file, code, a piece of the line it must be reported on, which occurrence of it, severity)
BROKEN_CASES = [
    ("moved_connector", "A016", "front_left_hinge is Physics3D.Interactions.Hinge", 1, "error"),
    ("flipped_axis", "A018", "main_axis: {0, 0, 1}", 1, "warning"),
    ("wrong_motor_connectors", "A020", "connectors: [chassis.front_left_hub, front_right_wheel.connector]", 1,
     "error"),
    ("zero_box_size", "A030", "geometry is Physics3D.Geometries.Box", 2, "error"),  # the chassis', not the ground's
    ("missing_radius", "M007", "geometry is Physics3D.Geometries.Cylinder", 1, "error"),
    ("duplicate_contact", "A035", "plate_contact is Physics.Interactions.SurfaceContact.Model", 1, "error"),
    ("missing_mesh", "A031", 'path: @"meshes/chassis.obj"', 1, "error"),
    ("mirrored_motors", "A023", "target_speed: 1", 2, "info"),  # the right motor's
]


@pytest.mark.parametrize("name,code,needle,occurrence,severity", BROKEN_CASES, ids=[c[0] for c in BROKEN_CASES])
def test_broken_boxtruck_variants(check_file, name, code, needle, occurrence, severity):
    path = BROKEN / f"{name}.openplx"
    fc = check_file(path)
    line = line_of(path, needle, occurrence)
    hits = [d for d in fc.diagnostics if d.code == code]
    assert [d.span.start.line + 1 for d in hits] == [line] * len(hits) and hits, found(fc)
    assert hits[0].severity.value == severity
    # nothing else is wrong with these files: only the intended finding
    # (A044: the example's DisableCollisionPair changes nothing at the start, an info every variant shares)
    others = {c for c, _ in found(fc)} - {code, "A044"}
    assert not others, found(fc)


def test_broken_variant_messages_carry_the_numbers(check_file):
    moved = check_file(BROKEN / "moved_connector.openplx")
    (d,) = [d for d in moved.diagnostics if d.code == "A016"]
    # the wheel is declared at z 1.0 instead of 1.1 - 0.6912: 0.5912 m off
    assert "0.5912 m apart" in d.message
    wheel_line = line_of(BROKEN / "moved_connector.openplx", "kinematics.local_transform.position: {-1.023")
    assert f"box_truck.front_left_wheel: declared transform at line {wheel_line}" in d.message
    flipped = check_file(BROKEN / "flipped_axis.openplx")
    (d,) = [d for d in flipped.diagnostics if d.code == "A018"]
    assert "90 deg away from the axis of its cylinder" in d.message and "also 3 more" in d.message
    dup = check_file(BROKEN / "duplicate_contact.openplx")
    (d,) = [d for d in dup.diagnostics if d.code == "A035"]
    assert "plxtools_example_plate / plxtools_example_tire" in d.message and "tire_contact" in d.message


def test_connector_mate_and_controller_mistakes(check_file):
    path = CASES / "connectors.openplx"
    fc = check_file(path)
    L = lambda needle, n=1: line_of(path, needle, n)  # noqa: E731
    expected = [
        ("A010", L("main_axis: {0, 0, 0}")),
        ("A011", L("normal: {0, -2, 0}")),
        ("A012", L("normal: {1, 0, 1}")),
        ("A015", L("connectors: [p.skew, p.plain]")),
        ("A014", L("connectors: [q.skew, q.skew]")),
        ("A013", L("connectors: [q.plain]")),
        ("A016", L("m6 is Physics3D.Interactions.Lock")),  # static floor 2 m below the world origin
        ("A017", L("m6 is Physics3D.Interactions.Lock")),
        ("A021", L("connectors: [p.skew, q.skew]", 2)),
        ("A022", L("target_speed: 90")),
        ("A024", L("start: 1")),
        # lint's: connectors that an earlier mate already holds (m1, m3, m4)
        ("A043", L("connectors: [q.plain]")),
        # (m3's p.skew is not counted as held: m3 joins one body to itself, A015, and holds nothing)
        ("A043", L("connectors: [p.skew, q.skew]")),
    ]
    assert sorted(found(fc, "A")) == sorted(expected)
    sev = {d.code: d.severity.value for d in fc.diagnostics}
    assert sev["A012"] == "info" and sev["A017"] == "warning" and sev["A022"] == "info" and sev["A010"] == "error"


def test_body_material_and_contact_mistakes(check_file, monkeypatch):
    monkeypatch.delenv("PLX_SURELY_UNSET_VAR", raising=False)
    path = CASES / "bodies.openplx"
    fc = check_file(path)
    L = lambda needle, n=1: line_of(path, needle, n)  # noqa: E731
    expected = [
        ("A038", L("density: 0")),
        ("A039", L("inner is Thing")),
        ("A032", L("inertia.mass: -5")),
        ("A033", L("ghost is Physics3D.Bodies.RigidBody")),
        ("A030", L("geometry.radius: 0")),  # and no A033 for `flat`: its only geometry is rejected
        ("A033", L("foam is Thing")),
        ("A034", L("inertia.tensor:")),
        ("A033", L("holder is Holder")),
        ("A040", L("shaft is Physics1D.Bodies.Inertia")),
        # normal_restitution 0.5 is simulated (A137, a backend note), so no A040
        ("A036", L("tangential_restitution: 2")),
        ("A036", L("coefficient: -1")),
        ("A007", L("unique_name: $")),
    ]
    assert sorted(found(fc, "A")) == sorted(expected)
    msgs = {d.code + str(d.span.start.line + 1): d.message for d in fc.diagnostics}
    assert "principal moments 1 + 1 < 5" in msgs["A034" + str(L("inertia.tensor:"))]
    assert "PLX_SURELY_UNSET_VAR" in msgs["A007" + str(L("unique_name: $"))]


def test_root_model_selection(check_file):
    fc = check_file(EXAMPLE, model="Wheel")  # a library model can be checked on its own
    assert fc.model == "Wheel" and list(fc.assembled_bodies()) == ["Wheel"]  # the root body, at the origin
    assert [b.path for b in fc.scene.bodies] == ["Wheel"] and fc.scene.bodies[0].mass == 10
    fc = check_file(EXAMPLE, model="Nope")
    (d,) = [d for d in fc.diagnostics if d.code == "A001"]
    assert "no model named 'Nope'" in d.message and "BoxTruck" in d.message and fc.assembly is None


def test_trait_as_root_and_syntax_errors(check_text):
    fc = check_text("""
trait Shiny:
    gloss is Real: 1

Scene is Physics3D.System:
    x is Real: 1
""", model="Shiny")
    assert found(fc, "A") == [("A002", 1)]
    fc = check_text("""
Scene is Physics3D.System:
    box is Physics3D.Bodies.RigidBody:
        inertia.mass: (1
""")
    assert fc.skipped == "the file has syntax errors" and fc.assembly is None
    assert found(fc) and all(code.startswith("S") for code, _ in found(fc))


def test_inline_suppression_and_config_apply_to_check_codes(check_text):
    fc = check_text("""
Ball is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Sphere:
        radius: 0  # plx: ignore[A030]

Scene is Physics3D.System:
    ball is Ball
""")
    assert found(fc) == []  # A030 suppressed, and the suppression counts as used (no C002)
