"""An independent numpy model of a frame tree, to check pinframes against.

A :class:`TreeSpec` lists frames (static or keyframed) and robots (URDF text, mount pose and
joint samples) as plain arrays. :meth:`TreeSpec.pose_in_root` evaluates it with hand-written
numpy only: rotations about an axis by Rodrigues' formula, keyframe rotations stepped about
the axis each step was drawn with (so no quaternion, SLERP or matrix logarithm of pinframes
is involved), URDF joints read with ElementTree. :func:`build_tree` hands the same spec to
pinframes' public API.

Times are int64 nanoseconds. A spec is *relative* (no reference time anywhere: offsets are
the instants) or *absolute* (every moving thing has a reference time: instants are
nanoseconds since the epoch).
"""

from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace

import numpy as np

import pinframes
from pinframes import JointLimitWarning


def axis_rotation(axis, angles) -> np.ndarray:
    """Rotations (N, 3, 3) by ``angles`` (N,) radians about the unit ``axis`` (Rodrigues)."""
    x, y, z = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    cross = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    angles = np.atleast_1d(np.asarray(angles, dtype=float))
    return (np.eye(3) + np.sin(angles)[:, None, None] * cross
            + (1.0 - np.cos(angles))[:, None, None] * (cross @ cross))


def rpy_rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw) @ Ry(pitch) @ Rx(roll)``, the URDF convention."""
    return (axis_rotation((0, 0, 1), yaw)[0] @ axis_rotation((0, 1, 0), pitch)[0]
            @ axis_rotation((1, 0, 0), roll)[0])


def homogeneous(rotations: np.ndarray, translations: np.ndarray) -> np.ndarray:
    """Stacks of 4x4 matrices from rotations (N, 3, 3) and translations (N, 3)."""
    out = np.zeros((*rotations.shape[:-2], 4, 4))
    out[..., :3, :3] = rotations
    out[..., :3, 3] = translations
    out[..., 3, 3] = 1.0
    return out


def segments(sample_times: np.ndarray, instants: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each instant: the segment index k and the fraction in [0, 1] between samples k, k+1.

    Before the first sample: (0, 0); after the last: (last segment, 1) (held poses).
    """
    if len(sample_times) == 1:
        return np.zeros(len(instants), dtype=int), np.zeros(len(instants))
    index = np.clip(np.searchsorted(sample_times, instants, side="right") - 1, 0,
                    len(sample_times) - 2)
    start, stop = sample_times[index], sample_times[index + 1]
    fraction = np.clip((instants - start) / (stop - start), 0.0, 1.0)
    return index, fraction


@dataclass(frozen=True)
class Keyframes:
    """A moving pose: keyframe k+1's rotation is keyframe k's turned by ``step_angles[k]``.

    ``times`` are ns after ``reference`` (ns since the epoch), or instants when it is None.
    """

    times: np.ndarray
    reference: int | None
    translations: np.ndarray
    start_rotation: np.ndarray
    step_axes: np.ndarray
    step_angles: np.ndarray

    def rotations(self) -> np.ndarray:
        rotations = [self.start_rotation]
        for axis, angle in zip(self.step_axes, self.step_angles, strict=True):
            rotations.append(rotations[-1] @ axis_rotation(axis, angle)[0])
        return np.array(rotations)

    def instants(self) -> np.ndarray:
        return self.times + (self.reference or 0)

    def matrices(self, instants: np.ndarray) -> np.ndarray:
        """Poses (N, 4, 4) at ``instants``: linear translation, rotation about the step axis."""
        index, fraction = segments(self.instants(), instants)
        rotations = self.rotations()
        if len(self.times) == 1:
            return homogeneous(np.broadcast_to(rotations[0], (len(instants), 3, 3)),
                               np.broadcast_to(self.translations[0], (len(instants), 3)))
        turned = np.array([rotations[k] @ axis_rotation(self.step_axes[k],
                                                         f * self.step_angles[k])[0]
                           for k, f in zip(index, fraction, strict=True)])
        moved = ((1.0 - fraction)[:, None] * self.translations[index]
                 + fraction[:, None] * self.translations[index + 1])
        return homogeneous(turned, moved)

    def pose(self) -> pinframes.Pose:
        reference = None if self.reference is None else np.datetime64(self.reference, "ns")
        return pinframes.Pose(self.translations, self.rotations(),
                              times=self.times.astype("timedelta64[ns]"),
                              reference_time=reference)


@dataclass(frozen=True)
class FrameItem:
    """A frame at a static ``matrix`` (4, 4) in ``parent``, or moving by ``keyframes``."""

    name: str
    parent: str
    matrix: np.ndarray
    keyframes: Keyframes | None = None


@dataclass(frozen=True)
class UrdfJoint:
    """A URDF joint as read here with ElementTree (names without the mount prefix)."""

    name: str
    kind: str
    parent: str
    child: str
    origin: np.ndarray
    axis: np.ndarray
    mimic: tuple[str, float, float] | None


def urdf_joints(text: str) -> list[UrdfJoint]:
    """The joints of a URDF, read with ElementTree."""
    joints = []
    for element in ET.fromstring(text).iter("joint"):
        origin = element.find("origin")
        xyz = [float(v) for v in (origin.get("xyz", "0 0 0") if origin is not None
                                  else "0 0 0").split()]
        rpy = [float(v) for v in (origin.get("rpy", "0 0 0") if origin is not None
                                  else "0 0 0").split()]
        axis_element = element.find("axis")
        axis = np.array([float(v) for v in (axis_element.get("xyz") if axis_element is not None
                                            else "1 0 0").split()])
        mimic_element = element.find("mimic")
        mimic = None if mimic_element is None else (
            mimic_element.get("joint"), float(mimic_element.get("multiplier", 1.0)),
            float(mimic_element.get("offset", 0.0)))
        joints.append(UrdfJoint(
            element.get("name"), element.get("type"), element.find("parent").get("link"),
            element.find("child").get("link"), homogeneous(rpy_rotation(*rpy), np.array(xyz)),
            axis / np.linalg.norm(axis), mimic))
    return joints


@dataclass(frozen=True)
class RobotItem:
    """A robot mounted at static ``mount`` (4, 4) in ``parent``, driven by joint samples.

    ``positions`` (T, n) are the values of the ``driven`` joints (URDF names) at ``times``
    (ns after ``reference``, or instants when it is None).
    """

    urdf: str
    parent: str
    prefix: str
    mount: np.ndarray
    times: np.ndarray
    reference: int | None
    driven: tuple[str, ...]
    positions: np.ndarray

    def root_link(self) -> str:
        joints = urdf_joints(self.urdf)
        children = {joint.child for joint in joints}
        links = [e.get("name") for e in ET.fromstring(self.urdf).iter("link")]
        return next(link for link in links if link not in children)

    def joint_values(self, instants: np.ndarray) -> dict[str, np.ndarray]:
        """Every joint's value at ``instants``: samples linear in between, held outside."""
        index, fraction = segments(self.times + (self.reference or 0), instants)
        values = {}
        for column, name in enumerate(self.driven):
            samples = self.positions[:, column]
            if len(samples) == 1:
                values[name] = np.full(len(instants), samples[0])
            else:
                values[name] = ((1.0 - fraction) * samples[index]
                                + fraction * samples[index + 1])
        for joint in urdf_joints(self.urdf):
            if joint.mimic is not None:
                master, multiplier, offset = joint.mimic
                values[joint.name] = multiplier * values.get(
                    master, np.zeros(len(instants))) + offset
        return values

    def link_matrices(self, instants: np.ndarray) -> dict[str, tuple[str, np.ndarray]]:
        """Each link frame's parent frame and its poses (N, 4, 4) in it."""
        values = self.joint_values(instants)
        count = len(instants)
        out = {self.prefix + self.root_link(): (self.parent,
                                                np.broadcast_to(self.mount, (count, 4, 4)))}
        for joint in urdf_joints(self.urdf):
            q = values.get(joint.name, np.zeros(count))
            if joint.kind in ("revolute", "continuous"):
                motion = homogeneous(axis_rotation(joint.axis, q), np.zeros((count, 3)))
            elif joint.kind == "prismatic":
                motion = homogeneous(np.broadcast_to(np.eye(3), (count, 3, 3)),
                                     q[:, None] * joint.axis)
            else:
                motion = np.broadcast_to(np.eye(4), (count, 4, 4))
            out[self.prefix + joint.child] = (self.prefix + joint.parent, joint.origin @ motion)
        return out

    def instants(self) -> np.ndarray:
        return self.times + (self.reference or 0)

    def query_times(self):
        """The joint sample times as handed to pinframes."""
        if self.reference is None:
            return self.times.astype("timedelta64[ns]")
        return (self.times + self.reference).astype("datetime64[ns]")


@dataclass(frozen=True)
class TreeSpec:
    """A whole tree: the root, an optional reference time and frames and robots in order."""

    root: str
    reference: int | None
    items: tuple[FrameItem | RobotItem, ...]

    @property
    def is_absolute(self) -> bool:
        return any(item.reference is not None for item in self.moving_items())

    def moving_items(self) -> list[Keyframes | RobotItem]:
        return [item.keyframes if isinstance(item, FrameItem) else item
                for item in self.items
                if isinstance(item, RobotItem) or item.keyframes is not None]

    def local_matrices(self, instants: np.ndarray) -> dict[str, tuple[str, np.ndarray]]:
        """Every frame's parent and its poses (N, 4, 4) in it at ``instants``."""
        out = {}
        for item in self.items:
            if isinstance(item, RobotItem):
                out.update(item.link_matrices(instants))
            elif item.keyframes is not None:
                out[item.name] = (item.parent, item.keyframes.matrices(instants))
            else:
                out[item.name] = (item.parent,
                                  np.broadcast_to(item.matrix, (len(instants), 4, 4)))
        return out

    def parents(self) -> dict[str, str]:
        return {name: parent for name, (parent, _) in self.local_matrices(np.zeros(1)).items()}

    def poses_in_root(self, instants: np.ndarray) -> dict[str, np.ndarray]:
        """Every frame's poses (N, 4, 4) in the root at ``instants``, by numpy matmul."""
        local = self.local_matrices(instants)
        world = {self.root: np.broadcast_to(np.eye(4), (len(instants), 4, 4))}

        def resolve(name: str) -> np.ndarray:
            if name not in world:
                parent, matrices = local[name]
                world[name] = resolve(parent) @ matrices
            return world[name]

        for name in local:
            resolve(name)
        return world

    def instants(self) -> np.ndarray:
        """Keyframe and joint sample instants, their midpoints and one before and after."""
        keyed = [item.instants() for item in self.moving_items()]
        if not keyed:
            return np.array([0 if self.reference is None else self.reference])
        union = np.unique(np.concatenate(keyed))
        middles = union[:-1] + np.diff(union) // 2
        return np.unique(np.concatenate([union, middles, [union[0] - 10**9,
                                                          union[-1] + 10**9]]))

    def query_times(self, instants: np.ndarray):
        """``instants`` as pinframes takes them: durations, or timestamps when absolute."""
        if self.is_absolute:
            return instants.astype("datetime64[ns]")
        return instants.astype("timedelta64[ns]")


def build_tree(spec: TreeSpec) -> pinframes.FrameTree:
    """The tree of ``spec``, built with pinframes' public API."""
    reference = None if spec.reference is None else np.datetime64(spec.reference, "ns")
    tree = pinframes.FrameTree(spec.root, reference_time=reference)
    for item in spec.items:
        if isinstance(item, RobotItem):
            tree.attach_urdf(item.urdf, item.parent, pinframes.Pose.from_matrix(item.mount),
                             prefix=item.prefix)
            drive(tree, item)
        elif item.keyframes is not None:
            tree.add(item.name, item.parent, item.keyframes.pose())
        else:
            tree.add(item.name, item.parent, pinframes.Pose.from_matrix(item.matrix))
    return tree


def drive(tree: pinframes.FrameTree, robot: RobotItem) -> None:
    """Set ``robot``'s joint samples on ``tree`` (for a tree read back from a URDF too)."""
    if robot.driven:
        with warnings.catch_warnings():  # random values leave the welding robot's limits
            warnings.simplefilter("ignore", JointLimitWarning)
            tree.set_joint_trajectory(robot.query_times(), robot.positions,
                                      [robot.prefix + name for name in robot.driven])


def shifted_to_absolute(spec: TreeSpec, start: int, shifts: list[int],
                        tree_reference: int | None) -> TreeSpec:
    """``spec`` (relative) with its instant 0 at ``start`` ns since the epoch.

    Moving thing i gets the reference time ``start + shifts[i]`` and its times move back
    by ``shifts[i]``, so every keyframe keeps its instant ``start + offset``.
    """
    items, moving = [], 0
    for item in spec.items:
        if isinstance(item, RobotItem):
            item = replace(item, times=item.times - shifts[moving],
                           reference=start + shifts[moving])
            moving += 1
        elif item.keyframes is not None:
            keyframes = replace(item.keyframes, times=item.keyframes.times - shifts[moving],
                                reference=start + shifts[moving])
            item = replace(item, keyframes=keyframes)
            moving += 1
        items.append(item)
    return TreeSpec(spec.root, tree_reference, tuple(items))
