"""Rigid poses as (R, p) numpy pairs, and conversions to the OpenPLX/natives quaternion (x, y, z, w)
and the scene IR quaternion (w, x, y, z)."""

from __future__ import annotations

import math

import numpy as np

Pose = tuple  # (R: (3, 3) ndarray, p: (3,) ndarray)

IDENTITY: Pose = (np.eye(3), np.zeros(3))


def orthogonal_unit(v: np.ndarray, z: np.ndarray) -> np.ndarray | None:
    """The unit part of ``v`` orthogonal to the unit vector ``z`` (a connector's normal made
    orthogonal to its main axis), or None when ``v`` is zero or (nearly) parallel to ``z``."""
    nn = float(np.linalg.norm(v))
    perp = v - float(np.dot(v, z)) * z
    n_perp = float(np.linalg.norm(perp))
    if nn < 1e-9 or n_perp < 1e-6 * max(nn, 1.0):
        return None
    return perp / n_perp


def compose(a: Pose, b: Pose) -> Pose:
    """``a * b``: the frame ``b`` (given in ``a``) expressed in ``a``'s parent."""
    return a[0] @ b[0], a[0] @ b[1] + a[1]


def inverse(a: Pose) -> Pose:
    rt = a[0].T
    return rt, -(rt @ a[1])


def quat_xyzw_to_mat(q) -> np.ndarray:
    x, y, z, w = (float(c) for c in q)
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if n < 1e-12:
        return np.eye(3)
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def mat_to_quat_wxyz(m: np.ndarray) -> tuple[float, float, float, float]:
    """Rotation matrix to a unit quaternion (w, x, y, z) with w >= 0."""
    t = m[0, 0] + m[1, 1] + m[2, 2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        w, x, y, z = 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        w, x, y, z = (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        w, x, y, z = (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        w, x, y, z = (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s
    q = np.array([w, x, y, z])
    q /= np.linalg.norm(q)
    if q[0] < 0:
        q = -q
    return tuple(float(c) + 0.0 for c in q)  # type: ignore[return-value]


def from_transform(t) -> Pose:
    """natives.Transform (position, rotation xyzw) -> Pose."""
    return quat_xyzw_to_mat(t.rotation), np.asarray(t.position, dtype=float).copy()


def rot_z(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def angle_between(a: np.ndarray, b: np.ndarray) -> float:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na < 1e-12 or nb < 1e-12:
        return 0.0
    c = float(np.dot(a, b)) / (na * nb)
    return math.acos(max(-1.0, min(1.0, c)))


def rotation_angle(r: np.ndarray) -> float:
    """Angle of a rotation matrix (0..pi)."""
    c = (float(np.trace(r)) - 1.0) / 2.0
    return math.acos(max(-1.0, min(1.0, c)))


def fmt_vec(v, digits: int = 3) -> str:
    return "(" + ", ".join(f"{float(x):.{digits}f}" for x in v) + ")"
