"""Bad calls to the Python API, as data: the call, the error, its frame and field.

Every call is made on the tree of :func:`sample_tree` (static, moving and robot frames,
joint tracks, a subsystem), which must come out of a failed call unchanged.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from hardening.file_cases import ARM, joint, urdf
from pinframes import FrameTree, Joint, Pose, Subsystem
from pinframes.errors import (
    ArgumentTypeError,
    ExtrapolationError,
    FileFormatError,
    FrameExistsError,
    FrameNotFoundError,
    InvalidPoseError,
    InvalidTimeError,
    JointError,
    JointNotFoundError,
    ReferenceTimeError,
    TreeStructureError,
)

START = np.datetime64("2024-03-01T08:00:00", "ns")
MIMIC_ARM = urdf(joint("j1", "a", "b") + joint("j2", "b", "c", inner='<mimic joint="j1"/>'))


def sample_tree() -> FrameTree:
    """world > table (static) > turntable (moving, own reference time) > arm (a URDF)."""
    tree = FrameTree("world", name="cell")
    tree.add("table", "world", Pose.from_xyz_rpy(1.0, 0.0, 0.8, yaw=0.3))
    tree.add("turntable", "table", Pose(
        [[0.0, 0.0, 0.1], [0.0, 0.0, 0.2]], [[0, 0, 0, 1], [0, 0, 1, 0]],
        times=[0.0, 2.0], reference_time=START))
    tree.attach_urdf(MIMIC_ARM, "turntable", prefix="arm/")
    tree.set_joint_trajectory([START, START + np.timedelta64(1, "s")], [[0.0], [0.5]],
                              ["arm/j1"])
    tree.subsystems = [Subsystem("cell", "world", ("world", "table"))]
    return tree


def moving(reference_time: Any = None) -> Pose:
    return Pose([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], times=[0.0, 1.0],
                reference_time=reference_time)


@dataclass(frozen=True)
class Call:
    id: str
    call: Callable[[FrameTree], Any]
    error: type[Exception]
    frame: str | None
    field: str | None
    message: str


REFLECTION = np.diag([1.0, 1.0, -1.0])
SHEARED = np.array([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
BAD_BOTTOM = np.vstack([np.hstack([np.eye(3), np.zeros((3, 1))]), [0.0, 0.0, 1.0, 1.0]])

CALLS = [
    # FrameTree.add
    Call("add-existing", lambda t: t.add("table", "world"), FrameExistsError, "table", None,
         "already has a frame"),
    Call("add-unknown-parent", lambda t: t.add("x", "ghost"), FrameNotFoundError, "x",
         "parent", "'ghost' is not in the tree"),
    Call("add-name-not-a-string", lambda t: t.add(5, "world"), ArgumentTypeError, None, "name",
         "got int"),
    Call("add-empty-name", lambda t: t.add("", "world"), TreeStructureError, None, "name",
         "must not be empty"),
    Call("add-parent-a-list", lambda t: t.add("x", ["world"]), ArgumentTypeError, "x",
         "parent", "got list"),
    Call("add-pose-a-matrix", lambda t: t.add("x", "world", np.eye(4)), ArgumentTypeError, "x",
         "pose", "got ndarray"),
    Call("add-moving-without-reference", lambda t: t.add("x", "world", moving()),
         ReferenceTimeError, "x", "reference_time", "has no reference time"),
    # FrameTree.attach_joint
    Call("attach-joint-a-string", lambda t: t.attach_joint("x", "world", "revolute"),
         ArgumentTypeError, "x", "joint", "got str"),
    Call("attach-joint-name-taken",
         lambda t: t.attach_joint("x", "world", Joint("arm/j1", "revolute")),
         FrameExistsError, "x", "joint", "already has a joint"),
    Call("attach-joint-moving-origin",
         lambda t: t.attach_joint("x", "world", Joint("k", "revolute"), moving(START)),
         InvalidPoseError, "x", "origin", "must be static"),
    Call("attach-joint-origin-a-list",
         lambda t: t.attach_joint("x", "world", Joint("k", "revolute"), [0, 0, 0]),
         ArgumentTypeError, "x", "origin", "got list"),
    # FrameTree.attach_urdf
    Call("attach-urdf-unknown-parent", lambda t: t.attach_urdf(ARM, "ghost"),
         FrameNotFoundError, None, "parent", "'ghost' is not in the tree"),
    Call("attach-urdf-twice", lambda t: t.attach_urdf(MIMIC_ARM, "world", prefix="arm/"),
         FrameExistsError, "arm/a", None, "another prefix"),
    Call("attach-urdf-prefix-a-number", lambda t: t.attach_urdf(ARM, "world", prefix=5),
         ArgumentTypeError, None, "prefix", "got int"),
    Call("attach-urdf-pose-a-matrix",
         lambda t: t.attach_urdf(ARM, "world", pose=np.eye(4), prefix="b/"),
         ArgumentTypeError, "b/a", "pose", "got ndarray"),
    Call("attach-urdf-moving-without-reference",
         lambda t: t.attach_urdf(ARM, "world", pose=moving(), prefix="b/"),
         ReferenceTimeError, "b/a", "reference_time", "has no reference time"),
    Call("attach-urdf-path-a-number", lambda t: t.attach_urdf(7, "world"), ArgumentTypeError,
         None, "path", "got int"),
    Call("attach-urdf-mimic-cycle",
         lambda t: t.attach_urdf(urdf(joint("j1", "a", "b", inner='<mimic joint="j1"/>'),
                                      "a b"), "world", prefix="b/"),
         FileFormatError, "j1", "mimic.joint", "mimic cycle: j1 -> j1"),
    # FrameTree.set_joint_trajectory
    Call("trajectory-unknown-joint", lambda t: t.set_joint_trajectory([0.0], [[1.0]], ["ghost"]),
         JointNotFoundError, None, "joint_names", "no joint named 'ghost'"),
    Call("trajectory-mimic-joint",
         lambda t: t.set_joint_trajectory([START], [[1.0]], ["arm/j2"]),
         JointError, None, "joint_names", "joint 'arm/j2' is a mimic joint"),
    Call("trajectory-names-a-string",
         lambda t: t.set_joint_trajectory([START], [[1.0]], "arm/j1"),
         ArgumentTypeError, None, "joint_names", "got the string"),
    Call("trajectory-names-repeat",
         lambda t: t.set_joint_trajectory([START], [[1.0, 2.0]], ["arm/j1", "arm/j1"]),
         JointError, None, "joint_names", "repeat"),
    Call("trajectory-times-decreasing",
         lambda t: t.set_joint_trajectory(["2024-03-01T08:00:01", "2024-03-01T08:00:00"],
                                          [[0.0], [1.0]], ["arm/j1"]),
         InvalidTimeError, None, "times", "strictly increasing"),
    Call("trajectory-times-duplicate",
         lambda t: t.set_joint_trajectory([START, START], [[0.0], [1.0]], ["arm/j1"]),
         InvalidTimeError, None, "times", "strictly increasing"),
    Call("trajectory-shape-mismatch",
         lambda t: t.set_joint_trajectory([START], [[0.0], [1.0]], ["arm/j1"]),
         JointError, None, "positions", "shape (2, 1), expected (1, 1)"),
    Call("trajectory-nan", lambda t: t.set_joint_trajectory([START], [[np.nan]], ["arm/j1"]),
         JointError, "arm/j1", "positions", "non-finite"),
    Call("trajectory-text", lambda t: t.set_joint_trajectory([START], [["up"]], ["arm/j1"]),
         JointError, None, "positions", "expected numbers"),
    Call("trajectory-huge-integer",
         lambda t: t.set_joint_trajectory([START], [[10**400]], ["arm/j1"]),
         JointError, None, "positions", "expected numbers"),
    Call("trajectory-times-overflow",
         lambda t: t.set_joint_trajectory([0.0, 1e300], [[0.0], [1.0]], ["arm/j1"]),
         InvalidTimeError, None, "times", "292 years"),
    Call("trajectory-relative-times-among-referenced-frames",
         lambda t: t.set_joint_trajectory([0.0, 1.0], [[0.0], [1.0]], ["arm/j1"]),
         ReferenceTimeError, "arm/j1", "reference_time", "has no reference time"),
    # FrameTree.set_local_pose
    Call("set-pose-a-matrix", lambda t: t.set_local_pose("table", np.eye(4)),
         ArgumentTypeError, "table", "pose", "got ndarray"),
    Call("set-pose-of-root", lambda t: t.set_local_pose("world", Pose()), TreeStructureError,
         "world", None, "no parent"),
    Call("set-pose-unknown", lambda t: t.set_local_pose("ghost", Pose()), FrameNotFoundError,
         "ghost", None, "no frame"),
    Call("set-pose-moving-joint-origin", lambda t: t.set_local_pose("arm/b", moving(START)),
         InvalidPoseError, "arm/b", "pose", "must be static"),
    Call("set-pose-moving-without-reference", lambda t: t.set_local_pose("turntable", moving()),
         ReferenceTimeError, "turntable", "reference_time", "has no reference time"),
    # FrameTree.pose
    Call("pose-unknown-frame", lambda t: t.pose("ghost", "world"), FrameNotFoundError, "ghost",
         None, "no frame"),
    Call("pose-unknown-reference", lambda t: t.pose("table", "ghost"), FrameNotFoundError,
         "ghost", None, "no frame"),
    Call("pose-frame-a-list", lambda t: t.pose(["table"], "world"), ArgumentTypeError, None,
         "frame", "got list"),
    Call("pose-of-root-without-reference", lambda t: t.pose("world"), TreeStructureError,
         "world", "relative_to", "no parent"),
    Call("pose-times-text", lambda t: t.pose("turntable", "world", times="soon"),
         InvalidTimeError, None, "times", "cannot read a time"),
    Call("pose-times-overflow", lambda t: t.pose("turntable", "world", times=[10**30]),
         InvalidTimeError, None, "times", "292 years"),
    Call("pose-timestamp-out-of-range",
         lambda t: t.pose("turntable", "world", times=["2500-01-01T00:00:00"]),
         InvalidTimeError, None, "times", "292 years"),
    Call("pose-unknown-extrapolation",
         lambda t: t.pose("turntable", "world", extrapolation="linear"),
         ExtrapolationError, None, "extrapolation", "got 'linear'"),
    Call("pose-outside-keyframes",
         lambda t: t.pose("turntable", "world", times=[START + np.timedelta64(9, "s")],
                          extrapolation="error"),
         ExtrapolationError, "turntable", "times", "after its last keyframe"),
    # FrameTree.rename and remove
    Call("rename-to-existing", lambda t: t.rename("table", "turntable"), FrameExistsError,
         "turntable", None, "already has a frame"),
    Call("rename-unknown", lambda t: t.rename("ghost", "x"), FrameNotFoundError, "ghost", None,
         "no frame"),
    Call("rename-to-a-number", lambda t: t.rename("table", 3), ArgumentTypeError, None, "name",
         "got int"),
    Call("remove-root", lambda t: t.remove("world"), TreeStructureError, "world", None,
         "cannot be removed"),
    Call("remove-with-children", lambda t: t.remove("table"), TreeStructureError, "table",
         None, "recursive=True"),
    Call("remove-unknown", lambda t: t.remove("ghost", recursive=True), FrameNotFoundError,
         "ghost", None, "no frame"),
    # Pose, Joint and FrameTree constructors (no tree involved; it must stay as it is anyway)
    Call("pose-translation-two-numbers", lambda t: Pose([1.0, 2.0]), InvalidPoseError, None,
         "translation", "got (2,)"),
    Call("pose-translation-nan", lambda t: Pose([np.nan, 0.0, 0.0]), InvalidPoseError, None,
         "translation", "finite"),
    Call("pose-translation-text", lambda t: Pose("abc"), InvalidPoseError, None,
         "translation", "expected numbers"),
    Call("pose-sheared-rotation", lambda t: Pose(rotation=SHEARED), InvalidPoseError, None,
         "rotation", "not orthonormal"),
    Call("pose-reflection", lambda t: Pose(rotation=REFLECTION), InvalidPoseError, None,
         "rotation", "reflection"),
    Call("pose-zero-quaternion", lambda t: Pose(rotation=[0, 0, 0, 0]), InvalidPoseError, None,
         "rotation", "unit norm"),
    Call("pose-rotation-2x2", lambda t: Pose(rotation=np.eye(2)), InvalidPoseError, None,
         "rotation", "got shape (2, 2)"),
    Call("pose-times-decreasing",
         lambda t: Pose([[0, 0, 0], [1, 0, 0]], times=[1.0, 0.0]), InvalidTimeError, None,
         "times", "strictly increasing"),
    Call("pose-times-duplicate", lambda t: Pose([[0, 0, 0], [1, 0, 0]], times=["1s", "1000ms"]),
         InvalidTimeError, None, "times", "strictly increasing"),
    Call("pose-samples-for-other-times",
         lambda t: Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0, 2.0]), InvalidPoseError, None,
         "translation", "2 samples given for 3 times"),
    Call("pose-reference-without-times", lambda t: Pose(reference_time=START),
         InvalidTimeError, None, "reference_time", "needs times"),
    Call("pose-times-mixed-kinds",
         lambda t: Pose([[0, 0, 0], [1, 0, 0]], times=["2024-01-01T00:00:00", "2s"]),
         InvalidTimeError, None, "times", "mixes absolute"),
    Call("pose-times-integer-overflow", lambda t: Pose([0, 0, 0], times=[10**30]),
         InvalidTimeError, None, "times", "292 years"),
    Call("pose-date-out-of-range",
         lambda t: Pose([0, 0, 0], times=np.array(["9999-12-31"], dtype="datetime64[D]")),
         InvalidTimeError, None, "times", "292 years"),
    Call("pose-span-out-of-range",
         lambda t: Pose([[0, 0, 0], [1, 0, 0]],
                        times=["1700-01-01T00:00:00", "2200-01-01T00:00:00"]),
         InvalidTimeError, None, "times", "292 years"),
    Call("xyz-rpy-text", lambda t: Pose.from_xyz_rpy(x="a"), InvalidPoseError, None, "xyz_rpy",
         "expected numbers"),
    Call("xyz-rpy-nan", lambda t: Pose.from_xyz_rpy(yaw=float("nan")), InvalidPoseError, None,
         "xyz_rpy", "finite"),
    Call("xyz-rpy-huge-integer", lambda t: Pose.from_xyz_rpy(10**400), InvalidPoseError, None,
         "xyz_rpy", "expected numbers"),
    Call("matrix-bad-bottom-row", lambda t: Pose.from_matrix(BAD_BOTTOM), InvalidPoseError,
         None, "matrix", "(0, 0, 0, 1)"),
    Call("matrix-3x3", lambda t: Pose.from_matrix(np.eye(3)), InvalidPoseError, None, "matrix",
         "got (3, 3)"),
    Call("joint-unknown-kind", lambda t: Joint("k", "hinge"), JointError, "k", "type",
         "unknown joint kind"),
    Call("joint-zero-axis", lambda t: Joint("k", "revolute", (0, 0, 0)), JointError, "k",
         "axis", "non-zero"),
    Call("tree-reference-time-text", lambda t: FrameTree(reference_time="soon"),
         InvalidTimeError, None, "reference_time", "cannot read a time"),
    Call("tree-root-a-number", lambda t: FrameTree(root=1), ArgumentTypeError, None, "name",
         "got int"),
]
