"""Python/numpy implementations of the natively implemented OpenPLX functions and operators.

The OpenPLX bundles declare ``fn``, ``static fn`` and ``operator`` signatures only; the runtime
implements them natively.  This module is the evaluator's implementation, keyed by qualified name.
Signatures (parameter and return types) still come from the bundle sources; this module only
computes values.  It imports numpy and the standard library only.

Value representation (the contract with the evaluator)
-------------------------------------------------------
=========================================  =====================================================
OpenPLX type                               Python value
=========================================  =====================================================
``Real`` / ``Int`` / ``Bool`` / ``String``  ``float`` / ``int`` / ``bool`` / ``str``
``Math.Vec2`` / ``Math.Vec3``              float ndarray, shape (2,) / (3,)
``Math.Quat``                              float ndarray, shape (4,), order **(x, y, z, w)**
``Math.Matrix3x3`` / ``Math.Matrix4x4``    float ndarray, shape (3, 3) / (4, 4), ``m[row, col]``
``Math.AffineTransform``                   :class:`Transform` (position (3,), rotation (4,) xyzw)
``Math.Line``                              :class:`Line` (start (3,), end (3,))
``Robotics.Kinematics.ElementaryTransform`` :class:`ElementaryTransform`
``Real[]``                                 ``list[float]``
=========================================  =====================================================

Functions accept any numeric Python/numpy scalar for ``Real`` (``Int`` is promoted) and any array-like
of the right shape for vectors and matrices.  ``Real`` results are plain ``float``; ``Int`` results are
``int``; ``Bool`` results are ``bool``.  Instance methods take the receiver as their first argument:
``FUNCTIONS["Math.Vec3.cross"](a, b)`` is ``a.cross(b)``.

Conventions
-----------
* **Quaternions** are Hamilton quaternions stored (x, y, z, w).  ``q.rotate(v)`` is ``q v q*`` (an active
  rotation; the quaternion is normalised first).  ``q1 * q2`` is the Hamilton product, so
  ``(q1 * q2).rotate(v) == q1.rotate(q2.rotate(v))`` (apply ``q2`` first).  ``q1 / q2`` is
  ``q1 * q2.inverse()``.  Quaternions built from matrices have ``w >= 0``.
* **Euler angles** ``from_euler_angles_<ijk><s|r>(alpha, beta, gamma)`` follow Shoemake's naming (the
  bundle lists the same 24 orders, in the same order, as Graphics Gems IV "Euler Angle Conversion"):
  ``s`` = static (extrinsic) axes, rotate ``alpha`` about world ``i``, then ``beta`` about world ``j``,
  then ``gamma`` about world ``k``: ``R = R_k(gamma) R_j(beta) R_i(alpha)``;
  ``r`` = rotating (intrinsic) axes, rotate ``alpha`` about ``i``, then ``beta`` about the new ``j``, then
  ``gamma`` about the newest ``k``: ``R = R_i(alpha) R_j(beta) R_k(gamma)``.  So ``zyxr(a, b, c)`` equals
  ``xyzs(c, b, a)``, as in Shoemake.  ``to_euler_angles_*`` returns ``Vec3(alpha, beta, gamma)`` with
  alpha and gamma in [-pi, pi], beta in [-pi/2, pi/2] (Tait-Bryan, e.g. ``xyz``) or [0, pi] (proper Euler,
  e.g. ``zxz``).  At gimbal lock (beta at the end of its range) gamma is set to 0 and alpha carries the
  rotation.  ``from_euler_angles`` / ``to_euler_angles`` alias ``xyzs``.
* **AffineTransform** ``T = (p, q)`` maps a local point ``x`` to ``q.rotate(x) + p``.  ``T1 * T2`` is the
  composition ``x -> T1(T2(x))`` (parent * child).  ``from_axes(new_Z, new_X, position)``: z = new_Z
  normalised, x = new_X with its z component removed, normalised, y = z x x.  Raises when new_Z is zero or
  new_X is (anti)parallel to new_Z.
* **get_orthogonal_unit_vector(v)**: take the world axis e_i with the smallest ``|v_i|`` (ties: lowest
  index, x before y before z), remove its component along v (Gram-Schmidt) and normalise.  So Z -> X,
  X -> Y, Y -> X.  The zero vector gives X (1, 0, 0) and does not raise.
* **Division**: ``Int / Int`` is float division and returns a ``Real`` (OpenPLX does not document this).
  ``Int + - * Int`` stay ``Int``; a mix of ``Int`` and ``Real`` gives ``Real``.  Division by zero raises.
* **Math.Functions.arctan2(x, y)** follows the declared parameter names: the angle of the point (x, y),
  i.e. C's ``atan2(y, x)``.  ``round`` rounds half away from zero (C ``round``).  ``equals_approx`` is
  ``|value - ref| <= 1e-6 * max(1, |ref|)``.  ``arcsin``/``arccos`` clamp arguments within 1e-12 of
  [-1, 1] and raise beyond.

Errors
------
Domain errors (normalising a zero vector, sqrt of a negative, arccos out of range, division by zero, wrong
argument count or shape, numerical overflow) raise :class:`NativeError`.  numpy floating-point warnings
never escape: every native runs under ``np.errstate`` and FP errors become :class:`NativeError`.

Functions that need the object graph or the runtime (``Physics3D.System.resnap``, ``on_init`` hooks, the
signal plumbing...) are listed in :data:`UNSUPPORTED` instead of :data:`FUNCTIONS`.
"""

from __future__ import annotations

import functools
import math
import weakref
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "NativeError",
    "Transform",
    "Line",
    "ElementaryTransform",
    "StructCodec",
    "SHAPES",
    "struct_types",
    "FUNCTIONS",
    "OPERATORS",
    "UNSUPPORTED",
    "EULER_ORDERS",
    "EQUALS_APPROX_TOL",
    "apply_operator",
    "call",
    "type_of",
    "primitive_result_type",
]


class NativeError(Exception):
    """A native function or operator was called outside its domain (or with bad arguments)."""


# --------------------------------------------------------------------------------------------------
# Value classes
# --------------------------------------------------------------------------------------------------


def _frozen_array(value: Any, shape: tuple[int, ...], what: str) -> np.ndarray:
    arr = _array(value, shape, what).copy()
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class Transform:
    """``Math.AffineTransform``: maps a local point x to ``rotate(rotation, x) + position``.

    ``rotation`` is a quaternion in (x, y, z, w) order.  Both arrays are read-only copies.
    """

    position: np.ndarray
    rotation: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _frozen_array(self.position, (3,), "Transform.position"))
        object.__setattr__(self, "rotation", _frozen_array(self.rotation, (4,), "Transform.rotation"))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Transform):
            return NotImplemented
        return bool(
            np.array_equal(self.position, other.position) and np.array_equal(self.rotation, other.rotation)
        )

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"Transform(position={self.position.tolist()}, rotation={self.rotation.tolist()})"


@dataclass(frozen=True, eq=False)
class Line:
    """``Math.Line``: a segment from ``start`` to ``end`` (read-only Vec3 arrays)."""

    start: np.ndarray
    end: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _frozen_array(self.start, (3,), "Line.start"))
        object.__setattr__(self, "end", _frozen_array(self.end, (3,), "Line.end"))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Line):
            return NotImplemented
        return bool(np.array_equal(self.start, other.start) and np.array_equal(self.end, other.end))

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"Line(start={self.start.tolist()}, end={self.end.tolist()})"


@dataclass(frozen=True)
class ElementaryTransform:
    """``Robotics.Kinematics.ElementaryTransform``: one step of an elementary transform sequence.

    ``type`` is one of tx, ty, tz, Rx, Ry, Rz (case-insensitive); ``c`` is the constant value of a fixed
    step; ``free`` marks a joint variable and ``flip`` negates it.
    """

    type: str = "tx"
    c: float = 0.0
    free: bool = False
    flip: bool = False


# --------------------------------------------------------------------------------------------------
# Argument coercion
# --------------------------------------------------------------------------------------------------

_NUMBER_TYPES = (int, float, np.integer, np.floating)


def _is_number(x: Any) -> bool:
    return isinstance(x, _NUMBER_TYPES) and not isinstance(x, (bool, np.bool_))


def _real(x: Any, what: str = "argument") -> float:
    if not _is_number(x):
        raise NativeError(f"{what} must be a Real, got {type(x).__name__}")
    return float(x)


def _bool(x: Any, what: str = "argument") -> bool:
    if not isinstance(x, (bool, np.bool_)):
        raise NativeError(f"{what} must be a Bool, got {type(x).__name__}")
    return bool(x)


def _array(x: Any, shape: tuple[int, ...], what: str) -> np.ndarray:
    if isinstance(x, (str, bytes, Transform, Line)) or x is None:
        raise NativeError(f"{what} must be an array of shape {shape}, got {type(x).__name__}")
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise NativeError(f"{what} must be an array of shape {shape}: {exc}") from None
    if arr.shape != shape:
        raise NativeError(f"{what} must have shape {shape}, got {arr.shape}")
    return arr


def _vec2(x: Any, what: str = "Vec2 argument") -> np.ndarray:
    return _array(x, (2,), what)


def _vec3(x: Any, what: str = "Vec3 argument") -> np.ndarray:
    return _array(x, (3,), what)


def _quat(x: Any, what: str = "Quat argument") -> np.ndarray:
    return _array(x, (4,), what)


def _mat3(x: Any, what: str = "Matrix3x3 argument") -> np.ndarray:
    return _array(x, (3, 3), what)


def _mat4(x: Any, what: str = "Matrix4x4 argument") -> np.ndarray:
    return _array(x, (4, 4), what)


def _transform(x: Any, what: str = "AffineTransform argument") -> Transform:
    if not isinstance(x, Transform):
        raise NativeError(f"{what} must be a Transform, got {type(x).__name__}")
    return x


def _reals(x: Any, what: str = "Real[] argument") -> list[float]:
    if isinstance(x, np.ndarray):
        if x.ndim != 1:
            raise NativeError(f"{what} must be one-dimensional, got shape {x.shape}")
        x = x.tolist()
    if isinstance(x, (str, bytes)) or not isinstance(x, Sequence):
        raise NativeError(f"{what} must be a list of Real, got {type(x).__name__}")
    return [_real(v, f"{what} element") for v in x]


def _row(x: Any, n: int, what: str) -> np.ndarray:
    values = _reals(x, what)
    if len(values) != n:
        raise NativeError(f"{what} must have {n} elements, got {len(values)}")
    return np.array(values, dtype=float)


# --------------------------------------------------------------------------------------------------
# Core maths (plain helpers, no registry)
# --------------------------------------------------------------------------------------------------

_IDENTITY_QUAT = (0.0, 0.0, 0.0, 1.0)
_ACOS_CLAMP_TOL = 1e-12
EQUALS_APPROX_TOL = 1e-6
"""Tolerance of ``Math.Functions.equals_approx``: ``|value - ref| <= tol * max(1, |ref|)``."""


def _norm(v: np.ndarray) -> float:
    return math.hypot(*v.tolist())  # no overflow or underflow in the squares


def _normalised(v: np.ndarray, what: str) -> np.ndarray:
    n = _norm(v)
    if not math.isfinite(n):
        raise NativeError(f"{what}: cannot normalise a non-finite vector {v.tolist()}")
    if n == 0.0:
        raise NativeError(f"{what}: cannot normalise the zero vector")
    return v / n


def _qmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product a*b, both (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array(
        [
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ]
    )


def _qconj(q: np.ndarray) -> np.ndarray:
    return np.array([-q[0], -q[1], -q[2], q[3]])


def _qinverse(q: np.ndarray, what: str) -> np.ndarray:
    n = _norm(q)
    if n == 0.0:
        raise NativeError(f"{what}: the zero quaternion has no inverse")
    return _qconj(q) / n / n


def _qrotate(q: np.ndarray, v: np.ndarray, what: str = "Math.Quat.rotate") -> np.ndarray:
    u = _normalised(q, what)
    qv = u[:3]
    t = 2.0 * np.cross(qv, v)
    return v + u[3] * t + np.cross(qv, t)


def _axis_quat(axis: int, angle: float) -> np.ndarray:
    q = np.zeros(4)
    q[axis] = math.sin(angle / 2.0)
    q[3] = math.cos(angle / 2.0)
    return q


def _quat_to_matrix(q: np.ndarray, what: str) -> np.ndarray:
    x, y, z, w = _normalised(q, what)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def _matrix_to_quat(m: np.ndarray) -> np.ndarray:
    """Unit quaternion (x, y, z, w), w >= 0, of a rotation matrix (Shepperd's method)."""
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0.0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = np.array([(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s])
    elif m[0, 0] >= m[1, 1] and m[0, 0] >= m[2, 2]:
        s = math.sqrt(max(1.0 + m[0, 0] - m[1, 1] - m[2, 2], 0.0)) * 2.0
        q = np.array([0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s])
    elif m[1, 1] >= m[2, 2]:
        s = math.sqrt(max(1.0 + m[1, 1] - m[0, 0] - m[2, 2], 0.0)) * 2.0
        q = np.array([(m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s])
    else:
        s = math.sqrt(max(1.0 + m[2, 2] - m[0, 0] - m[1, 1], 0.0)) * 2.0
        q = np.array([(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s])
    q = q / _norm(q)
    return -q if q[3] < 0.0 else q


def _orthogonal_unit(v: np.ndarray) -> np.ndarray:
    n = _norm(v)
    if not math.isfinite(n):
        raise NativeError(f"Math.Vec3.get_orthogonal_unit_vector: non-finite vector {v.tolist()}")
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0])
    u = v / n
    i = int(np.argmin(np.abs(u)))  # first index wins ties
    e = np.zeros(3)
    e[i] = 1.0
    w = e - u[i] * u  # |w| >= sqrt(2/3)
    return w / _norm(w)


def _from_to(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ua = _normalised(a, "Math.Quat.from_to (from)")
    ub = _normalised(b, "Math.Quat.from_to (to)")
    d = float(np.dot(ua, ub))
    if d <= -1.0 + 1e-12:  # antiparallel: half turn about a deterministic orthogonal axis
        axis = _orthogonal_unit(ua)
        return np.array([axis[0], axis[1], axis[2], 0.0])
    c = np.cross(ua, ub)
    q = np.array([c[0], c[1], c[2], 1.0 + d])
    return q / _norm(q)


def _t_compose(a: Transform, b: Transform) -> Transform:
    return Transform(a.position + _qrotate(a.rotation, b.position), _qmul(a.rotation, b.rotation))


def _t_inverse(t: Transform) -> Transform:
    inv = _qinverse(t.rotation, "Math.AffineTransform.inverse")
    return Transform(-_qrotate(inv, t.position), inv)


def _from_axes(new_z: np.ndarray, new_x: np.ndarray, position: np.ndarray) -> Transform:
    z = _normalised(new_z, "Math.AffineTransform.from_axes (new_Z)")
    x = new_x - float(np.dot(new_x, z)) * z
    nx = _norm(x)
    if not nx > 1e-12 * _norm(new_x):  # zero, or (anti)parallel to new_Z up to rounding
        raise NativeError(
            "Math.AffineTransform.from_axes: new_X must not be zero or parallel to new_Z "
            f"(new_Z={new_z.tolist()}, new_X={new_x.tolist()})"
        )
    x = x / nx
    y = np.cross(z, x)
    return Transform(position, _matrix_to_quat(np.column_stack([x, y, z])))


# ---- Euler angles --------------------------------------------------------------------------------

_AXIS_INDEX = {"x": 0, "y": 1, "z": 2}
EULER_ORDERS: tuple[str, ...] = tuple(
    f"{i}{j}{k}{frame}"
    for frame in "sr"
    for i in "xyz"
    for j in "xyz"
    if j != i
    for k in "xyz"
    if k != j
)
"""The 24 Euler orders, e.g. ``"xyzs"`` (static/extrinsic) and ``"zyxr"`` (rotating/intrinsic)."""


def _quat_from_euler(order: str, alpha: float, beta: float, gamma: float) -> np.ndarray:
    i, j, k = (_AXIS_INDEX[c] for c in order[:3])
    qa, qb, qc = _axis_quat(i, alpha), _axis_quat(j, beta), _axis_quat(k, gamma)
    if order[3] == "s":
        return _qmul(qc, _qmul(qb, qa))
    return _qmul(qa, _qmul(qb, qc))


def _wrap_angle(a: float) -> float:
    if a > math.pi:
        a -= 2.0 * math.pi
    elif a < -math.pi:
        a += 2.0 * math.pi
    return a


def _euler_from_quat(order: str, q: np.ndarray) -> np.ndarray:
    """Inverse of :func:`_quat_from_euler` for any of the 24 orders.

    Direct quaternion method of Bernardes & Viollet (PLOS ONE 2022, doi:10.1371/journal.pone.0276302).
    At gimbal lock gamma is set to zero and alpha carries the whole rotation.
    """
    n = _norm(q)
    if n == 0.0 or not math.isfinite(n):
        raise NativeError(f"Math.Quat.to_euler_angles_{order}: invalid quaternion {q.tolist()}")
    q = q / n
    extrinsic = order[3] == "s"
    seq = order[:3] if extrinsic else order[2::-1]
    i, j, k = (_AXIS_INDEX[c] for c in seq)
    symmetric = i == k
    if symmetric:
        k = 3 - i - j
    sign = (i - j) * (j - k) * (k - i) // 2  # +1 for an even permutation, -1 for an odd one
    if symmetric:
        a, b, c, d = q[3], q[i], q[j], q[k] * sign
    else:
        a, b, c, d = q[3] - q[j], q[i] + q[k] * sign, q[j] + q[3], q[k] * sign - q[i]
    angles = [0.0, 2.0 * math.atan2(math.hypot(c, d), math.hypot(a, b)), 0.0]
    eps = 1e-9
    half_sum = math.atan2(b, a)
    half_diff = math.atan2(d, c)
    if abs(angles[1]) <= eps or abs(angles[1] - math.pi) <= eps:
        # gimbal lock: only the sum (or difference) of the outer angles is defined; gamma := 0
        free = 0 if extrinsic else 2
        if abs(angles[1]) <= eps:
            angles[free] = 2.0 * half_sum
        else:
            angles[free] = 2.0 * half_diff * (-1.0 if extrinsic else 1.0)
    else:
        angles[0] = half_sum - half_diff
        angles[2] = half_sum + half_diff
    if not symmetric:
        angles[2] *= sign
        angles[1] -= math.pi / 2.0
    if not extrinsic:
        angles[0], angles[2] = angles[2], angles[0]
    return np.array([_wrap_angle(float(x)) for x in angles])


# --------------------------------------------------------------------------------------------------
# Registry
# --------------------------------------------------------------------------------------------------

FUNCTIONS: dict[str, Callable[..., Any]] = {}
"""Native functions by qualified name.  Instance methods take the receiver first."""

_FP_ERRORS = (FloatingPointError, OverflowError, ZeroDivisionError, ValueError)


def _guard(name: str, fn: Callable[..., Any], arity: int) -> Callable[..., Any]:
    """Check the argument count and turn floating-point trouble into NativeError."""

    @functools.wraps(fn)
    def native(*args: Any) -> Any:
        if len(args) != arity:
            raise NativeError(f"{name} takes {arity} argument(s), {len(args)} given")
        with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
            try:
                return fn(*args)
            except NativeError:
                raise
            except _FP_ERRORS as exc:
                raise NativeError(f"{name}: {exc}") from None

    native.arity = arity  # type: ignore[attr-defined]
    native.qualified_name = name  # type: ignore[attr-defined]
    return native


def _native(name: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    def register(fn: Callable[..., Any]) -> Callable[..., Any]:
        if name in FUNCTIONS:
            raise RuntimeError(f"native {name} registered twice")
        FUNCTIONS[name] = _guard(name, fn, fn.__code__.co_argcount)
        return fn

    return register


# ---- Math.Vec2 -----------------------------------------------------------------------------------


@_native("Math.Vec2.X_AXIS")
def _vec2_x_axis() -> np.ndarray:
    return np.array([1.0, 0.0])


@_native("Math.Vec2.Y_AXIS")
def _vec2_y_axis() -> np.ndarray:
    return np.array([0.0, 1.0])


@_native("Math.Vec2.from_xy")
def _vec2_from_xy(x: Any, y: Any) -> np.ndarray:
    return np.array([_real(x, "x"), _real(y, "y")])


@_native("Math.Vec2.length")
def _vec2_length(v: Any) -> float:
    return _norm(_vec2(v))


@_native("Math.Vec2.normal")
def _vec2_normal(v: Any) -> np.ndarray:
    return _normalised(_vec2(v), "Math.Vec2.normal")


@_native("Math.Vec2.dot")
def _vec2_dot(v: Any, rhs: Any) -> float:
    return float(np.dot(_vec2(v), _vec2(rhs)))


# ---- Math.Vec3 -----------------------------------------------------------------------------------


@_native("Math.Vec3.X_AXIS")
def _vec3_x_axis() -> np.ndarray:
    return np.array([1.0, 0.0, 0.0])


@_native("Math.Vec3.Y_AXIS")
def _vec3_y_axis() -> np.ndarray:
    return np.array([0.0, 1.0, 0.0])


@_native("Math.Vec3.Z_AXIS")
def _vec3_z_axis() -> np.ndarray:
    return np.array([0.0, 0.0, 1.0])


@_native("Math.Vec3.from_xyz")
def _vec3_from_xyz(x: Any, y: Any, z: Any) -> np.ndarray:
    return np.array([_real(x, "x"), _real(y, "y"), _real(z, "z")])


@_native("Math.Vec3.length")
def _vec3_length(v: Any) -> float:
    return _norm(_vec3(v))


@_native("Math.Vec3.normal")
def _vec3_normal(v: Any) -> np.ndarray:
    return _normalised(_vec3(v), "Math.Vec3.normal")


@_native("Math.Vec3.dot")
def _vec3_dot(v: Any, rhs: Any) -> float:
    return float(np.dot(_vec3(v), _vec3(rhs)))


@_native("Math.Vec3.cross")
def _vec3_cross(v: Any, rhs: Any) -> np.ndarray:
    return np.cross(_vec3(v), _vec3(rhs))


@_native("Math.Vec3.get_orthogonal_unit_vector")
def _vec3_orthogonal(v: Any) -> np.ndarray:
    return _orthogonal_unit(_vec3(v))


@_native("Math.Vec3.angle_between_vectors")
def _vec3_angle_between(vector1: Any, vector2: Any, rot_vector: Any) -> float:
    """Signed angle from vector1 to vector2 in [-pi, pi], positive counter-clockwise about rot_vector."""
    a, b, r = _vec3(vector1, "vector1"), _vec3(vector2, "vector2"), _vec3(rot_vector, "rot_vector")
    for v, label in ((a, "vector1"), (b, "vector2"), (r, "rot_vector")):
        if _norm(v) == 0.0:
            raise NativeError(f"Math.Vec3.angle_between_vectors: {label} is the zero vector")
    c = np.cross(a, b)
    angle = math.atan2(_norm(c), float(np.dot(a, b)))
    return -angle if float(np.dot(c, r)) < 0.0 else angle


# ---- Math.Quat -----------------------------------------------------------------------------------


@_native("Math.Quat.rotate")
def _quat_rotate(q: Any, v: Any) -> np.ndarray:
    return _qrotate(_quat(q), _vec3(v))


@_native("Math.Quat.conj")
def _quat_conj(q: Any) -> np.ndarray:
    return _qconj(_quat(q))


@_native("Math.Quat.inverse")
def _quat_inverse(q: Any) -> np.ndarray:
    return _qinverse(_quat(q), "Math.Quat.inverse")


@_native("Math.Quat.angle_axis")
def _quat_angle_axis(angle: Any, axis: Any) -> np.ndarray:
    a = _real(angle, "angle")
    u = _normalised(_vec3(axis, "axis"), "Math.Quat.angle_axis (axis)")
    s = math.sin(a / 2.0)
    return np.array([u[0] * s, u[1] * s, u[2] * s, math.cos(a / 2.0)])


@_native("Math.Quat.from_to")
def _quat_from_to(from_: Any, to: Any) -> np.ndarray:
    return _from_to(_vec3(from_, "from"), _vec3(to, "to"))


@_native("Math.Quat.normal")
def _quat_normal(q: Any) -> np.ndarray:
    return _normalised(_quat(q), "Math.Quat.normal")


@_native("Math.Quat.from_xyzw")
def _quat_from_xyzw(x: Any, y: Any, z: Any, w: Any) -> np.ndarray:
    return np.array([_real(x, "x"), _real(y, "y"), _real(z, "z"), _real(w, "w")])


def _register_euler(order: str, suffix: str) -> None:
    def from_euler(alpha: Any, beta: Any, gamma: Any) -> np.ndarray:
        return _quat_from_euler(order, _real(alpha, "alpha"), _real(beta, "beta"), _real(gamma, "gamma"))

    def to_euler(q: Any) -> np.ndarray:
        return _euler_from_quat(order, _quat(q))

    _native(f"Math.Quat.from_euler_angles{suffix}")(from_euler)
    _native(f"Math.Quat.to_euler_angles{suffix}")(to_euler)


for _order in EULER_ORDERS:
    _register_euler(_order, "_" + _order)
_register_euler("xyzs", "")  # documented alias
del _order


# ---- Math.Matrix3x3 / Math.Matrix4x4 -------------------------------------------------------------


@_native("Math.Matrix3x3.from_row_major")
def _m3_from_row_major(r0c0, r0c1, r0c2, r1c0, r1c1, r1c2, r2c0, r2c1, r2c2) -> np.ndarray:  # noqa: ANN001
    values = [r0c0, r0c1, r0c2, r1c0, r1c1, r1c2, r2c0, r2c1, r2c2]
    return np.array([_real(v, "matrix element") for v in values]).reshape(3, 3)


@_native("Math.Matrix3x3.from_rows")
def _m3_from_rows(r0: Any, r1: Any, r2: Any) -> np.ndarray:
    return np.vstack([_row(r, 3, f"row {i}") for i, r in enumerate((r0, r1, r2))])


@_native("Math.Matrix3x3.from_columns")
def _m3_from_columns(c0: Any, c1: Any, c2: Any) -> np.ndarray:
    return np.column_stack([_row(c, 3, f"column {i}") for i, c in enumerate((c0, c1, c2))])


@_native("Math.Matrix3x3.diag")
def _m3_diag(x: Any, y: Any, z: Any) -> np.ndarray:
    return np.diag([_real(x, "x"), _real(y, "y"), _real(z, "z")])


@_native("Math.Matrix4x4.from_row_major")
def _m4_from_row_major(  # noqa: ANN001
    r0c0, r0c1, r0c2, r0c3, r1c0, r1c1, r1c2, r1c3, r2c0, r2c1, r2c2, r2c3, r3c0, r3c1, r3c2, r3c3
) -> np.ndarray:
    values = [r0c0, r0c1, r0c2, r0c3, r1c0, r1c1, r1c2, r1c3, r2c0, r2c1, r2c2, r2c3, r3c0, r3c1, r3c2, r3c3]
    return np.array([_real(v, "matrix element") for v in values]).reshape(4, 4)


@_native("Math.Matrix4x4.from_rows")
def _m4_from_rows(r0: Any, r1: Any, r2: Any, r3: Any) -> np.ndarray:
    return np.vstack([_row(r, 4, f"row {i}") for i, r in enumerate((r0, r1, r2, r3))])


@_native("Math.Matrix4x4.from_columns")
def _m4_from_columns(c0: Any, c1: Any, c2: Any, c3: Any) -> np.ndarray:
    return np.column_stack([_row(c, 4, f"column {i}") for i, c in enumerate((c0, c1, c2, c3))])


@_native("Math.Matrix4x4.from_vec3_quat")
def _m4_from_vec3_quat(v: Any, q: Any) -> np.ndarray:
    """Affine matrix: rotation of q in the upper-left 3x3, translation v in the last column."""
    m = np.eye(4)
    m[:3, :3] = _quat_to_matrix(_quat(q), "Math.Matrix4x4.from_vec3_quat")
    m[:3, 3] = _vec3(v)
    return m


@_native("Math.Matrix4x4.transpose")
def _m4_transpose(m: Any) -> np.ndarray:
    return _mat4(m).T.copy()


@_native("Math.Matrix4x4.copy")
def _m4_copy(m: Any) -> np.ndarray:
    return _mat4(m).copy()


@_native("Math.Matrix4x4.get_affine_translation")
def _m4_translation(m: Any) -> np.ndarray:
    return _mat4(m)[:3, 3].copy()


@_native("Math.Matrix4x4.get_affine_rotation")
def _m4_rotation(m: Any) -> np.ndarray:
    """Rotation of the upper-left 3x3 block; a scaled block is orthonormalised (polar decomposition)."""
    r = _mat4(m)[:3, :3]
    if not np.all(np.isfinite(r)) or np.linalg.det(r) <= 1e-12:
        raise NativeError("Math.Matrix4x4.get_affine_rotation: the upper-left 3x3 block is not a rotation")
    u, _, vt = np.linalg.svd(r)
    return _matrix_to_quat(u @ vt)


# ---- Math.AffineTransform ------------------------------------------------------------------------


@_native("Math.AffineTransform.create")
def _t_create() -> Transform:
    return Transform(np.zeros(3), np.array(_IDENTITY_QUAT))


@_native("Math.AffineTransform.from")
def _t_from(p: Any, r: Any) -> Transform:
    return Transform(_vec3(p, "p"), _quat(r, "r"))


@_native("Math.AffineTransform.from_axes")
def _t_from_axes(new_Z: Any, new_X: Any, position: Any) -> Transform:  # noqa: N803
    return _from_axes(_vec3(new_Z, "new_Z"), _vec3(new_X, "new_X"), _vec3(position, "position"))


@_native("Math.AffineTransform.inverse_of")
def _t_inverse_of(p: Any, r: Any) -> Transform:
    return _t_inverse(Transform(_vec3(p, "p"), _quat(r, "r")))


@_native("Math.AffineTransform.inverse")
def _t_inverse_method(t: Any) -> Transform:
    return _t_inverse(_transform(t))


@_native("Math.AffineTransform.transform_vec3_point")
def _t_point(t: Any, v: Any) -> np.ndarray:
    tr = _transform(t)
    return _qrotate(tr.rotation, _vec3(v), "Math.AffineTransform.transform_vec3_point") + tr.position


@_native("Math.AffineTransform.transform_vec3_vector")
def _t_vector(t: Any, v: Any) -> np.ndarray:
    return _qrotate(_transform(t).rotation, _vec3(v), "Math.AffineTransform.transform_vec3_vector")


# ---- Math.Line -----------------------------------------------------------------------------------


@_native("Math.Line.from_points")
def _line_from_points(start: Any, end: Any) -> Line:
    return Line(_vec3(start, "start"), _vec3(end, "end"))


@_native("Math.Line.length")
def _line_length(line: Any) -> float:
    if not isinstance(line, Line):
        raise NativeError(f"Math.Line.length: expected a Line, got {type(line).__name__}")
    return _norm(line.end - line.start)


# ---- Math.Functions ------------------------------------------------------------------------------

_F = "Math.Functions."


def _unary_real(name: str, fn: Callable[[float], float]) -> None:
    def native(x: Any) -> float:
        return float(fn(_real(x, "x")))

    _native(_F + name)(native)


_unary_real("sin", math.sin)
_unary_real("cos", math.cos)
_unary_real("tan", math.tan)
_unary_real("arctan", math.atan)
_unary_real("rad_to_deg", math.degrees)
_unary_real("deg_to_rad", math.radians)


def _clamped_unit(name: str, x: Any) -> float:
    v = _real(x, "x")
    if not -1.0 - _ACOS_CLAMP_TOL <= v <= 1.0 + _ACOS_CLAMP_TOL:
        raise NativeError(f"{_F}{name}: argument {v!r} is outside [-1, 1]")
    return min(1.0, max(-1.0, v))


@_native(_F + "arcsin")
def _f_arcsin(x: Any) -> float:
    return math.asin(_clamped_unit("arcsin", x))


@_native(_F + "arccos")
def _f_arccos(x: Any) -> float:
    return math.acos(_clamped_unit("arccos", x))


@_native(_F + "arctan2")
def _f_arctan2(x: Any, y: Any) -> float:
    """Angle of the point (x, y): C ``atan2(y, x)``, following the declared parameter names."""
    return math.atan2(_real(y, "y"), _real(x, "x"))


@_native(_F + "sqrt")
def _f_sqrt(values: Any) -> float:
    v = _real(values, "values")
    if v < 0.0:
        raise NativeError(f"{_F}sqrt: square root of the negative number {v!r}")
    return math.sqrt(v)


@_native(_F + "pow")
def _f_pow(base: Any, exponent: Any) -> float:
    b, e = _real(base, "base"), _real(exponent, "exponent")
    if b == 0.0 and e < 0.0:
        raise NativeError(f"{_F}pow: zero raised to the negative power {e!r}")
    if b < 0.0 and math.isfinite(e) and not e.is_integer():
        raise NativeError(f"{_F}pow: negative base {b!r} with non-integer exponent {e!r}")
    try:
        return math.pow(b, e)
    except OverflowError:
        raise NativeError(f"{_F}pow: {b!r} ** {e!r} overflows") from None


def _nonempty(name: str, values: Any) -> list[float]:
    vals = _reals(values, "values")
    if not vals:
        raise NativeError(f"{_F}{name} of an empty list")
    return vals


@_native(_F + "mean")
def _f_mean(values: Any) -> float:
    vals = _nonempty("mean", values)
    return math.fsum(vals) / len(vals)


@_native(_F + "median")
def _f_median(values: Any) -> float:
    vals = sorted(_nonempty("median", values))
    mid = len(vals) // 2
    return vals[mid] if len(vals) % 2 else (vals[mid - 1] + vals[mid]) / 2.0


@_native(_F + "harmonic_mean")
def _f_harmonic_mean(values: Any) -> float:
    """n / sum(1/x).  Negative values raise; any zero gives 0 (the limit), as Python's statistics does."""
    vals = _nonempty("harmonic_mean", values)
    if any(v < 0.0 for v in vals):
        raise NativeError(f"{_F}harmonic_mean is not defined for negative values")
    if any(v == 0.0 for v in vals):
        return 0.0
    return len(vals) / math.fsum(1.0 / v for v in vals)


@_native(_F + "min")
def _f_min(values: Any) -> float:
    return min(_nonempty("min", values))


@_native(_F + "max")
def _f_max(values: Any) -> float:
    return max(_nonempty("max", values))


@_native(_F + "sum")
def _f_sum(values: Any) -> float:
    return float(math.fsum(_reals(values, "values")))


@_native(_F + "equals_approx")
def _f_equals_approx(value: Any, ref: Any) -> bool:
    v, r = _real(value, "value"), _real(ref, "ref")
    if v == r:  # also equal infinities
        return True
    return abs(v - r) <= EQUALS_APPROX_TOL * max(1.0, abs(r))


@_native(_F + "inf")
def _f_inf() -> float:
    return math.inf


@_native(_F + "neg_inf")
def _f_neg_inf() -> float:
    return -math.inf


def _to_int(name: str, x: Any, fn: Callable[[float], float]) -> int:
    v = _real(x, "x")
    if not math.isfinite(v):
        raise NativeError(f"{_F}{name}: cannot convert {v!r} to Int")
    return int(fn(v))


@_native(_F + "round")
def _f_round(x: Any) -> int:
    """Round half away from zero (like C ``round``), not Python's half-to-even."""
    return _to_int("round", x, lambda v: math.copysign(math.floor(abs(v) + 0.5), v))


@_native(_F + "floor")
def _f_floor(x: Any) -> int:
    return _to_int("floor", x, math.floor)


@_native(_F + "ceil")
def _f_ceil(x: Any) -> int:
    return _to_int("ceil", x, math.ceil)


# ---- Physics3D -----------------------------------------------------------------------------------


@_native("Physics3D.Bodies.Inertia.symmetric_tensor")
def _inertia_symmetric_tensor(diag: Any, e01_10: Any, e02_20: Any, e12_21: Any) -> np.ndarray:
    d = _vec3(diag, "diag")
    a, b, c = _real(e01_10, "e01_10"), _real(e02_20, "e02_20"), _real(e12_21, "e12_21")
    return np.array([[d[0], a, b], [a, d[1], c], [b, c, d[2]]])


# ---- Robotics.Kinematics.ElementaryTransform -----------------------------------------------------
# Constructors and forward kinematics only; the ``*_from_ets`` helpers are in UNSUPPORTED because
# their exact meaning (which frame, which joint numbering) is not documented.

_ET = "Robotics.Kinematics.ElementaryTransform."
_ET_TYPES = ("tx", "ty", "tz", "Rx", "Ry", "Rz")


def _register_et(kind: str) -> None:
    def fixed(value: Any) -> ElementaryTransform:
        return ElementaryTransform(type=kind, c=_real(value, "value"))

    def free(flip: Any) -> ElementaryTransform:
        return ElementaryTransform(type=kind, free=True, flip=_bool(flip, "flip"))

    _native(_ET + kind)(fixed)
    _native(_ET + kind + "_free")(free)


for _kind in _ET_TYPES:
    _register_et(_kind)
del _kind


def _et_transform(et: ElementaryTransform, value: float) -> Transform:
    kind = et.type.lower()
    if kind not in ("tx", "ty", "tz", "rx", "ry", "rz"):
        raise NativeError(f"ElementaryTransform: unknown type {et.type!r} (expected tx|ty|tz|Rx|Ry|Rz)")
    axis = _AXIS_INDEX[kind[1]]
    if kind[0] == "t":
        p = np.zeros(3)
        p[axis] = value
        return Transform(p, np.array(_IDENTITY_QUAT))
    return Transform(np.zeros(3), _axis_quat(axis, value))


@_native(_ET + "fkine")
def _et_fkine(ets: Any, q: Any) -> Transform:
    """Product of the steps; free steps take the next value of q (negated when flip)."""
    if isinstance(ets, (str, bytes)) or not isinstance(ets, Sequence):
        raise NativeError("fkine: ets must be a list of ElementaryTransform")
    qs = _reals(q, "q")
    n_free = sum(1 for et in ets if isinstance(et, ElementaryTransform) and et.free)
    if len(qs) != n_free:
        raise NativeError(f"fkine: {n_free} free joint(s) but {len(qs)} joint value(s) given")
    result = Transform(np.zeros(3), np.array(_IDENTITY_QUAT))
    it = iter(qs)
    for et in ets:
        if not isinstance(et, ElementaryTransform):
            raise NativeError(f"fkine: expected ElementaryTransform, got {type(et).__name__}")
        value = (-next(it) if et.flip else next(it)) if et.free else float(et.c)
        result = _t_compose(result, _et_transform(et, value))
    return result


# --------------------------------------------------------------------------------------------------
# Unsupported: declared natives that need the object graph or the runtime
# --------------------------------------------------------------------------------------------------

_SIGNAL_VALUE_MODELS = (
    "IntValue", "BoolValue", "AngleValue", "AngularVelocity1DValue", "DistanceValue", "Force1DValue",
    "Velocity1DValue", "Torque1DValue", "RpmValue", "FractionValue", "DurationValue", "RatioValue",
    "MassValue", "TorqueRangeValue", "ForceRangeValue", "Acceleration3DValue",
    "AngularAcceleration3DValue", "AngularVelocity3DValue", "Force3DValue", "Torque3DValue",
    "Velocity3DValue", "Position3DValue", "RPYvalue",
)  # fmt: skip
_VALUE_OUTPUT_KINDS = (
    "angle", "angular_velocity_1d", "distance", "force_1d", "velocity_1d", "torque_1d", "rpm",
    "acceleration_3d", "angular_acceleration_3d", "angular_velocity_3d", "force_3d", "torque_3d",
    "velocity_3d", "position_3d", "rpy", "int", "bool", "fraction", "duration", "torque_range",
    "force_range", "ratio", "mass",
)  # fmt: skip

UNSUPPORTED: frozenset[str] = frozenset(
    {
        # object graph / SNAP
        "Physics3D.System.on_init",
        "Physics3D.System.resnap",
        "Physics3D.System.reduce_body_to_world_system_transform",
        "Physics3D.System.reduce_to_world_system_transform",
        "Physics.Geometries.Material.on_init",
        "Physics.Geometries.Material.is_default_material",
        "Terrain.TerrainMaterial.is_default_terrain_material",
        "Urdf.PackagePath.on_init",
        "Physics.Signals.SignalInterface.on_init",
        # robotics helpers needing the system, or with undocumented semantics
        _ET + "calculateElementaryTransformSequence",
        _ET + "position_from_ets",
        _ET + "main_axis_from_ets",
        _ET + "normal_from_ets",
        # runtime signal plumbing
        "Robotics.Signals.RobotInput.process",
        "Robotics.Signals.RobotOutput.process",
        "Robotics.Signals.RobotOutputSignal.create",
        "Robotics.Signals.SensorValues.create",
        "Robotics.Signals.RobotInputSignal.create",
        "Robotics.Signals.RobotInputSignal.from_values",
        "Physics.Signals.ValueOutputSignal.create",
        *(f"Physics.Signals.ValueOutputSignal.from_{k}" for k in _VALUE_OUTPUT_KINDS),
        *(f"Physics.Signals.ValueOutputSignal.as_{k}" for k in _VALUE_OUTPUT_KINDS),
        *(f"Physics.Signals.ValueOutputSignal.{m}" for m in (
            "is_real", "is_vec3", "is_vec2", "is_int", "is_bool", "as_real", "as_vec3", "as_vec2",
        )),  # fmt: skip
        *(f"Physics.Signals.{m}.create" for m in _SIGNAL_VALUE_MODELS),
        *(f"Physics.Signals.{m}.create" for m in (
            "RealInputSignal", "RealRangeInputSignal", "BoolInputSignal", "IntInputSignal", "Vec3InputSignal",
        )),  # fmt: skip
    }
)
"""Declared natives this module deliberately does not implement (they need the object graph/runtime)."""


# --------------------------------------------------------------------------------------------------
# Operators
# --------------------------------------------------------------------------------------------------

OPERATORS: dict[tuple[str, str, str | None], Callable[..., Any]] = {}
"""``(op, lhs_type, rhs_type)`` -> implementation; ``rhs_type`` is None for unary minus.

Holds every operator declared in the Math bundle plus plain Real/Int arithmetic.  Types are qualified
model names or ``Real``/``Int``.  Prefer :func:`apply_operator`, which also promotes Int to Real.
"""

_V2, _V3, _Q, _M3, _M4, _T = (
    "Math.Vec2", "Math.Vec3", "Math.Quat", "Math.Matrix3x3", "Math.Matrix4x4", "Math.AffineTransform",
)  # fmt: skip


def _op(op: str, lhs: str, rhs: str | None, fn: Callable[..., Any]) -> None:
    label = f"operator {op}({lhs}, {rhs})" if rhs else f"operator {op}({lhs})"
    OPERATORS[(op, lhs, rhs)] = _guard(label, fn, 1 if rhs is None else 2)


def _nonzero(x: Any, what: str) -> float:
    d = _real(x, what)
    if d == 0.0:
        raise NativeError("division by zero")
    return d


def _register_vector_ops(type_name: str, coerce: Callable[..., np.ndarray]) -> None:
    _op("+", type_name, type_name, lambda a, b: coerce(a) + coerce(b))
    _op("-", type_name, type_name, lambda a, b: coerce(a) - coerce(b))
    _op("*", "Real", type_name, lambda s, v: _real(s, "lhs") * coerce(v))
    _op("*", type_name, "Real", lambda v, s: coerce(v) * _real(s, "rhs"))
    _op("/", type_name, "Real", lambda v, s: coerce(v) / _nonzero(s, "rhs"))
    _op("-", type_name, None, lambda v: -coerce(v))


_register_vector_ops(_V2, _vec2)
_op("*", _V2, _V2, lambda a, b: float(np.dot(_vec2(a), _vec2(b))))
_register_vector_ops(_V3, _vec3)
_op("*", _V3, _V3, lambda a, b: float(np.dot(_vec3(a), _vec3(b))))
_register_vector_ops(_Q, _quat)
_op("*", _Q, _Q, lambda a, b: _qmul(_quat(a), _quat(b)))
_op("/", _Q, _Q, lambda a, b: _qmul(_quat(a), _qinverse(_quat(b), "operator /(Quat, Quat)")))
_op("+", _M3, _M3, lambda a, b: _mat3(a) + _mat3(b))
_op("-", _M3, _M3, lambda a, b: _mat3(a) - _mat3(b))
_op("*", _M3, _M3, lambda a, b: _mat3(a) @ _mat3(b))
_op("*", _M3, _V3, lambda m, v: _mat3(m) @ _vec3(v))
_op("+", _M4, _M4, lambda a, b: _mat4(a) + _mat4(b))
_op("-", _M4, _M4, lambda a, b: _mat4(a) - _mat4(b))
_op("*", _M4, _M4, lambda a, b: _mat4(a) @ _mat4(b))
_op("*", _T, _T, lambda a, b: _t_compose(_transform(a, "lhs"), _transform(b, "rhs")))

# Plain arithmetic.  Int (+ - *) Int stays Int; anything with a Real is Real; / is always Real.


def _int(x: Any, what: str) -> int:
    if not isinstance(x, (int, np.integer)) or isinstance(x, (bool, np.bool_)):
        raise NativeError(f"{what} must be an Int, got {type(x).__name__}")
    return int(x)


def _register_arithmetic() -> None:
    for lt in ("Int", "Real"):
        for rt in ("Int", "Real"):
            if lt == rt == "Int":
                _op("+", lt, rt, lambda a, b: _int(a, "lhs") + _int(b, "rhs"))
                _op("-", lt, rt, lambda a, b: _int(a, "lhs") - _int(b, "rhs"))
                _op("*", lt, rt, lambda a, b: _int(a, "lhs") * _int(b, "rhs"))
            else:
                _op("+", lt, rt, lambda a, b: _real(a, "lhs") + _real(b, "rhs"))
                _op("-", lt, rt, lambda a, b: _real(a, "lhs") - _real(b, "rhs"))
                _op("*", lt, rt, lambda a, b: _real(a, "lhs") * _real(b, "rhs"))
            _op("/", lt, rt, lambda a, b: _real(a, "lhs") / _nonzero(b, "rhs"))
    _op("-", "Int", None, lambda a: -_int(a, "operand"))
    _op("-", "Real", None, lambda a: -_real(a, "operand"))


_register_arithmetic()


def primitive_result_type(op: str, lhs_type: str, rhs_type: str | None) -> str | None:
    """Result type of plain arithmetic on Int/Real, or None when the operands are not both Int/Real."""
    if lhs_type not in ("Int", "Real") or rhs_type not in ("Int", "Real", None):
        return None
    if op not in ("+", "-", "*", "/") or (rhs_type is None and op != "-"):
        return None
    if op == "/":
        return "Real"
    return "Int" if lhs_type == "Int" and rhs_type in ("Int", None) else "Real"


def _promote(t: str | None) -> str | None:
    return "Real" if t == "Int" else t


def apply_operator(op: str, lhs_type: str, lhs: Any, rhs_type: str | None = None, rhs: Any = None) -> Any:
    """Apply ``lhs op rhs`` (or unary ``op lhs`` when ``rhs_type`` is None).

    Looks up ``(op, lhs_type, rhs_type)`` first, then the same with Int promoted to Real on both sides
    (converting the Int operands to float).  Raises NativeError when no operator matches.
    """
    unary = rhs_type is None
    fn = OPERATORS.get((op, lhs_type, rhs_type))
    if fn is None:
        key = (op, _promote(lhs_type), _promote(rhs_type))
        fn = OPERATORS.get(key)
        if fn is not None:
            if lhs_type == "Int":
                lhs = float(_int(lhs, "lhs"))
            if rhs_type == "Int":
                rhs = float(_int(rhs, "rhs"))
    if fn is None:
        shown = f"{op}{lhs_type}" if unary else f"{lhs_type} {op} {rhs_type}"
        raise NativeError(f"no operator for {shown}")
    return fn(lhs) if unary else fn(lhs, rhs)


def call(name: str, *args: Any) -> Any:
    """Call the native ``name``; NativeError for unknown or unsupported names."""
    fn = FUNCTIONS.get(name)
    if fn is None:
        if name in UNSUPPORTED:
            raise NativeError(f"{name} is not supported by the plxtools evaluator")
        raise NativeError(f"unknown native function {name}")
    return fn(*args)


# --------------------------------------------------------------------------------------------------
# Struct codecs: objects with attributes <-> values
# --------------------------------------------------------------------------------------------------

_MISSING = object()


@dataclass(frozen=True)
class StructCodec:
    """Converts between a model's attribute values (by field name) and its Python value.

    ``fields`` are the attribute names in bundle order; ``field_types`` their OpenPLX types;
    ``defaults`` the bundle defaults (a field without a default is required).  Nested model fields
    (AffineTransform.position/rotation, Line.start/end) take and give already-converted values.
    """

    type_name: str
    fields: tuple[str, ...]
    field_types: Mapping[str, str]
    defaults: Mapping[str, Any]
    python_type: type
    _build: Callable[[dict[str, Any]], Any]
    _split: Callable[[Any], dict[str, Any]]

    def from_fields(self, values: Mapping[str, Any]) -> Any:
        """Build the value; missing fields take the bundle default; unknown keys are ignored."""
        resolved: dict[str, Any] = {}
        for name in self.fields:
            v = values.get(name, _MISSING)
            if v is _MISSING:
                v = self.defaults.get(name, _MISSING)
                if v is _MISSING:
                    raise NativeError(f"{self.type_name}: missing value for field {name!r}")
            resolved[name] = _coerce_field(self.field_types[name], v, f"{self.type_name}.{name}")
        return self._build(resolved)

    def to_fields(self, value: Any) -> dict[str, Any]:
        if not isinstance(value, self.python_type):
            expected, got = self.python_type.__name__, type(value).__name__
            raise NativeError(f"{self.type_name}: expected {expected}, got {got}")
        return self._split(value)

    def default(self) -> Any:
        """The default-constructed value (NativeError when a field has no default, e.g. Matrix4x4)."""
        return self.from_fields({})


def _coerce_field(type_name: str, v: Any, what: str) -> Any:
    if type_name == "Real":
        return _real(v, what)
    if type_name == "Bool":
        return _bool(v, what)
    if type_name == "String":
        if not isinstance(v, str):
            raise NativeError(f"{what} must be a String, got {type(v).__name__}")
        return v
    return _array(v, _SHAPES[type_name], what).copy()


SHAPES = {_V2: (2,), _V3: (3,), _Q: (4,), _M3: (3, 3), _M4: (4, 4)}
"""The numpy shape of each array-represented math type: the one table of shapes."""
_SHAPES = SHAPES


def _array_repr(type_name: str):
    shape = SHAPES[type_name]

    def make(names: tuple[str, ...]):
        return (np.ndarray,
                lambda f: np.array([f[n] for n in names], dtype=float).reshape(shape),
                lambda v: dict(zip(names, (float(x) for x in _array(v, shape, type_name).ravel()))))
    return make


# Only the Python representation is hand-written; fields, field types and defaults are read from the
# bundle program by `struct_types`, once per program (the bundles declare them: `x is Real: 0` in Math/Vec3).
_REPRESENTATIONS: dict[str, Callable] = {
    _V2: _array_repr(_V2),
    _V3: _array_repr(_V3),
    _Q: _array_repr(_Q),
    _M3: _array_repr(_M3),
    _M4: _array_repr(_M4),
    _T: lambda names: (Transform, lambda f: Transform(f["position"], f["rotation"]),
                       lambda t: {"position": t.position.copy(), "rotation": t.rotation.copy()}),
    "Math.Line": lambda names: (Line, lambda f: Line(f["start"], f["end"]),
                                lambda line: {"start": line.start.copy(), "end": line.end.copy()}),
}

# ElementaryTransform is opaque in the bundle (static constructors only, no attributes): its fields
# are this module's own representation, not bundle knowledge.
_ET_CODEC = StructCodec(
    type_name=_ET[:-1],
    fields=("type", "c", "free", "flip"),
    field_types={"type": "String", "c": "Real", "free": "Bool", "flip": "Bool"},
    defaults={"type": "tx", "c": 0.0, "free": False, "flip": False},
    python_type=ElementaryTransform,
    _build=lambda f: ElementaryTransform(**f),
    _split=lambda e: {"type": e.type, "c": e.c, "free": e.free, "flip": e.flip},
)

# the value types whose representation is an object of ours (the rest are numpy arrays, by shape)
_OBJECT_TYPES = ((Transform, _T), (Line, "Math.Line"), (ElementaryTransform, _ET_CODEC.type_name))

_STRUCTS_OF: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # program -> its codecs


def struct_types(program) -> dict[str, StructCodec]:
    """Codecs by qualified model name for the value types of ``program``: the math types' fields,
    field types and defaults as that program's bundles declare them (`x is Real: 0` in Math/Vec3),
    plus ElementaryTransform. Read once per program (and forgotten with it), so programs of different
    versions in one process never share them. A type the program does not declare has no codec."""
    cached = _STRUCTS_OF.get(program)
    if cached is not None:
        return cached
    from plxtools.syntax import ast

    codecs: dict[str, StructCodec] = {_ET_CODEC.type_name: _ET_CODEC}
    for name in _REPRESENTATIONS:  # dependencies first: Vec3/Quat before AffineTransform and Line
        model = program.lookup_outside_visibility(name.split("."))
        if model is None or not hasattr(model, "members"):
            continue
        members = program.all_members(model)
        names = tuple(members)
        types: dict[str, str] = {}
        defaults: dict[str, Any] = {}
        for field_name, mem in members.items():
            ty = program.member_type(mem)
            tname = ty.primitive or (ty.model.qname if ty.model is not None else "Real")
            types[field_name] = tname
            value = _literal(mem.value, ast)
            if value is not None:
                defaults[field_name] = float(value) if tname == "Real" else value
            elif tname in codecs:
                try:
                    defaults[field_name] = codecs[tname].default()
                except NativeError:
                    pass
        python_type, build, split = _REPRESENTATIONS[name](names)
        codecs[name] = StructCodec(name, names, types, defaults, python_type, build, split)
    _STRUCTS_OF[program] = codecs
    return codecs


def _literal(expr, ast) -> Any:
    """A default written as a literal (`0`, `-1.5`, `true`, `"x"`); None for anything else."""
    if isinstance(expr, ast.Number):
        return expr.value
    if isinstance(expr, ast.Unary) and expr.op == "-" and isinstance(expr.operand, ast.Number):
        return -expr.operand.value
    if isinstance(expr, ast.Bool):
        return expr.value
    if isinstance(expr, ast.String):
        return expr.value
    return None


_SHAPE_TYPES = {shape: name for name, shape in _SHAPES.items()}


def type_of(value: Any) -> str | None:
    """The OpenPLX type of a value in this module's representation (``"Real"``, ``"Math.Vec3"``, ...).

    Returns None for values that are not one of the representations above (lists included).
    """
    if isinstance(value, (bool, np.bool_)):
        return "Bool"
    if isinstance(value, (int, np.integer)):
        return "Int"
    if isinstance(value, (float, np.floating)):
        return "Real"
    if isinstance(value, str):
        return "String"
    if isinstance(value, np.ndarray):
        return _SHAPE_TYPES.get(value.shape)
    for python_type, type_name in _OBJECT_TYPES:
        if isinstance(value, python_type):
            return type_name
    return None
