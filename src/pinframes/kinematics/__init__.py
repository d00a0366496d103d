"""Kinematics of compiled query paths: rates of what is interpolated, velocities, Jacobians."""
