"""Small numpy pose helpers for the MuJoCo backend (quaternions are w, x, y, z)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

# OpenPLX cylinders/capsules lie along local Y, MuJoCo's along local Z: rotate -90 deg about X
# (maps Z onto Y).
Z_TO_Y_QUAT = np.array([math.sqrt(0.5), -math.sqrt(0.5), 0.0, 0.0])


def unit(v: Sequence[float]) -> np.ndarray:
    a = np.asarray(v, dtype=float)
    n = float(np.linalg.norm(a))
    return a / n if n > 0 else a * 0.0


def quat_normalize(q: Sequence[float]) -> np.ndarray:
    a = np.asarray(q, dtype=float)
    n = float(np.linalg.norm(a))
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    a = a / n
    return a if a[0] >= 0 else -a


def quat_mul(a: Sequence[float], b: Sequence[float]) -> np.ndarray:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ]
    )


def quat_conj(q: Sequence[float]) -> np.ndarray:
    return np.array([q[0], -q[1], -q[2], -q[3]], dtype=float)


def quat_to_mat(q: Sequence[float]) -> np.ndarray:
    w, x, y, z = quat_normalize(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def rotate(q: Sequence[float], v: Sequence[float]) -> np.ndarray:
    return quat_to_mat(q) @ np.asarray(v, dtype=float)


def relative_pose(
    parent_pos: Sequence[float],
    parent_quat: Sequence[float],
    child_pos: Sequence[float],
    child_quat: Sequence[float],
) -> tuple[np.ndarray, np.ndarray]:
    """Pose of the child expressed in the parent frame."""
    pinv = quat_conj(quat_normalize(parent_quat))
    pos = rotate(pinv, np.asarray(child_pos, dtype=float) - np.asarray(parent_pos, dtype=float))
    return pos, quat_normalize(quat_mul(pinv, quat_normalize(child_quat)))


def yaw_of_mat(r: np.ndarray) -> float:
    """Heading of the body x axis about world Z."""
    return math.atan2(float(r[1, 0]), float(r[0, 0]))


def angle_between(a: np.ndarray, b: np.ndarray) -> float:
    d = float(np.clip(np.dot(unit(a), unit(b)), -1.0, 1.0))
    return math.acos(d)
