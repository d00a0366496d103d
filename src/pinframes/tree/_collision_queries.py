"""`CollisionQueries`: the clearance between the shapes of a tree's frames.

Names and glob patterns turned into frames with geometry, the pairs left out (given, or
disabled by the robots' SRDFs), then the tree's
:class:`~pinframes.kinematics.TreeDescription` of this version handed to
:mod:`pinframes.kinematics.collision`, which does the work.
"""

from __future__ import annotations

import fnmatch
import os
from collections.abc import Iterable, Sequence
from typing import Any

from ..errors import ArgumentTypeError, FrameNotFoundError, GeometryError, near_misses
from ..kinematics import Clearance, TreeDescription, clearance_times, evaluate_clearance
from ..kinematics.collision.mesh_reader import DEFAULT_BOUNDS, MeshBounds
from ..values.timeconv import TimeAxis
from ._queries import TreeQueries
from .robot_semantics import disabled_frame_pairs

__all__ = ["CollisionQueries"]


class CollisionQueries(TreeQueries):
    """:class:`TreeQueries` with the clearance between frames' shapes."""

    def clearance(
        self, a: str | Sequence[str], b: str | Sequence[str], *, times: Any = None,
        time_ref: Any = None, package_dirs: Iterable[str | os.PathLike[str]] = (),
        geometry: str = "collision", exclude: Iterable[tuple[str, str]] = (),
        extrapolation: str = "clamp", srdf_exclude: bool = True, limits: Any = None,
    ) -> Clearance:
        """The smallest distance between the shapes of the frames ``a`` and ``b``, per sample.

        Parameters
        ----------
        a, b : str or sequence of str
            Frame names or glob patterns over frame names (``"robot/*"``). Their geometry
            is the ``<collision>`` (or, with ``geometry="visual"``, ``<visual>``) geometry
            of the URDF links among them and the shapes :meth:`add_geometry` gave them:
            boxes, cylinders, spheres and meshes. A frame
            named outright must have such geometry; a pattern takes the frames it matches
            that have some (a link such as ``tool0`` without any is left out, as
            ``pinocchio.buildGeomFromUrdf`` leaves it out) and must take at least one.
            Every pair of one frame of ``a`` and one of ``b`` (not the same frame) is
            checked, each pair once.
        times, time_ref, extrapolation
            As for :meth:`pose`; ``times=None`` takes every keyframe and joint sample time
            on the paths from the root to the frames of ``a`` and ``b``.
        package_dirs : iterable of path
            Folders searched first for ``package://``, ``model://`` and relative mesh names
            (then those given when the robot was read, ``ROS_PACKAGE_PATH``, for
            ``model://`` ``GAZEBO_MODEL_PATH``, then the URDF's folder and its ancestors).
        geometry : {"collision", "visual"}
            Which geometry of the links.
        exclude : iterable of (str, str)
            Pairs of frame names or patterns not to check, in either order (a torch that
            works at the seam, a robot standing on its base).
        srdf_exclude : bool
            Also leave out the link pairs whose collisions the robots' SRDFs disable
            (``srdf=`` when the robot was read; default True). The pairs left out are in
            :attr:`Clearance.excluded`.

            Pairs whose distance cannot change (no robot joint and no moving frame between
            the two frames: links bolted together by a fixed joint) are left out too, unless
            both frames are named outright; they are in :attr:`Clearance.fixed_together`.
        limits : pinframes.Limits or None
            Its ``max_triangles`` bounds the triangles of each mesh file after
            instancing, its ``max_decompressed_bytes`` the file's size (None: 1,000,000
            triangles, any size; the command line passes its ``--max-...`` options).

        Returns
        -------
        Clearance
            ``distance`` (T,) m, smallest over the pairs, negative when primitives overlap;
            ``closest`` (T, 2) the pair's frames; ``point_a``, ``point_b`` (T, 3) m in the
            root's axes; ``times``, ``seconds``, ``reference_time``; ``first_contact``.
            Distances are coal's, as ``pinocchio.computeDistances`` computes them on the
            same URDF geometry; but a closed mesh is a solid here (a shape wholly inside it
            is in contact, at minus the distance between their surfaces), and COLLADA
            meshes are in the unit their file gives.

        Raises
        ------
        GeometryError
            A frame without geometry, a malformed shape, a mesh missing, unreadable or of more
        triangles than ``max_triangles``, a shape not finite or placed beyond 1e9 m.
        FrameNotFoundError
            A name that is no frame and a pattern that matches none.
        """
        frames_a = self._frames_with_geometry(a, geometry, "a")
        frames_b = self._frames_with_geometry(b, geometry, "b")
        excluded = [(first, second) for pattern_a, pattern_b in exclude
                    for first in self._frames_matching(pattern_a, "exclude")
                    for second in self._frames_matching(pattern_b, "exclude")]
        if srdf_exclude:
            excluded += disabled_frame_pairs(self, [*frames_a, *frames_b])
        recorded = {frame: self._recorded_geometry(frame) for frame in [*frames_a, *frames_b]}
        bounds = DEFAULT_BOUNDS if limits is None else MeshBounds(
            limits.max_triangles, limits.max_decompressed_bytes)
        description = self._frozen()
        return evaluate_clearance(description, recorded, frames_a, frames_b, excluded,
                                  geometry, package_dirs, times, time_ref, extrapolation,
                                  bounds, _fixed_together(description, frames_a, frames_b,
                                                          _named_outright(a, b), excluded))

    def clearance_times(self, a: str | Sequence[str], b: str | Sequence[str], *,
                        geometry: str = "collision") -> TimeAxis | None:
        """The times :meth:`clearance` evaluates at when given none, without evaluating:
        every keyframe and joint sample time on the paths from the root to the frames of
        ``a`` and ``b`` (as a :class:`~pinframes.TimeAxis`); None when nothing on them moves.
        """
        frames = [*self._frames_with_geometry(a, geometry, "a"),
                  *self._frames_with_geometry(b, geometry, "b")]
        return clearance_times(self._frozen(), frames)

    def _frames_matching(self, names: str | Sequence[str], field: str) -> list[str]:
        """The frames that ``names`` (names or glob patterns) name, each once, in order."""
        if isinstance(names, str):
            names = [names]
        found: dict[str, None] = {}
        for name in names:
            if not isinstance(name, str):
                raise ArgumentTypeError(f"expected frame names, got {type(name).__name__}",
                                        field=field)
            if name in self._children:
                found[name] = None
                continue
            matched = fnmatch.filter(self._children, name) if _is_pattern(name) else []
            if not matched:
                raise FrameNotFoundError(
                    f"{'pattern' if _is_pattern(name) else 'frame'} {name!r} names no frame"
                    + near_misses(name, self._children), field=field)
            found.update(dict.fromkeys(matched))
        return list(found)

    def _frames_with_geometry(self, names: str | Sequence[str], kind: str,
                              field: str) -> list[str]:
        """:meth:`_frames_matching`, keeping of what patterns match only the frames that have
        ``kind`` geometry (one named outright is kept: the query then says what it lacks)."""
        outright = {names} if isinstance(names, str) else set(names)
        kept = []
        for frame in self._frames_matching(names, field):
            recorded = self._recorded_geometry(frame)
            if frame in outright or (recorded is not None and (
                    recorded.shapes(kind) or recorded.unreadable_shapes(kind))):
                kept.append(frame)
        if not kept:
            raise GeometryError(f"{', '.join(map(repr, outright))} match no frame with {kind} "
                                "geometry (only the links of attached URDFs and frames given "
                                "shapes by add_geometry have some)",
                                field=field)
        return kept


def _named_outright(a: str | Sequence[str], b: str | Sequence[str]) -> set[str]:
    """The names of ``a`` and ``b`` that are no glob patterns."""
    names = [*([a] if isinstance(a, str) else a), *([b] if isinstance(b, str) else b)]
    return {name for name in names if isinstance(name, str) and not _is_pattern(name)}


def _fixed_together(description: TreeDescription, frames_a: list[str], frames_b: list[str],
                    outright: set[str], excluded: list[tuple[str, str]]
                    ) -> list[tuple[str, str]]:
    """The pairs of one frame of ``frames_a`` and one of ``frames_b`` whose distance cannot
    change: both hang from the same robot joint or moving frame (their anchor), with only
    fixed placements between. A pair whose two frames are both named outright stays in, and
    a pair already ``excluded`` is not listed again."""
    anchor_b = {frame: description.anchor(frame)[0] for frame in frames_b}
    skipped = {frozenset(pair) for pair in excluded}
    found: dict[frozenset[str], tuple[str, str]] = {}
    for first in frames_a:
        anchor = description.anchor(first)[0]
        for second in frames_b:
            pair = frozenset((first, second))
            if (first != second and anchor_b[second] == anchor and pair not in found
                    and pair not in skipped and not {first, second} <= outright):
                found[pair] = (first, second)
    return list(found.values())


def _is_pattern(name: str) -> bool:
    """Whether ``name`` holds glob characters (``*``, ``?``, ``[``)."""
    return any(character in name for character in "*?[")
