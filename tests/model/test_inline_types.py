"""The semantic model's answers, written next to the model they are about (issue 28, point 5).

Each fixture is an OpenPLX text analysed in process; a line may end with `# type: T` (the member's
type as `Program.member_type` gives it), `# lint: CODE` (what lint reports on that line, `-` for
nothing) and `# layers: A B C` (a model's class order, lowest priority first). The test reads the
comments, so a reader sees each answer beside the source it is about.
"""

from __future__ import annotations

import re

from plxtools.rules.analysis import analyse_file
from plxtools.syntax import parse_text

EXPECT = re.compile(r"(?:#|\|)\s*(type|lint|layers):\s*([^#|]+?)\s*(?=$|\|)")
DECL = re.compile(r"^(\s*)([\w.]+)[\s:]")


def analyse(workspace, text: str, name: str):
    return analyse_file(workspace, parse_text(text, f"/tmp/plx-inline-type-tests/{name}.openplx"))


def expectations(text: str):
    """(line, indent, name, {kind: value}) for every line that carries an expectation."""
    for line_no, line in enumerate(text.splitlines()):
        found = {m.group(1): m.group(2).strip() for m in EXPECT.finditer(line)}
        decl = DECL.match(line)
        if found and decl:
            yield line_no, len(decl.group(1)), decl.group(2), found


def owner_at(text: str, line_no: int) -> str:
    """The top-level model a line belongs to."""
    for line in reversed(text.splitlines()[: line_no + 1]):
        m = re.match(r"^(?:trait )?(\w+)", line)
        if m and not line.startswith(" "):
            return m.group(1)
    raise AssertionError(line_no)


def written(text: str) -> int:
    """How many expectations the text carries (each must be checked)."""
    return len(re.findall(r"(?:#|\|)\s*(?:type|lint|layers):", text))


def check(workspace, text: str, name: str) -> int:
    result = analyse(workspace, text, name)
    p = workspace.program
    checked = 0
    for line_no, indent, attr, want in expectations(text):
        if "lint" in want:
            codes = sorted({d.code for d in result.diagnostics if d.span.start.line == line_no})
            assert codes == ([] if want["lint"] == "-" else want["lint"].split()), (line_no, attr, codes)
            checked += 1
        if "type" in want:
            model = result.unit.locals[owner_at(text, line_no)]
            member = p.all_members(model)[attr]
            assert p.member_type(member).display() == want["type"], (line_no, attr)
            checked += 1
        if "layers" in want:
            model = result.unit.locals[attr]
            assert [m.name for m in p.linearize(model)] == want["layers"].split(), attr
            checked += 1
    return checked


INHERITANCE = """\
Part:
    mass is Real: 1                      # type: Real
    label is String: "part"              # type: String

trait Coated:
    thickness is Real: 0.001             # type: Real

trait Painted:
    colour is String: "red"              # type: String

Bracket is Part with Coated, Painted:    # layers: Part Coated Painted Bracket
    holes is Int: 4                      # type: Int

Corner is Bracket:                       # layers: Part Coated Painted Bracket Corner
    mass: 2                              # type: Real | lint: -
    thickness: 0.002                     # type: Real | lint: -
    colour: 3                            # type: String | lint: T001
    holes: 4.5                           # type: Int | lint: T002
    spare is Part                        # type: Part
"""


def test_members_keep_their_types_through_bases_and_traits(workspace):
    assert check(workspace, INHERITANCE, "inheritance") == written(INHERITANCE)


REDECLARED = """\
Wheel is Physics3D.Bodies.RigidBody:
    rim is Physics3D.Geometries.Cylinder

Truck is Physics3D.System:
    front is Wheel                                          # type: Wheel
    shape is Physics3D.Geometries.ContactGeometry           # type: Physics3D.Geometries.ContactGeometry

HeavyTruck is Truck:
    shape becomes Physics3D.Geometries.Box                  # type: Physics3D.Geometries.Box | lint: -
    front becomes Physics3D.Geometries.Box                  # lint: M003
"""


def test_becomes_narrows_a_type_and_a_sideways_becomes_is_reported(workspace):
    assert check(workspace, REDECLARED, "redeclared") == written(REDECLARED)


LOOKUP = """\
Vehicle is Physics3D.System:
    wheel_radius is Real: 0.4
    chassis is Physics3D.Bodies.RigidBody:
        inertia.mass: wheel_radius * 1000            # lint: -
    frame is Physics3D.Bodies.RigidBody:
        inertia.mass: wheel_radious                  # lint: N003
    g is Math.Vec3: Math.Vec3.Z_AXIS()               # type: Math.Vec3 | lint: -
    h is Math.Vec3: Math.Vec3.Z_AXES()               # lint: N004
"""


def test_names_in_values_are_looked_up_from_the_outermost_model_and_the_bundles(workspace):
    assert check(workspace, LOOKUP, "lookup") == written(LOOKUP)
