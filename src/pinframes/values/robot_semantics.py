"""What a robot's SRDF says about it: joint groups, named joint states, link pairs never checked.

An SRDF (MoveIt's semantic robot description, also read by Tesseract) sits beside a URDF and
names things in the URDF's own link and joint names. :class:`RobotSemantics` keeps what
pinframes uses, already resolved against the URDF: a group is the tuple of its driven joints
(chains, joints, links and subgroups expanded as MoveIt expands them), a group state the
values of those joints, and the disabled collision pairs are link pairs and links (a link
whose every pair is disabled is kept as one rule, not as its pairs).

The URDF mounter records one :class:`LinkSemantics` on every link frame of a robot read with
an SRDF (frame metadata :data:`SEMANTICS_METADATA_KEY`), so that renaming, grafting and
copying carry it; queries find a robot's links by their URDF link names through it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["SEMANTICS_METADATA_KEY", "GroupState", "LinkSemantics", "RobotSemantics"]

SEMANTICS_METADATA_KEY = "srdf"
"""Key of ``FrameTree.frame_metadata(frame)`` under which a link's :class:`LinkSemantics` lives."""


@dataclass(frozen=True)
class GroupState:
    """A named joint state of a group (``<group_state>``): radians or metres by URDF joint."""

    group: str
    values: dict[str, float]


@dataclass(frozen=True)
class RobotSemantics:
    """An SRDF resolved against its URDF; every name is the URDF's (no tree prefix).

    Attributes
    ----------
    source : str
        The SRDF file.
    groups : dict of str to tuple of str
        Group name -> its driven joints (revolute, continuous, prismatic; mimic joints
        left out, they follow their primaries), in the URDF's order from the root.
    states : dict of str to GroupState
        Group state name -> the state.
    disabled_pairs : frozenset of frozenset of str
        Link pairs whose collisions are never checked (``<disable_collisions>``).
    disabled_links : frozenset of str
        Links none of whose pairs is checked (``<disable_default_collisions>``).
    enabled_pairs : frozenset of frozenset of str
        Link pairs checked even so (``<enable_collisions>``): exceptions to the two above.
    joint_links : dict of str to str
        URDF joint name -> its child link, how a joint is found among a tree's frames.
    link_parents : dict of str to str
        URDF link name -> its parent link (the root link has none).
    root_link : str
        The URDF's root link.
    """

    source: str
    groups: dict[str, tuple[str, ...]] = field(default_factory=dict)
    states: dict[str, GroupState] = field(default_factory=dict)
    disabled_pairs: frozenset[frozenset[str]] = field(default_factory=frozenset)
    joint_links: dict[str, str] = field(default_factory=dict)
    link_parents: dict[str, str] = field(default_factory=dict)
    root_link: str = ""
    disabled_links: frozenset[str] = field(default_factory=frozenset)
    enabled_pairs: frozenset[frozenset[str]] = field(default_factory=frozenset)

    def disables(self, link_a: str, link_b: str) -> bool:
        """Whether the SRDF leaves the pair of links ``link_a``, ``link_b`` unchecked."""
        pair = frozenset((link_a, link_b))
        if link_a == link_b or pair in self.enabled_pairs:
            return False
        return (pair in self.disabled_pairs or link_a in self.disabled_links
                or link_b in self.disabled_links)

    @property
    def links(self) -> frozenset[str]:
        """The URDF's links."""
        return frozenset(self.link_parents) | {self.root_link}

    def disabled_pair_count(self) -> int:
        """How many pairs of the URDF's links the SRDF leaves unchecked (counted, not
        listed: a disabled link stands for a pair with every other link)."""
        every = len(self.links)
        held = len(self.disabled_links)
        by_link = held * (every - held) + held * (held - 1) // 2
        by_name = sum(1 for pair in self.disabled_pairs if not pair & self.disabled_links)
        enabled = sum(1 for pair in self.enabled_pairs
                      if len(pair) == 2 and (pair & self.disabled_links
                                             or pair in self.disabled_pairs))
        return by_link + by_name - enabled


@dataclass(frozen=True)
class LinkSemantics:
    """The SRDF of the robot a link frame belongs to, and the link's URDF name."""

    link: str
    robot: RobotSemantics
