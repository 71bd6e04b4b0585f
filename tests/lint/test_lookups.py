"""Name at an offset -> its declaration, straight from the semantic model's recorded occurrences."""

from pathlib import Path

from plxtools.model.symbols import MemberSym, ModelSym
from plxtools.syntax import parse_file
from tests.conftest import bundle_root


def occurrence_at(analysis, offset):
    hits = [o for o in analysis.occurrences if o.span.start.offset <= offset < o.span.end.offset]
    return min(hits, key=lambda o: o.span.end.offset - o.span.start.offset) if hits else None


def test_base_type_resolves_to_its_file(workspace):
    path = bundle_root() / "Physics3D" / "Bodies" / "RigidBody.openplx"
    tree = workspace.program.units[str(path)].tree
    analysis = workspace.analyse(tree)
    offset = tree.text.index("Physics3D.Bodies.Body") + len("Physics3D.Bodies.")
    occ = occurrence_at(analysis, offset)
    assert isinstance(occ.target, ModelSym) and occ.target.qname == "Physics3D.Bodies.Body"
    assert Path(occ.target.unit.path).name == "Body.openplx"
    assert occ.target.stmt.header.start.line == 0


def test_relative_name_resolves_through_the_namespace_rule(workspace):
    # inside Physics3D/Geometries, `ContactGeometry` means Physics3D.Geometries.ContactGeometry (spec C.2)
    path = bundle_root() / "Physics3D" / "Geometries" / "Box.openplx"
    tree = workspace.program.units[str(path)].tree
    analysis = workspace.analyse(tree)
    occ = occurrence_at(analysis, tree.text.index("ContactGeometry"))
    assert occ.target.qname == "Physics3D.Geometries.ContactGeometry"


def test_dotted_assignment_path_resolves_each_segment(workspace):
    tree = parse_file(Path(__file__).resolve().parents[2] / "examples" / "boxtruck" / "boxtruck.openplx")
    analysis = workspace.analyse(tree)
    text = tree.text
    at = text.index("kinematics.local_transform.position.z")
    names = []
    for seg in ("kinematics", "local_transform", "position", "z"):
        occ = occurrence_at(analysis, text.index(seg, at))
        assert isinstance(occ.target, MemberSym)
        names.append(occ.target.qname)
    assert names == ["Physics3D.Bodies.RigidBody.kinematics", "Physics3D.Bodies.Kinematics.local_transform",
                     "Math.AffineTransform.position", "Math.Vec3.z"]


def test_every_type_reference_in_the_bundles_has_a_declaration(workspace, bundles):
    refs = 0
    for path in bundles:
        unit = workspace.program.units.get(str(path))
        if unit is None:
            continue  # config.openplx files
        for occ in workspace.analyse(unit.tree).occurrences:
            if occ.kind == "type":
                refs += 1
                target = occ.target
                assert getattr(target, "stmt", None) is not None or not isinstance(target, ModelSym)
    assert refs > 1000
