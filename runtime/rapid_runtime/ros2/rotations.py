"""Rotations between ROS 2 quaternions (x, y, z, w) and RAPID's encodings of Transform3D.rot
(RAPID_ROT_M33, RAPID_ROT_QUAT, intrinsic Euler angles). Pure arithmetic: no ROS 2, no DDS."""
from __future__ import annotations

import math
from typing import Any, Sequence

Quat = tuple[float, float, float, float]


def quat_from_rpy(r: float, p: float, y: float) -> Quat:
    """Roll, pitch, yaw (rotations about fixed X, Y, Z, as tf2's setRPY) -> (x, y, z, w)."""
    cr, sr, cp, sp = math.cos(r / 2), math.sin(r / 2), math.cos(p / 2), math.sin(p / 2)
    cy, sy = math.cos(y / 2), math.sin(y / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def quat_from_m33(m: Sequence[float]) -> Quat:
    """A row-major rotation matrix -> (x, y, z, w)."""
    m00, m01, m02, m10, m11, m12, m20, m21, m22 = (float(v) for v in m)
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    if m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        return (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    if m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        return ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    s = math.sqrt(1.0 + m22 - m00 - m11) * 2
    return ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)


def m33_from_quat(x: float, y: float, z: float, w: float) -> list[float]:
    """A unit quaternion -> its row-major rotation matrix."""
    return [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]


def quat_from_euler(angles: Sequence[float], axes: str) -> Quat:
    """Intrinsic Euler angles [rad] in the order `axes` ('ZYX', 'XYZ', 'ZYZ') -> (x, y, z, w)."""
    q = (0.0, 0.0, 0.0, 1.0)
    for axis, angle in zip(axes, angles):
        s, c = math.sin(float(angle) / 2), math.cos(float(angle) / 2)
        bx, by, bz, bw = (s if axis == "X" else 0.0, s if axis == "Y" else 0.0, s if axis == "Z" else 0.0, c)
        ax, ay, az, aw = q
        q = (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
             aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)
    return q


def _clamp(v: float) -> float:
    return max(-1.0, min(1.0, v))  # rounding past +-1 at the poles


def euler_from_quat(x: float, y: float, z: float, w: float, axes: str) -> list[float]:
    """Intrinsic Euler angles [rad] in the order `axes` ('ZYX': yaw, pitch, roll; 'XYZ')."""
    m = m33_from_quat(x, y, z, w)
    if axes == "ZYX":  # R = Rz(a) Ry(b) Rx(c)
        return [math.atan2(m[3], m[0]), math.asin(_clamp(-m[6])), math.atan2(m[7], m[8])]
    return [math.atan2(-m[5], m[8]), math.asin(_clamp(m[2])), math.atan2(-m[1], m[0])]  # Rx(a) Ry(b) Rz(c)


def yaw_from_quat(x: float, y: float, z: float, w: float) -> float:
    """The heading [rad] of a quaternion: rotation about z, as tf2's getRPY gives it."""
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def rotate(q: Sequence[float], v: Sequence[float]) -> list[float]:
    """Vector v (x, y, z) rotated by the quaternion q (x, y, z, w): from a body frame into its parent."""
    n = math.sqrt(sum(c * c for c in q)) or 1.0
    x, y, z, w = (c / n for c in q)
    m = m33_from_quat(x, y, z, w)
    return [m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
            m[6] * v[0] + m[7] * v[1] + m[8] * v[2]]


def rapid_rot(q: Any, encoding: str) -> list[float]:
    """A geometry_msgs Quaternion as the 9 floats of Transform3D.rot in `encoding`."""
    x, y, z, w = q.x, q.y, q.z, q.w
    if encoding == "RAPID_ROT_M33":
        return m33_from_quat(x, y, z, w)
    if encoding == "RAPID_ROT_QUAT":
        return [x, y, z, w, 0.0, 0.0, 0.0, 0.0, 0.0]
    if encoding in ("RAPID_ROT_ZYX", "RAPID_ROT_XYZ"):
        return euler_from_quat(x, y, z, w, encoding[-3:]) + [0.0] * 6
    return [0.0] * 9


def quat_of_pose(rot: Sequence[float], encoding: str) -> Quat:
    """Transform3D.rot in `encoding` -> (x, y, z, w); an encoding with no rotation to read
    (RAPID_ROT_NONE, an unknown one) is the identity."""
    if encoding == "RAPID_ROT_QUAT":
        x, y, z, w = (float(v) for v in rot[:4])
        return (x, y, z, w)
    if encoding == "RAPID_ROT_M33":
        return quat_from_m33(rot)
    if encoding in ("RAPID_ROT_XYZ", "RAPID_ROT_ZYX", "RAPID_ROT_ZYZ"):  # a rover's heading: ZYX
        return quat_from_euler(rot[:3], encoding[-3:])
    return (0.0, 0.0, 0.0, 1.0)
