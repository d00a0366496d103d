"""The ``joints=`` arguments of the queries that name robot joints (``jacobian``,
``solve_joints``: ``joints=`` and ``add_joints=``), checked in one place."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from ..errors import ArgumentTypeError, JointError, joint_not_found
from ..values.joint import Joint

__all__ = ["named_joints"]


def named_joints(requested: object, joints: Mapping[str, Joint], frame: str,
                 field: str = "joints") -> list[str]:
    """``requested`` as a list of distinct names of ``joints`` that no other joint drives,
    else an error naming ``frame`` and ``field`` (the argument's name)."""
    if isinstance(requested, str) or not isinstance(requested, Sequence):
        raise ArgumentTypeError(f"expected a list of joint names, got {requested!r}",
                                frame=frame, field=field)
    for name in requested:
        if not isinstance(name, str) or name not in joints:
            raise joint_not_found(name, joints, frame=frame, field=field)
        mimic = joints[name].mimic
        if mimic is not None:
            raise JointError(f"joint {name!r} mimics {mimic.joint!r} and follows it; name "
                             "that joint instead", frame=frame, field=field)
    if len(set(requested)) != len(requested):
        raise JointError("joint names repeat", frame=frame, field=field)
    return list(requested)
