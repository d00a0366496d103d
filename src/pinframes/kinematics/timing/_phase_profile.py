"""Joints that move in phases of constant jerk: their state at each phase and at any time.

A :class:`PhaseProfile` holds, per joint, the phases' durations, the jerk in each phase and
the acceleration each phase starts with (so a trapezoid is phases of constant acceleration and
no jerk); positions, velocities and accelerations follow by exact integration, vectorised over
joints and samples.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PhaseProfile"]


@dataclass(frozen=True)
class PhaseProfile:
    """Joints in phases of constant jerk, from rest at ``start``.

    Attributes
    ----------
    start : numpy.ndarray
        Shape ``(n,)``: the joints at time 0 (rad or m).
    durations : numpy.ndarray
        Shape ``(n, P)``: each phase's duration (s); a joint's phases follow each other.
    jerks : numpy.ndarray
        Shape ``(n, P)``: the jerk within each phase (per s^3).
    accelerations : numpy.ndarray
        Shape ``(n, P)``: the acceleration each phase starts with (per s^2).
    """

    start: np.ndarray
    durations: np.ndarray
    jerks: np.ndarray
    accelerations: np.ndarray

    def phase_starts(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each phase's start time, position and velocity, each shape ``(n, P)``."""
        count = self.durations.shape[1]
        times = np.zeros_like(self.durations)
        positions = np.zeros_like(self.durations)
        velocities = np.zeros_like(self.durations)
        positions[:, 0] = self.start
        for phase in range(1, count):  # P <= 7 phases, vectorised over joints
            dt = self.durations[:, phase - 1]
            a0 = self.accelerations[:, phase - 1]
            jerk = self.jerks[:, phase - 1]
            v0 = velocities[:, phase - 1]
            times[:, phase] = times[:, phase - 1] + dt
            velocities[:, phase] = v0 + a0 * dt + jerk * dt**2 / 2
            positions[:, phase] = (positions[:, phase - 1] + v0 * dt + a0 * dt**2 / 2
                                   + jerk * dt**3 / 6)
        return times, positions, velocities

    def sample(self, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities, accelerations ``(T, n)`` at each joint's own ``times (T, n)``
        (s from its start; past the last phase the joint goes on from its last phase)."""
        starts, positions, velocities = self.phase_starts()
        joints = np.arange(starts.shape[0])
        phase = np.maximum((times[:, :, None] >= starts[None, :, 1:]).sum(axis=2), 0)
        phase = np.minimum(phase, starts.shape[1] - 1)
        dt = np.minimum(times - starts[joints, phase], self.durations[joints, phase])
        jerk = self.jerks[joints, phase]
        a0 = self.accelerations[joints, phase]
        v0 = velocities[joints, phase]
        position = positions[joints, phase] + v0 * dt + a0 * dt**2 / 2 + jerk * dt**3 / 6
        velocity = v0 + a0 * dt + jerk * dt**2 / 2
        acceleration = a0 + jerk * dt
        return position, velocity, acceleration
