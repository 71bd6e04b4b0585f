"""Tests for plxtools.model.natives: the Python/numpy implementations of OpenPLX's native functions."""

from __future__ import annotations

import itertools
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from plxtools.model import natives as n
from plxtools.model.natives import (
    FUNCTIONS,
    OPERATORS,
    UNSUPPORTED,
    ElementaryTransform,
    Line,
    NativeError,
    Transform,
    apply_operator,
    call,
    primitive_result_type,
    type_of,
)

openplxbundles = pytest.importorskip("openplxbundles")
BUNDLE_ROOT = Path(openplxbundles.package_dir())

PRIMITIVES = {"Real", "Int", "Bool", "String"}
X, Y, Z = np.eye(3)
ID_Q = np.array([0.0, 0.0, 0.0, 1.0])


def f(name: str):
    return FUNCTIONS[name]


@pytest.fixture(scope="module", autouse=True)
def official_struct_types():
    """The math types' fields and defaults come from the bundle program, as in `plx check`."""
    from plxtools.model.workspace import Workspace

    return Workspace().program


@pytest.fixture(scope="module")
def structs(official_struct_types):
    from plxtools.model.natives import struct_types

    return struct_types(official_struct_types)


def test_struct_fields_and_defaults_are_read_from_the_bundles(official_struct_types, structs):
    p = official_struct_types
    for name in ("Math.Vec2", "Math.Vec3", "Math.Quat", "Math.Matrix3x3", "Math.Matrix4x4", "Math.AffineTransform",
                 "Math.Line"):
        model = p.lookup_outside_visibility(name.split("."))
        assert structs[name].fields == tuple(p.all_members(model)), name
    quat = p.lookup_outside_visibility(["Math", "Quat"])
    assert p.all_members(quat)["w"].value.value == 1 and structs["Math.Quat"].defaults["w"] == 1.0
    assert structs["Math.AffineTransform"].field_types == {"position": "Math.Vec3", "rotation": "Math.Quat"}
    assert "e00" not in structs["Math.Matrix4x4"].defaults  # the bundle gives Matrix4x4 no defaults


def close(a, b, tol=1e-9) -> bool:
    return bool(np.allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), atol=tol, rtol=0))


def rot_matrix(q) -> np.ndarray:
    """Rotation matrix of q computed through the public rotate(), column by column."""
    return np.column_stack([f("Math.Quat.rotate")(q, e) for e in np.eye(3)])


def same_rotation(q1, q2, tol=1e-9) -> bool:
    return close(rot_matrix(q1), rot_matrix(q2), tol)


def qmul(a, b) -> np.ndarray:
    return apply_operator("*", "Math.Quat", a, "Math.Quat", b)


def random_unit_quat(rng) -> np.ndarray:
    q = rng.normal(size=4)
    return q / np.linalg.norm(q)


# ------------------------------------------------------------------------------------------------
# The bundles' declarations, read with a small parser of our own
# ------------------------------------------------------------------------------------------------

_TOP = re.compile(r"^(?:const\s+)?(?:trait\s+)?([A-Za-z_]\w*)\b")
_FN = re.compile(r"^\s+(static\s+)?fn\s+(\w+)\s*\(([^)]*)\)")
_ATTR = re.compile(r"^\s+(\w+)\s+is\s+([\w.\[\]]+)")
_OPERATOR = re.compile(r"^operator\s*([-+*/])\s*\(([^)]*)\)\s*->\s*([\w.]+)")


def _qualify(bundle: str, type_name: str) -> str:
    type_name = type_name.strip()
    return type_name if type_name in PRIMITIVES or "." in type_name else f"{bundle}.{type_name}"


def _parse_bundles(root: Path):
    """Return (fns, operators, attributes).

    fns: qualified name -> (is_static, number of declared parameters)
    operators: set of (op, lhs_type, rhs_type or None)
    attributes: qualified model name -> [attribute names in order] (top-level models only)
    """
    fns: dict[str, tuple[bool, int]] = {}
    operators: set[tuple[str, str, str | None]] = set()
    attributes: dict[str, list[str]] = {}
    for path in sorted(root.rglob("*.openplx")):
        rel = path.relative_to(root)
        bundle = rel.parts[0]
        namespace = ".".join(rel.parts[:-1])
        model = None
        in_doc = False
        for line in path.read_text(encoding="utf-8").splitlines():
            quotes = line.count('"""')
            if in_doc or quotes:
                if quotes % 2:
                    in_doc = not in_doc
                continue
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            if not line[0].isspace():
                m = _OPERATOR.match(line)
                if m:
                    op, params, _ = m.groups()
                    types = [_qualify(bundle, p.split(":")[1]) for p in params.split(",")]
                    operators.add((op, types[0], types[1] if len(types) == 2 else None))
                    model = None
                    continue
                m = _TOP.match(line)
                model = m.group(1) if m else None
                if model:
                    attributes.setdefault(f"{namespace}.{model}", [])
                continue
            if model is None:
                continue
            m = _FN.match(line)
            if m:
                static, name, params = m.groups()
                count = len([p for p in params.split(",") if p.strip()])
                fns[f"{namespace}.{model}.{name}"] = (bool(static), count)
                continue
            m = _ATTR.match(line)
            if m and len(line) - len(line.lstrip()) <= 4:
                attributes[f"{namespace}.{model}"].append(m.group(1))
    return fns, operators, attributes


DECLARED_FNS, DECLARED_OPERATORS, DECLARED_ATTRIBUTES = _parse_bundles(BUNDLE_ROOT)
MATH_FNS = {k: v for k, v in DECLARED_FNS.items() if k.startswith("Math.")}


def test_parser_found_the_bundle_declarations():
    # Guards against a parser that silently finds nothing.
    assert len(MATH_FNS) >= 110  # 117 in the 0.19 bundles
    assert "Math.Quat.from_euler_angles_zyzr" in MATH_FNS
    assert MATH_FNS["Math.Vec3.cross"] == (False, 1)
    assert MATH_FNS["Math.Functions.arctan2"] == (True, 2)
    assert "Physics3D.Bodies.Inertia.symmetric_tensor" in DECLARED_FNS
    assert "Physics3D.System.resnap" in DECLARED_FNS
    assert ("*", "Math.Matrix3x3", "Math.Vec3") in DECLARED_OPERATORS
    assert ("-", "Math.Quat", None) in DECLARED_OPERATORS
    assert len(DECLARED_OPERATORS) >= 30


def test_every_declared_math_function_is_implemented():
    missing = sorted(set(MATH_FNS) - set(FUNCTIONS))
    assert missing == []
    assert not set(MATH_FNS) & UNSUPPORTED


def test_every_declared_function_is_implemented_or_listed_unsupported():
    missing = sorted(name for name in DECLARED_FNS if name not in FUNCTIONS and name not in UNSUPPORTED)
    assert missing == []


def test_unsupported_and_implemented_names_are_all_declared():
    assert sorted(UNSUPPORTED - set(DECLARED_FNS)) == []
    assert sorted(set(FUNCTIONS) - set(DECLARED_FNS)) == []
    assert not set(FUNCTIONS) & UNSUPPORTED


def test_function_arity_matches_declaration():
    for name, (static, count) in DECLARED_FNS.items():
        if name in FUNCTIONS:
            expected = count if static else count + 1  # receiver first
            assert FUNCTIONS[name].arity == expected, name


def test_every_declared_math_operator_is_implemented():
    assert sorted(DECLARED_OPERATORS - set(OPERATORS), key=str) == []


def test_codec_fields_match_bundle_attributes(structs):
    for type_name, codec in structs.items():
        assert list(codec.fields) == DECLARED_ATTRIBUTES[type_name][: len(codec.fields)], type_name
        assert set(DECLARED_ATTRIBUTES[type_name]) == set(codec.fields), type_name


# ------------------------------------------------------------------------------------------------
# Vectors
# ------------------------------------------------------------------------------------------------


def test_vec3_basics():
    a, b = np.array([1.0, 2.0, 3.0]), np.array([4.0, 5.0, 6.0])
    assert close(f("Math.Vec3.cross")(a, b), [-3.0, 6.0, -3.0])
    assert close(f("Math.Vec3.cross")(X, Y), Z)
    assert f("Math.Vec3.dot")(a, b) == 32.0
    assert type(f("Math.Vec3.dot")(a, b)) is float
    assert f("Math.Vec3.length")([3.0, 4.0, 0.0]) == 5.0
    assert type(f("Math.Vec3.length")([3.0, 4.0, 0.0])) is float
    assert close(f("Math.Vec3.normal")([0.0, 3.0, 4.0]), [0.0, 0.6, 0.8])
    assert close(f("Math.Vec3.from_xyz")(1, 2.5, -3), [1.0, 2.5, -3.0])
    assert close(f("Math.Vec3.X_AXIS")(), X)
    assert close(f("Math.Vec3.Y_AXIS")(), Y)
    assert close(f("Math.Vec3.Z_AXIS")(), Z)


def test_extreme_magnitudes_do_not_overflow_or_underflow():
    assert close(f("Math.Vec3.normal")([1e200, 0.0, 1e200]), [math.sqrt(0.5), 0.0, math.sqrt(0.5)])
    assert close(f("Math.Vec3.normal")([0.0, 3e-300, 4e-300]), [0.0, 0.6, 0.8])
    assert f("Math.Vec3.length")([3e200, 4e200, 0.0]) == pytest.approx(5e200)
    assert close(f("Math.Vec3.get_orthogonal_unit_vector")([0.0, 0.0, 1e-310]), X)
    assert close(f("Math.Quat.angle_axis")(math.pi, [0.0, 0.0, 1e-300]), [0.0, 0.0, 1.0, math.cos(math.pi / 2)])
    t = f("Math.AffineTransform.from_axes")([0.0, 0.0, 1e-200], [1e-200, 0.0, 0.0], np.zeros(3))
    assert close(t.rotation, ID_Q)


def test_axis_constants_are_fresh_arrays():
    v = f("Math.Vec3.X_AXIS")()
    v[0] = 5.0
    assert close(f("Math.Vec3.X_AXIS")(), X)


def test_vec2_basics():
    assert close(f("Math.Vec2.from_xy")(3, 4), [3.0, 4.0])
    assert f("Math.Vec2.length")([3.0, 4.0]) == 5.0
    assert close(f("Math.Vec2.normal")([3.0, 4.0]), [0.6, 0.8])
    assert f("Math.Vec2.dot")([1.0, 2.0], [3.0, -4.0]) == -5.0
    assert close(f("Math.Vec2.X_AXIS")(), [1.0, 0.0])
    assert close(f("Math.Vec2.Y_AXIS")(), [0.0, 1.0])


@pytest.mark.parametrize(
    "v1, v2, axis, expected",
    [
        (X, Y, Z, math.pi / 2),
        (X, Y, -Z, -math.pi / 2),
        (Y, X, Z, -math.pi / 2),
        (X, -X, Z, math.pi),
        (X, X, Z, 0.0),
        (X, [1.0, 1.0, 0.0], [0.0, 0.0, 5.0], math.pi / 4),
        ([2.0, 0.0, 0.0], [-1.0, -1.0, 0.0], Z, -3 * math.pi / 4),
    ],
)
def test_angle_between_vectors(v1, v2, axis, expected):
    assert f("Math.Vec3.angle_between_vectors")(v1, v2, axis) == pytest.approx(expected)


def test_orthogonal_unit_vector_documented_choices():
    g = f("Math.Vec3.get_orthogonal_unit_vector")
    assert close(g(Z), X)  # default MateConnector: main Z -> normal X
    assert close(g(X), Y)
    assert close(g(Y), X)
    assert close(g([0.0, 0.0, -3.0]), X)
    assert close(g([0.0, 0.0, 0.0]), X)  # zero vector: defined, no error
    assert close(g([1.0, 1.0, 1.0]), np.array([2.0, -1.0, -1.0]) / math.sqrt(6))


def test_orthogonal_unit_vector_is_unit_and_orthogonal():
    g = f("Math.Vec3.get_orthogonal_unit_vector")
    rng = np.random.default_rng(1)
    vectors = [rng.normal(size=3) * 10.0 ** rng.integers(-6, 7) for _ in range(500)]
    vectors += [s * e for e in np.eye(3) for s in (1.0, -1.0, 1e-12, 1e9)]
    vectors += [np.array(v, dtype=float) for v in itertools.product((-1.0, 0.0, 1.0), repeat=3) if any(v)]
    for v in vectors:
        u = g(v)
        assert abs(np.linalg.norm(u) - 1.0) < 1e-12
        assert abs(np.dot(u, v / np.linalg.norm(v))) < 1e-12
        assert close(g(v), u, 0.0)  # deterministic


# ------------------------------------------------------------------------------------------------
# Quaternions
# ------------------------------------------------------------------------------------------------


def test_angle_axis_rotate_x_about_z_gives_y():
    q = f("Math.Quat.angle_axis")(math.pi / 2, Z)
    assert close(q, [0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])
    assert close(f("Math.Quat.rotate")(q, X), Y)
    assert close(f("Math.Quat.rotate")(q, Y), -X)
    assert close(f("Math.Quat.rotate")(q, Z), Z)
    # The axis need not be unit length.
    assert close(f("Math.Quat.angle_axis")(math.pi / 2, [0.0, 0.0, 7.0]), q)


def test_structural_planar_connector_normal_expression():
    # normal: Math.Quat.angle_axis(angle, main_axis).rotate(Math.Vec3.X_AXIS())
    q = f("Math.Quat.angle_axis")(math.radians(30.0), f("Math.Vec3.Z_AXIS")())
    assert close(f("Math.Quat.rotate")(q, f("Math.Vec3.X_AXIS")()), [math.sqrt(3) / 2, 0.5, 0.0])


def test_quat_product_is_sequential_rotation():
    rng = np.random.default_rng(2)
    for _ in range(100):
        q1, q2, v = random_unit_quat(rng), random_unit_quat(rng), rng.normal(size=3)
        q12 = apply_operator("*", "Math.Quat", q1, "Math.Quat", q2)
        rot = f("Math.Quat.rotate")
        assert close(rot(q12, v), rot(q1, rot(q2, v)))


def test_quat_product_hand_checked():
    qz = f("Math.Quat.angle_axis")(math.pi / 2, Z)
    qx = f("Math.Quat.angle_axis")(math.pi / 2, X)
    # first about X (Y -> Z), then about Z (Z stays): Y -> Z
    q = apply_operator("*", "Math.Quat", qz, "Math.Quat", qx)
    assert close(f("Math.Quat.rotate")(q, Y), Z)
    # first about Z (Y -> -X), then about X (-X stays): Y -> -X
    q = apply_operator("*", "Math.Quat", qx, "Math.Quat", qz)
    assert close(f("Math.Quat.rotate")(q, Y), -X)


def test_quat_conj_inverse_normal_division():
    q = np.array([1.0, 2.0, 3.0, 4.0])
    assert close(f("Math.Quat.conj")(q), [-1.0, -2.0, -3.0, 4.0])
    inv = f("Math.Quat.inverse")(q)
    assert close(inv, np.array([-1.0, -2.0, -3.0, 4.0]) / 30.0)
    assert close(apply_operator("*", "Math.Quat", q, "Math.Quat", inv), ID_Q)
    assert close(f("Math.Quat.normal")(q), q / math.sqrt(30.0))
    p = np.array([0.5, -1.0, 2.0, 0.25])
    quotient = apply_operator("/", "Math.Quat", p, "Math.Quat", q)
    assert close(apply_operator("*", "Math.Quat", quotient, "Math.Quat", q), p)
    assert close(f("Math.Quat.from_xyzw")(1, 2, 3, 4), q)


def test_quat_scalar_and_additive_operators():
    q = np.array([1.0, 2.0, 3.0, 4.0])
    p = np.array([0.5, 0.5, 0.5, 0.5])
    assert close(apply_operator("*", "Math.Quat", q, "Real", 2.0), 2 * q)
    assert close(apply_operator("*", "Real", 2.0, "Math.Quat", q), 2 * q)
    assert close(apply_operator("/", "Math.Quat", q, "Real", 2.0), q / 2)
    assert close(apply_operator("+", "Math.Quat", q, "Math.Quat", p), q + p)
    assert close(apply_operator("-", "Math.Quat", q, "Math.Quat", p), q - p)
    assert close(apply_operator("-", "Math.Quat", q), -q)


def test_rotate_normalises_the_quaternion():
    q = 3.0 * f("Math.Quat.angle_axis")(math.pi / 2, Z)
    assert close(f("Math.Quat.rotate")(q, X), Y)


def test_from_to():
    ft = f("Math.Quat.from_to")
    rot = f("Math.Quat.rotate")
    assert close(rot(ft(X, Y), X), Y)
    assert close(ft(X, Y), f("Math.Quat.angle_axis")(math.pi / 2, Z))
    assert close(ft(X, [5.0, 0.0, 0.0]), ID_Q)
    # antiparallel: a half turn about get_orthogonal_unit_vector(from)
    assert close(rot(ft(Z, -Z), Z), -Z)
    assert close(ft(Z, -Z), [1.0, 0.0, 0.0, 0.0])
    rng = np.random.default_rng(3)
    for _ in range(200):
        a, b = rng.normal(size=3), rng.normal(size=3)
        for to in (b, -a, a * 2.0):
            q = ft(a, to)
            assert abs(np.linalg.norm(q) - 1.0) < 1e-12
            assert close(rot(q, a / np.linalg.norm(a)), to / np.linalg.norm(to))


# ------------------------------------------------------------------------------------------------
# Euler angles
# ------------------------------------------------------------------------------------------------

ALL_ORDERS = [
    f"{i}{j}{k}{frame}"
    for frame in "sr"
    for i, j, k in itertools.product("xyz", repeat=3)
    if i != j and j != k
]


def test_there_are_24_orders_and_they_match_the_bundle():
    assert sorted(ALL_ORDERS) == sorted(n.EULER_ORDERS)
    prefix = "Math.Quat.from_euler_angles_"
    declared = {name[len(prefix) :] for name in MATH_FNS if name.startswith(prefix)}
    assert declared == set(ALL_ORDERS)


def _euler_grid(order):
    rng = np.random.default_rng(sum(map(ord, order)))
    symmetric = order[0] == order[2]
    locks = (0.0, math.pi) if symmetric else (math.pi / 2, -math.pi / 2)
    near = (1e-7, math.pi - 1e-7) if symmetric else (math.pi / 2 - 1e-7, -math.pi / 2 + 1e-7)
    grid = [rng.uniform(-math.pi, math.pi, size=3) for _ in range(100)]
    grid += [np.array([a, b, c]) for a in (0.3, -2.0) for b in locks + near for c in (0.0, 1.1, -3.0)]
    grid += [np.zeros(3), np.array([math.pi, 0.0, math.pi])]
    return grid


@pytest.mark.parametrize("order", ALL_ORDERS)
def test_euler_round_trip(order):
    from_e = f(f"Math.Quat.from_euler_angles_{order}")
    to_e = f(f"Math.Quat.to_euler_angles_{order}")
    symmetric = order[0] == order[2]
    for angles in _euler_grid(order):
        q = from_e(*angles)
        e = to_e(q)
        assert e.shape == (3,)
        assert same_rotation(from_e(*e), q, 1e-7), (order, angles, e)
        assert -math.pi <= e[0] <= math.pi and -math.pi <= e[2] <= math.pi
        if symmetric:
            assert 0.0 <= e[1] <= math.pi
        else:
            assert -math.pi / 2 <= e[1] <= math.pi / 2
        # the sign of the quaternion does not matter
        assert same_rotation(from_e(*to_e(-q)), q, 1e-7)


@pytest.mark.parametrize("order", ALL_ORDERS)
def test_euler_angles_recovered_away_from_gimbal_lock(order):
    angles = (0.3, 1.2, -0.7) if order[0] == order[2] else (0.3, 0.4, -0.7)
    q = f(f"Math.Quat.from_euler_angles_{order}")(*angles)
    assert close(f(f"Math.Quat.to_euler_angles_{order}")(q), angles)


@pytest.mark.parametrize("order", ALL_ORDERS)
def test_euler_definition(order):
    """s: R = R_k(c) R_j(b) R_i(a) (world axes); r: R = R_i(a) R_j(b) R_k(c) (body axes)."""
    aa = f("Math.Quat.angle_axis")
    axis = {"x": X, "y": Y, "z": Z}
    a, b, c = 0.4, -1.1, 2.3
    qa, qb, qc = aa(a, axis[order[0]]), aa(b, axis[order[1]]), aa(c, axis[order[2]])
    if order[3] == "s":
        expected = qmul(qc, qmul(qb, qa))
    else:
        expected = qmul(qa, qmul(qb, qc))
    assert same_rotation(f(f"Math.Quat.from_euler_angles_{order}")(a, b, c), expected)
    # Shoemake: the rotating order is the static order reversed, with alpha and gamma swapped
    frame = "r" if order[3] == "s" else "s"
    mirrored = f(f"Math.Quat.from_euler_angles_{order[2::-1]}{frame}")(c, b, a)
    assert same_rotation(mirrored, expected)


def test_euler_hand_checked_static_vs_rotating():
    rot = f("Math.Quat.rotate")
    half = math.pi / 2
    # static: about world X (X stays), then about world Y: X -> -Z
    assert close(rot(f("Math.Quat.from_euler_angles_xyzs")(half, half, 0.0), X), -Z)
    # rotating: about X, then about the new Y: X -> Y
    assert close(rot(f("Math.Quat.from_euler_angles_xyzr")(half, half, 0.0), X), Y)
    # a single angle is a plain axis rotation
    assert close(f("Math.Quat.from_euler_angles_zyxr")(0.5, 0.0, 0.0), f("Math.Quat.angle_axis")(0.5, Z))


def test_euler_aliases_are_xyzs():
    q = f("Math.Quat.from_euler_angles")(0.1, 0.2, 0.3)
    assert close(q, f("Math.Quat.from_euler_angles_xyzs")(0.1, 0.2, 0.3))
    assert close(f("Math.Quat.to_euler_angles")(q), [0.1, 0.2, 0.3])


def test_euler_gimbal_lock_sets_gamma_to_zero():
    e = f("Math.Quat.to_euler_angles_xyzs")(f("Math.Quat.from_euler_angles_xyzs")(0.3, math.pi / 2, 0.5))
    assert e[2] == 0.0 and e[1] == pytest.approx(math.pi / 2)
    e = f("Math.Quat.to_euler_angles_zxzr")(f("Math.Quat.from_euler_angles_zxzr")(0.3, 0.0, 0.5))
    assert e == pytest.approx([0.8, 0.0, 0.0])


# ------------------------------------------------------------------------------------------------
# AffineTransform
# ------------------------------------------------------------------------------------------------


def test_from_axes_frame_convention():
    fa = f("Math.AffineTransform.from_axes")
    vec = f("Math.AffineTransform.transform_vec3_vector")
    point = f("Math.AffineTransform.transform_vec3_point")
    t = fa([0.0, 2.0, 0.0], [1.0, 5.0, 0.0], [1.0, 2.0, 3.0])  # new_X has a component along new_Z
    assert close(vec(t, Z), Y)
    assert close(vec(t, X), X)  # projected onto the plane orthogonal to new_Z
    assert close(vec(t, Y), -Z)  # y = z x x
    assert close(point(t, [0.0, 0.0, 0.0]), [1.0, 2.0, 3.0])
    assert close(point(t, Z), [1.0, 3.0, 3.0])
    identity = fa(Z, X, np.zeros(3))
    assert close(identity.rotation, ID_Q) and close(identity.position, np.zeros(3))


def test_from_axes_random_frames():
    fa = f("Math.AffineTransform.from_axes")
    vec = f("Math.AffineTransform.transform_vec3_vector")
    rng = np.random.default_rng(4)
    for _ in range(200):
        nz, nx, p = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
        t = fa(nz, nx, p)
        z = nz / np.linalg.norm(nz)
        x = nx - np.dot(nx, z) * z
        x /= np.linalg.norm(x)
        assert close(vec(t, Z), z)
        assert close(vec(t, X), x)
        assert close(vec(t, Y), np.cross(z, x))
        assert t.rotation[3] >= 0.0
        assert abs(np.linalg.norm(t.rotation) - 1.0) < 1e-12


def test_transform_composition_and_inverse():
    rng = np.random.default_rng(5)
    point = f("Math.AffineTransform.transform_vec3_point")
    for _ in range(100):
        t1 = f("Math.AffineTransform.from")(rng.normal(size=3), random_unit_quat(rng))
        t2 = f("Math.AffineTransform.from")(rng.normal(size=3), random_unit_quat(rng))
        v = rng.normal(size=3)
        t12 = apply_operator("*", "Math.AffineTransform", t1, "Math.AffineTransform", t2)
        assert isinstance(t12, Transform)
        assert close(point(t12, v), point(t1, point(t2, v)))
        inv = f("Math.AffineTransform.inverse")(t1)
        assert close(point(inv, point(t1, v)), v)
        both = apply_operator("*", "Math.AffineTransform", t1, "Math.AffineTransform", inv)
        assert close(both.position, np.zeros(3)) and same_rotation(both.rotation, ID_Q)
        inv_of = f("Math.AffineTransform.inverse_of")(t1.position, t1.rotation)
        assert close(inv_of.position, inv.position) and close(inv_of.rotation, inv.rotation)


def test_transform_hand_checked(structs):
    q = f("Math.Quat.angle_axis")(math.pi / 2, Z)
    t = f("Math.AffineTransform.from")([1.0, 0.0, 0.0], q)
    assert close(f("Math.AffineTransform.transform_vec3_point")(t, X), [1.0, 1.0, 0.0])
    assert close(f("Math.AffineTransform.transform_vec3_vector")(t, X), Y)
    inv = f("Math.AffineTransform.inverse")(t)
    assert close(inv.position, [0.0, 1.0, 0.0])
    created = f("Math.AffineTransform.create")()
    assert created == Transform(np.zeros(3), ID_Q)
    assert created == structs["Math.AffineTransform"].default()


def test_transform_is_immutable_value():
    t = Transform([1, 2, 3], [0, 0, 0, 1])
    assert t.position.dtype == float and t.rotation.dtype == float
    with pytest.raises(ValueError):
        t.position[0] = 5.0
    with pytest.raises(AttributeError):
        t.position = np.zeros(3)  # type: ignore[misc]
    assert t == Transform(np.array([1.0, 2.0, 3.0]), ID_Q)
    assert t != Transform(np.zeros(3), ID_Q)
    with pytest.raises(NativeError):
        Transform([1.0, 2.0], ID_Q)


# ------------------------------------------------------------------------------------------------
# Matrices, Line, Inertia, ETS
# ------------------------------------------------------------------------------------------------


def test_matrix3x3():
    m = f("Math.Matrix3x3.from_row_major")(1, 2, 3, 4, 5, 6, 7, 8, 10)
    assert close(m, [[1, 2, 3], [4, 5, 6], [7, 8, 10]])
    assert close(f("Math.Matrix3x3.from_rows")([1, 2, 3], [4, 5, 6], [7, 8, 10]), m)
    assert close(f("Math.Matrix3x3.from_columns")([1, 4, 7], [2, 5, 8], [3, 6, 10]), m)
    assert close(f("Math.Matrix3x3.diag")(1, 2, 3), np.diag([1.0, 2.0, 3.0]))
    assert close(apply_operator("*", "Math.Matrix3x3", m, "Math.Vec3", [1.0, 0.0, -1.0]), [-2.0, -2.0, -3.0])
    assert close(apply_operator("*", "Math.Matrix3x3", m, "Math.Matrix3x3", np.eye(3)), m)
    assert close(apply_operator("*", "Math.Matrix3x3", m, "Math.Matrix3x3", m), np.array(m) @ np.array(m))
    assert close(apply_operator("+", "Math.Matrix3x3", m, "Math.Matrix3x3", np.eye(3)), m + np.eye(3))
    assert close(apply_operator("-", "Math.Matrix3x3", m, "Math.Matrix3x3", m), np.zeros((3, 3)))


def test_matrix4x4():
    values = list(range(16))
    m = f("Math.Matrix4x4.from_row_major")(*values)
    assert close(m, np.arange(16.0).reshape(4, 4))
    rows = [values[i : i + 4] for i in range(0, 16, 4)]
    assert close(f("Math.Matrix4x4.from_rows")(*rows), m)
    assert close(f("Math.Matrix4x4.from_columns")(*rows), m.T)
    assert close(f("Math.Matrix4x4.transpose")(m), m.T)
    c = f("Math.Matrix4x4.copy")(m)
    c[0, 0] = 99.0
    assert m[0, 0] == 0.0
    assert close(apply_operator("*", "Math.Matrix4x4", m, "Math.Matrix4x4", np.eye(4)), m)
    assert close(apply_operator("+", "Math.Matrix4x4", m, "Math.Matrix4x4", m), 2 * m)
    assert close(apply_operator("-", "Math.Matrix4x4", m, "Math.Matrix4x4", m), np.zeros((4, 4)))


def test_matrix4x4_affine():
    q = f("Math.Quat.angle_axis")(math.pi / 2, Z)
    m = f("Math.Matrix4x4.from_vec3_quat")([1.0, 2.0, 3.0], q)
    assert close(m, [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]])
    assert close(m @ [1.0, 0.0, 0.0, 1.0], [1.0, 3.0, 3.0, 1.0])
    assert close(f("Math.Matrix4x4.get_affine_translation")(m), [1.0, 2.0, 3.0])
    assert close(f("Math.Matrix4x4.get_affine_rotation")(m), q)
    scaled = m.copy()
    scaled[:3, :3] *= 2.5
    assert close(f("Math.Matrix4x4.get_affine_rotation")(scaled), q)
    rng = np.random.default_rng(6)
    for _ in range(50):
        q = random_unit_quat(rng)
        got = f("Math.Matrix4x4.get_affine_rotation")(f("Math.Matrix4x4.from_vec3_quat")(np.zeros(3), q))
        assert close(got, q if q[3] >= 0 else -q)
    with pytest.raises(NativeError):
        f("Math.Matrix4x4.get_affine_rotation")(np.zeros((4, 4)))


def test_line():
    line = f("Math.Line.from_points")([1.0, 1.0, 1.0], [4.0, 5.0, 1.0])
    assert isinstance(line, Line)
    assert f("Math.Line.length")(line) == 5.0


def test_inertia_symmetric_tensor(structs):
    t = f("Physics3D.Bodies.Inertia.symmetric_tensor")([1.0, 2.0, 3.0], 0.1, 0.2, 0.3)
    assert close(t, [[1.0, 0.1, 0.2], [0.1, 2.0, 0.3], [0.2, 0.3, 3.0]])
    assert close(t, t.T)
    assert structs["Math.Matrix3x3"].to_fields(t)["e12"] == 0.3


def test_elementary_transform_sequence_fkine():
    et = "Robotics.Kinematics.ElementaryTransform."
    ets = [f(et + "tz")(1.0), f(et + "Rz_free")(False), f(et + "tx")(2.0), f(et + "Ry_free")(True)]
    assert ets[1] == ElementaryTransform(type="Rz", free=True, flip=False)
    t = f(et + "fkine")(ets, [math.pi / 2, 0.0])
    assert close(t.position, [0.0, 2.0, 1.0])
    assert same_rotation(t.rotation, f("Math.Quat.angle_axis")(math.pi / 2, Z))
    t = f(et + "fkine")(ets, [0.0, math.pi / 2])  # flipped: -90 degrees about Y
    assert same_rotation(t.rotation, f("Math.Quat.angle_axis")(-math.pi / 2, Y))
    lower = f(et + "fkine")([ElementaryTransform(type="RZ", c=math.pi / 2)], [])
    assert same_rotation(lower.rotation, f("Math.Quat.angle_axis")(math.pi / 2, Z))
    with pytest.raises(NativeError, match="free joint"):
        f(et + "fkine")(ets, [0.0])
    with pytest.raises(NativeError, match="unknown type"):
        f(et + "fkine")([ElementaryTransform(type="rq")], [])


# ------------------------------------------------------------------------------------------------
# Math.Functions
# ------------------------------------------------------------------------------------------------

F = "Math.Functions."


def test_trigonometry():
    assert f(F + "sin")(math.pi / 2) == pytest.approx(1.0)
    assert f(F + "cos")(0) == 1.0
    assert f(F + "tan")(math.pi / 4) == pytest.approx(1.0)
    assert f(F + "arcsin")(1.0) == pytest.approx(math.pi / 2)
    assert f(F + "arccos")(-1.0) == pytest.approx(math.pi)
    assert f(F + "arccos")(1.0 + 1e-15) == 0.0  # clamped rounding noise
    assert f(F + "arctan")(1.0) == pytest.approx(math.pi / 4)
    assert f(F + "rad_to_deg")(math.pi) == pytest.approx(180.0)
    assert f(F + "deg_to_rad")(90) == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(
    "x, y, expected",
    [
        (1.0, 0.0, 0.0),
        (0.0, 1.0, math.pi / 2),
        (-1.0, 0.0, math.pi),
        (1.0, 1.0, math.pi / 4),
        (0.0, -2.0, -math.pi / 2),
    ],
)
def test_arctan2_follows_declared_parameter_order(x, y, expected):
    # declared arctan2(x: Real, y: Real): the angle of the point (x, y)
    assert f(F + "arctan2")(x, y) == pytest.approx(expected)


def test_sqrt_pow_inf():
    assert f(F + "sqrt")(16) == 4.0
    assert f(F + "pow")(2, 10) == 1024.0
    assert f(F + "pow")(-2.0, 3.0) == -8.0
    assert f(F + "pow")(4.0, 0.5) == 2.0
    assert f(F + "inf")() == math.inf
    assert f(F + "neg_inf")() == -math.inf


def test_round_floor_ceil_return_int():
    for name in ("round", "floor", "ceil"):
        assert type(f(F + name)(1.5)) is int
    assert [f(F + "round")(v) for v in (2.5, -2.5, 0.49, 1.5, -0.5)] == [3, -3, 0, 2, -1]
    assert f(F + "floor")(-1.2) == -2
    assert f(F + "ceil")(-1.2) == -1
    assert f(F + "ceil")(3) == 3


def test_list_functions():
    values = [4.0, 1.0, 2, 8.0]
    assert f(F + "mean")(values) == 3.75
    assert f(F + "median")(values) == 3.0
    assert f(F + "median")([5.0, 1.0, 3.0]) == 3.0
    assert f(F + "harmonic_mean")([1.0, 4.0, 4.0]) == 2.0
    assert f(F + "harmonic_mean")([0.0, 4.0]) == 0.0
    assert f(F + "min")(values) == 1.0
    assert f(F + "max")(values) == 8.0
    assert f(F + "sum")(values) == 15.0
    assert f(F + "sum")([]) == 0.0
    assert f(F + "sum")(np.array([0.1] * 10)) == 1.0  # fsum
    assert type(f(F + "max")([1, 2])) is float


def test_equals_approx():
    eq = f(F + "equals_approx")
    assert eq(1.0, 1.0 + 1e-9) is True
    assert eq(1.0, 1.001) is False
    assert eq(1e9, 1e9 + 1.0) is True  # relative for large values
    assert eq(0.0, 1e-7) is True
    assert eq(math.inf, math.inf) is True
    assert eq(math.inf, 1e300) is False


# ------------------------------------------------------------------------------------------------
# Operators and arithmetic
# ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "vt, a, b", [("Math.Vec2", [1.0, 2.0], [3.0, -1.0]), ("Math.Vec3", [1.0, 2.0, 3.0], [3.0, -1.0, 0.5])]
)
def test_vector_operators(vt, a, b):
    a, b = np.array(a), np.array(b)
    assert close(apply_operator("+", vt, a, vt, b), a + b)
    assert close(apply_operator("-", vt, a, vt, b), a - b)
    assert close(apply_operator("*", "Real", 2.0, vt, a), 2 * a)
    assert close(apply_operator("*", vt, a, "Real", 2.0), 2 * a)
    assert close(apply_operator("/", vt, a, "Real", 4.0), a / 4)
    dot = apply_operator("*", vt, a, vt, b)
    assert type(dot) is float and dot == pytest.approx(float(np.dot(a, b)))
    assert close(apply_operator("-", vt, a), -a)


def test_int_promotion_and_primitive_arithmetic():
    v = np.array([1.0, 2.0, 3.0])
    assert close(apply_operator("*", "Int", 2, "Math.Vec3", v), 2 * v)
    assert close(apply_operator("/", "Math.Vec3", v, "Int", 2), v / 2)
    r = apply_operator("/", "Int", 1, "Int", 2)
    assert r == 0.5 and type(r) is float  # Int / Int is float division
    r = apply_operator("+", "Int", 1, "Int", 2)
    assert r == 3 and type(r) is int
    assert type(apply_operator("*", "Int", 3, "Int", 4)) is int
    assert type(apply_operator("-", "Int", 3)) is int and apply_operator("-", "Int", 3) == -3
    r = apply_operator("+", "Real", 1.5, "Int", 2)
    assert r == 3.5 and type(r) is float
    assert apply_operator("-", "Real", 2.5) == -2.5
    assert apply_operator("-", "Int", 7, "Real", 0.5) == 6.5
    assert apply_operator("*", "Real", 1.5, "Real", 2.0) == 3.0


def test_primitive_result_type():
    assert primitive_result_type("/", "Int", "Int") == "Real"
    assert primitive_result_type("+", "Int", "Int") == "Int"
    assert primitive_result_type("*", "Int", "Real") == "Real"
    assert primitive_result_type("-", "Int", None) == "Int"
    assert primitive_result_type("-", "Real", None) == "Real"
    assert primitive_result_type("+", "Math.Vec3", "Math.Vec3") is None
    assert primitive_result_type("*", "Int", None) is None


def test_unknown_operator_raises():
    with pytest.raises(NativeError, match="no operator"):
        apply_operator("*", "Math.Quat", ID_Q, "Math.Vec3", X)  # use q.rotate(v)
    with pytest.raises(NativeError):
        apply_operator("+", "Bool", True, "Bool", False)
    with pytest.raises(NativeError):
        apply_operator("+", "Int", True, "Int", 1)  # a Bool posing as Int


# ------------------------------------------------------------------------------------------------
# Errors
# ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name, args, match",
    [
        ("Math.Vec3.normal", ([0.0, 0.0, 0.0],), "zero vector"),
        ("Math.Vec2.normal", ([0.0, 0.0],), "zero vector"),
        ("Math.Quat.normal", ([0.0, 0.0, 0.0, 0.0],), "zero"),
        ("Math.Quat.inverse", ([0.0, 0.0, 0.0, 0.0],), "zero quaternion"),
        ("Math.Quat.rotate", ([0.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), "zero"),
        ("Math.Quat.angle_axis", (1.0, [0.0, 0.0, 0.0]), "zero vector"),
        ("Math.Quat.from_to", ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]), "zero vector"),
        ("Math.Quat.to_euler_angles_xyzs", ([0.0, 0.0, 0.0, 0.0],), "invalid quaternion"),
        ("Math.AffineTransform.from_axes", ([0.0, 0.0, 1.0], [0.0, 0.0, -2.0], [0.0, 0.0, 0.0]), "parallel"),
        ("Math.AffineTransform.from_axes", ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]), "zero vector"),
        ("Math.Vec3.angle_between_vectors", ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]), "zero vector"),
        ("Math.Functions.sqrt", (-1.0,), "negative"),
        ("Math.Functions.arccos", (1.5,), r"outside \[-1, 1\]"),
        ("Math.Functions.arcsin", (-2.0,), r"outside \[-1, 1\]"),
        ("Math.Functions.pow", (0.0, -1.0), "negative power"),
        ("Math.Functions.pow", (-8.0, 1.0 / 3.0), "non-integer exponent"),
        ("Math.Functions.pow", (10.0, 400.0), "overflow"),
        ("Math.Functions.mean", ([],), "empty"),
        ("Math.Functions.median", ([],), "empty"),
        ("Math.Functions.min", ([],), "empty"),
        ("Math.Functions.harmonic_mean", ([1.0, -1.0],), "negative"),
        ("Math.Functions.round", (math.inf,), "Int"),
        ("Math.Functions.floor", (math.nan,), "Int"),
        ("Math.Functions.sin", ("one",), "Real"),
        ("Math.Functions.sin", (True,), "Real"),
        ("Math.Vec3.cross", ([1.0, 0.0], [0.0, 1.0, 0.0]), "shape"),
        ("Math.Matrix3x3.from_rows", ([1.0, 2.0], [1.0, 2.0, 3.0], [1.0, 2.0, 3.0]), "3 elements"),
        ("Math.AffineTransform.inverse", ([0.0, 0.0, 0.0],), "Transform"),
        ("Math.Vec3.cross", ([1.0, 0.0, 0.0],), "takes 2 argument"),
        ("Math.Vec3.X_AXIS", (1.0,), "takes 0 argument"),
    ],
)
def test_domain_errors(name, args, match):
    with pytest.raises(NativeError, match=match):
        FUNCTIONS[name](*args)


@pytest.mark.parametrize(
    "op, lt, lhs, rt, rhs",
    [
        ("/", "Math.Vec3", [1.0, 2.0, 3.0], "Real", 0.0),
        ("/", "Math.Vec2", [1.0, 2.0], "Int", 0),
        ("/", "Math.Quat", [0.0, 0.0, 0.0, 1.0], "Real", 0.0),
        ("/", "Math.Quat", [0.0, 0.0, 0.0, 1.0], "Math.Quat", [0.0, 0.0, 0.0, 0.0]),
        ("/", "Real", 1.0, "Real", 0.0),
        ("/", "Int", 1, "Int", 0),
    ],
)
def test_division_by_zero_raises(op, lt, lhs, rt, rhs):
    with pytest.raises(NativeError):
        apply_operator(op, lt, lhs, rt, rhs)


def test_no_numpy_warnings_escape():
    big = np.array([1e308, 1e308, 1e308])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(NativeError):
            apply_operator("*", "Math.Vec3", big, "Real", 10.0)
        with pytest.raises(NativeError):
            apply_operator("+", "Math.Vec3", big, "Math.Vec3", big)
        with pytest.raises(NativeError):
            f("Math.Vec3.normal")([math.inf, 0.0, 0.0])
        with pytest.raises(NativeError):
            f("Math.Vec3.dot")([math.inf, 0.0, 0.0], [0.0, 0.0, 0.0])  # inf * 0
        tiny = np.array([1e-300, 0.0, 0.0])
        assert close(f("Math.Vec3.normal")(tiny), X)  # underflow is fine


def test_call_helper():
    assert call("Math.Functions.sqrt", 9.0) == 3.0
    with pytest.raises(NativeError, match="not supported"):
        call("Physics3D.System.resnap", object())
    with pytest.raises(NativeError, match="unknown native"):
        call("Math.Vec3.frobnicate")


# ------------------------------------------------------------------------------------------------
# Codecs and type_of
# ------------------------------------------------------------------------------------------------


def test_codec_round_trips(structs):
    rng = np.random.default_rng(7)
    samples = {
        "Math.Vec2": rng.normal(size=2),
        "Math.Vec3": rng.normal(size=3),
        "Math.Quat": rng.normal(size=4),
        "Math.Matrix3x3": rng.normal(size=(3, 3)),
        "Math.Matrix4x4": rng.normal(size=(4, 4)),
        "Math.AffineTransform": Transform(rng.normal(size=3), random_unit_quat(rng)),
        "Math.Line": Line(rng.normal(size=3), rng.normal(size=3)),
        "Robotics.Kinematics.ElementaryTransform": ElementaryTransform("Ry", 0.5, True, True),
    }
    assert set(samples) == set(structs)
    for type_name, value in samples.items():
        codec = structs[type_name]
        fields = codec.to_fields(value)
        assert list(fields) == list(codec.fields)
        back = codec.from_fields(fields)
        if isinstance(value, np.ndarray):
            assert close(back, value, 0.0) and back.shape == value.shape
        else:
            assert back == value
        assert type_of(back) == type_name


def test_codec_field_values(structs):
    q = structs["Math.Quat"].to_fields(np.array([0.1, 0.2, 0.3, 0.9]))
    assert q == {"x": 0.1, "y": 0.2, "z": 0.3, "w": 0.9}
    assert all(type(v) is float for v in q.values())
    m = structs["Math.Matrix3x3"].to_fields(np.arange(9.0).reshape(3, 3))
    assert m["e01"] == 1.0 and m["e10"] == 3.0 and m["e22"] == 8.0
    t = structs["Math.AffineTransform"].from_fields({"position": np.array([1.0, 2.0, 3.0])})
    assert close(t.rotation, ID_Q)
    assert structs["Math.Vec3"].from_fields({"x": 1, "z": 2, "extra": "ignored"}).tolist() == [1.0, 0.0, 2.0]


def test_codec_defaults(structs):
    assert close(structs["Math.Vec3"].default(), np.zeros(3))
    assert close(structs["Math.Quat"].default(), ID_Q)
    assert close(structs["Math.Matrix3x3"].default(), np.eye(3))
    assert structs["Math.AffineTransform"].default() == Transform(np.zeros(3), ID_Q)
    with pytest.raises(NativeError, match="missing value for field 'e00'"):
        structs["Math.Matrix4x4"].default()


def test_codec_errors(structs):
    with pytest.raises(NativeError):
        structs["Math.Vec3"].from_fields({"x": "1"})
    with pytest.raises(NativeError):
        structs["Math.AffineTransform"].from_fields({"position": np.zeros(2)})
    with pytest.raises(NativeError):
        structs["Math.AffineTransform"].to_fields(np.zeros(3))


def test_type_of():
    assert type_of(True) == "Bool"
    assert type_of(3) == "Int"
    assert type_of(3.0) == "Real"
    assert type_of("s") == "String"
    assert type_of(np.zeros(2)) == "Math.Vec2"
    assert type_of(np.zeros(3)) == "Math.Vec3"
    assert type_of(np.zeros(4)) == "Math.Quat"
    assert type_of(np.eye(3)) == "Math.Matrix3x3"
    assert type_of(np.eye(4)) == "Math.Matrix4x4"
    assert type_of(Transform(np.zeros(3), ID_Q)) == "Math.AffineTransform"
    assert type_of([1.0]) is None


def test_import_is_cheap():
    import subprocess
    import sys

    code = (
        "import sys, plxtools.model.natives; "
        "print(sorted(m for m in ('scipy', 'mujoco', 'pygls') if m in sys.modules))"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=root)
    assert out.stdout.strip() == "[]"


def test_codecs_belong_to_their_program(structs, official_struct_types):
    """Two programs never share codecs: one that declares no math types has none of them, and the
    bundles' program keeps its own (they used to live in one module-level table)."""
    from plxtools.model.natives import struct_types

    class NoMath:
        def lookup_outside_visibility(self, parts):
            return None

    bare = struct_types(NoMath())
    assert set(bare) == {"Robotics.Kinematics.ElementaryTransform"}
    assert "Math.Vec3" in struct_types(official_struct_types)
    assert struct_types(official_struct_types) is structs
