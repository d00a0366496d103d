"""The independent references: what a careful engineer writes with numpy alone.

Nothing here imports pinframes, so a slow or wrong pinframes kernel cannot hide in the
reference it is measured against. Poses are (N, 4, 4) homogeneous matrices; quaternions
``(x, y, z, w)``; times float seconds.
"""

from __future__ import annotations

import numpy as np


def matrices_from_quaternions(q: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotation matrices of unit quaternions (N, 4), the textbook closed form."""
    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def rodrigues(axis: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotations by ``angles`` (N,) radians about the unit ``axis`` (3,)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]],
                  [-axis[1], axis[0], 0.0]])
    return (np.eye(3) + np.sin(angles)[:, None, None] * k
            + (1 - np.cos(angles))[:, None, None] * (k @ k))


def interpolate(times, keyframe_times, translations, quaternions) -> np.ndarray:
    """Linear translation + SLERP at ``times``, held at the ends, as (N, 4, 4)."""
    index = np.clip(np.searchsorted(keyframe_times, times, side="right") - 1, 0,
                    len(keyframe_times) - 2)
    w = np.clip((times - keyframe_times[index])
                / (keyframe_times[index + 1] - keyframe_times[index]), 0.0, 1.0)
    q0, q1 = quaternions[index], quaternions[index + 1]
    dot = np.sum(q0 * q1, axis=1)
    q1 = np.where(dot[:, None] < 0, -q1, q1)
    theta = np.arccos(np.clip(np.abs(dot), -1.0, 1.0))
    sin_theta = np.sin(theta)
    small = sin_theta < 1e-9
    a = np.where(small, 1 - w, np.sin((1 - w) * theta) / np.where(small, 1, sin_theta))
    b = np.where(small, w, np.sin(w * theta) / np.where(small, 1, sin_theta))
    q = a[:, None] * q0 + b[:, None] * q1
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    out = np.zeros((len(times), 4, 4))
    out[:, :3, :3] = matrices_from_quaternions(q)
    out[:, :3, 3] = (1 - w)[:, None] * translations[index] + w[:, None] * translations[index + 1]
    out[:, 3, 3] = 1.0
    return out


def chain(times, edges) -> np.ndarray:
    """Compose a chain's edges, each a static (4, 4) or (keyframe times, translations,
    quaternions), at ``times``: the pose of the last frame in the first one's parent."""
    result = None
    for edge in edges:
        matrix = edge if isinstance(edge, np.ndarray) else interpolate(times, *edge)
        result = matrix if result is None else result @ matrix
    return result


def random_walk_quaternions(rng: np.random.Generator, count: int, step: float) -> np.ndarray:
    """A random walk of rotations with steps below ``step`` radians, as quaternions."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    angles = rng.uniform(0, step, size=count)
    steps = np.concatenate([axes * np.sin(angles / 2)[:, None], np.cos(angles / 2)[:, None]],
                           axis=1)
    out = np.empty((count, 4))
    out[0] = [0.0, 0.0, 0.0, 1.0]
    for i in range(1, count):  # quaternion product out[i-1] * steps[i]
        x1, y1, z1, w1 = out[i - 1]
        x2, y2, z2, w2 = steps[i]
        out[i] = [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                  w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]
    return out
