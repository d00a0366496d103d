"""``FrameTree.clearance``: the smallest distance between two sets of link geometries, per sample.

Every frame's pose in the root comes from the pose queries (:mod:`.poses`), on one timeline
that follows the rules of ``pose()`` for all the moving things on the frames' paths. The
distance of a pair of shapes is coal's ``distance`` on the objects of
:mod:`.coal_objects` (what ``pinocchio.computeDistances`` computes on the same URDF).

Most pairs are far apart most of the time, so each shape carries a sphere that holds it: at
every sample the pairs are visited in the order of the distance between their spheres (a
lower bound of the pair's distance), and the visit stops at the first pair whose bound is not
below the smallest distance found. The pairs skipped cannot be closer, so the answer is the
one every pair would give.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import coal
import numpy as np
from numpy.typing import NDArray

from ...errors import GeometryError
from ...values.geometry import FrameGeometry
from ...values.timeconv import TimeAxis
from ...values.timed import Timed
from .._description import TreeDescription
from .._plan import QueryPlan, plan_query, prepare_path
from ..poses import planned_poses
from .coal_objects import LARGEST_COORDINATE, CollisionShape, ShapeLoader
from .mesh_reader import DEFAULT_BOUNDS, MeshBounds, TriangleBudget

__all__ = ["Clearance", "clearance_times", "evaluate_clearance"]

FloatArray = NDArray[np.float64]

CLEARANCE_CHUNK = 1 << 14
"""The most samples whose frame poses and sphere bounds are computed at once."""
_CHUNK_ELEMENTS = 1 << 21
"""Fewer samples at once for many pairs or shapes: a chunk's bounds (samples x pairs) and
placed shapes (samples x shapes x 12) stay within about 16 MB each."""


@dataclass(frozen=True)
class Clearance(Timed):
    """The smallest distance between the geometries of two sets of links, per sample.

    Attributes
    ----------
    distance : ndarray, shape (T,)
        Metres: the smallest distance over every pair of links (one of ``frames_a``, one of
        ``frames_b``); zero or negative when two shapes touch or overlap: minus the
        penetration depth for two primitives (boxes, cylinders, spheres: solids); zero or
        less for a mesh whose triangles cross another shape; for a shape wholly inside a
        closed mesh (a solid), minus the distance between their surfaces, which is at most
        the depth. An open mesh is a surface: a shape on either side of it is clear.
    closest : ndarray of str, shape (T, 2)
        The frames of that pair: one of ``frames_a``, then one of ``frames_b``.
    point_a, point_b : ndarray, shape (T, 3)
        The closest points of the pair's geometries (on the ``frames_a`` side, then on the
        ``frames_b`` side), metres in the axes and origin of the tree's root.
    times : ndarray of timedelta64[ns] or None
        Sample times after :attr:`reference_time`, as ``pose()`` chooses them; None when
        nothing moves and no times were given (then ``T`` is 1).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    frames_a, frames_b : tuple of str
        The frames whose geometry was checked on each side.
    excluded : tuple of (str, str)
        The pairs of frames left out: ``exclude=``, and those the robots' SRDFs disable.
    geometry : {"collision", "visual"}
        Which URDF geometry was used.
    fixed_together : tuple of (str, str)
        The pairs of frames left out because their distance cannot change: no robot joint
        and no moving frame lies between them (two links bolted together by a fixed joint).
    """

    distance: FloatArray
    closest: NDArray[np.str_]
    point_a: FloatArray
    point_b: FloatArray
    times: NDArray[np.timedelta64] | None
    reference_time: np.datetime64 | None
    frames_a: tuple[str, ...]
    frames_b: tuple[str, ...]
    excluded: tuple[tuple[str, str], ...]
    geometry: str
    fixed_together: tuple[tuple[str, str], ...] = ()

    def __len__(self) -> int:
        return int(self.distance.shape[0])

    @property
    def in_contact(self) -> NDArray[np.bool_]:
        """Per sample: whether the closest pair touches or overlaps (distance <= 0)."""
        return self.distance <= 0.0

    @property
    def first_contact(self) -> float | None:
        """The first sample time (seconds) at which the distance is <= 0, or None; 0.0 for a
        static result in contact."""
        touching = np.flatnonzero(self.in_contact)
        if touching.size == 0:
            return None
        seconds = self.seconds
        return 0.0 if seconds is None else float(seconds[touching[0]])

    @property
    def smallest(self) -> int:
        """The index of the sample with the smallest distance (the first, on a tie)."""
        return int(np.argmin(self.distance))


def evaluate_clearance(
    tree: TreeDescription, geometry: Mapping[str, FrameGeometry | None],
    frames_a: Sequence[str], frames_b: Sequence[str], excluded: Iterable[tuple[str, str]],
    kind: str, package_dirs: Iterable[str | os.PathLike[str]], times: Any, time_ref: Any,
    extrapolation: str, bounds: MeshBounds = DEFAULT_BOUNDS,
    fixed_together: Iterable[tuple[str, str]] = (),
) -> Clearance:
    """``tree.clearance(...)`` for frames already named and checked.

    ``geometry`` holds the recorded geometry of every frame of ``frames_a`` and
    ``frames_b``; ``excluded`` the frame pairs (either order) not to check, and
    ``fixed_together`` those left out because nothing moves between them;
    ``bounds`` what reading each mesh file, and all the request's meshes, may cost.
    """
    excluded, fixed_together = list(excluded), list(fixed_together)
    loader = _loader(tree, kind, package_dirs, bounds)
    frames = list(dict.fromkeys([*frames_a, *frames_b]))
    budget = TriangleBudget(bounds.max_triangles)  # the whole request's meshes
    shapes = [shape for frame in frames
              for shape in loader.shapes(frame, geometry[frame], budget)]
    skipped = {frozenset(pair) for pair in [*excluded, *fixed_together]}
    pairs = _shape_pairs(shapes, set(frames_a), set(frames_b), skipped)
    if not len(pairs):
        raise GeometryError("a and b leave no pair of two different frames to check (a frame "
                            "is never checked against itself; see also exclude, the pairs "
                            "an SRDF disables: srdf_exclude=False, --no-srdf-exclude, and "
                            f"the {len(fixed_together)} pairs fixed to each other, which "
                            "pinframes checks only when both frames are named outright)",
                            field="b")
    plan = _plan(tree, frames, times, time_ref, extrapolation)
    count = plan.count
    frame_index = {frame: position for position, frame in enumerate(frames)}
    owners = np.array([frame_index[shape.frame] for shape in shapes], dtype=np.intp)
    distance = np.empty(count)
    closest = np.empty((count, 2), dtype=np.intp)
    point_a, point_b = np.empty((count, 3)), np.empty((count, 3))
    chunk = max(16, min(CLEARANCE_CHUNK, _CHUNK_ELEMENTS // max(len(pairs), 12 * len(shapes))))
    roots = [tree.root] * len(frames)
    for part, piece in plan.parts(chunk):
        # every frame's pose in the root at these samples: (F, n, 3, 3) and (F, n, 3)
        poses = planned_poses(tree, frames, roots, piece)
        rotation, translation = poses.rotation, poses.translation
        if piece.offsets is None:
            rotation, translation = rotation[:, None], translation[:, None]
        rotation, translation = _placed_shapes(rotation, translation, shapes, owners)
        _require_placed(shapes, translation, piece.offsets)
        _closest_pairs(shapes, pairs, rotation, translation, distance[part], closest[part],
                       point_a[part], point_b[part])
    names = np.array([shape.frame for shape in shapes], dtype=np.str_)
    return Clearance(distance, names[closest], point_a, point_b,
                     plan.result_times, plan.reference_time, tuple(dict.fromkeys(frames_a)),
                     tuple(dict.fromkeys(frames_b)),
                     tuple(tuple(pair) for pair in excluded),  # type: ignore[misc]
                     kind, tuple(tuple(pair) for pair in fixed_together))  # type: ignore[misc]


def _loader(tree: TreeDescription, kind: str,
            package_dirs: Iterable[str | os.PathLike[str]], bounds: MeshBounds) -> ShapeLoader:
    """The shape loader of this tree version for ``kind``, these search folders and this
    bound (meshes are read once per version)."""
    folders = tuple(os.fspath(folder) for folder in package_dirs)
    key = ("clearance shapes", kind, repr(bounds), os.environ.get("ROS_PACKAGE_PATH", ""),
           *folders)
    loader = tree.memo.get(ShapeLoader, key)
    if loader is None:
        loader = tree.memo.keep(ShapeLoader, key, ShapeLoader(kind, folders, bounds))
    return loader


def _shape_pairs(shapes: list[CollisionShape], side_a: set[str], side_b: set[str],
                 skipped: set[frozenset[str]]) -> NDArray[np.intp]:
    """Shape index pairs ``(i, j)``: ``i`` on a frame of ``side_a``, ``j`` of ``side_b``, on
    different frames, not ``skipped``; each unordered pair once."""
    seen: set[frozenset[int]] = set()
    pairs = []
    for i, first in enumerate(shapes):
        if first.frame not in side_a:
            continue
        for j, second in enumerate(shapes):
            if (second.frame not in side_b or second.frame == first.frame
                    or frozenset((first.frame, second.frame)) in skipped
                    or frozenset((i, j)) in seen):
                continue
            seen.add(frozenset((i, j)))
            pairs.append((i, j))
    return np.array(pairs, dtype=np.intp).reshape(-1, 2)


def clearance_times(tree: TreeDescription, frames: Sequence[str]) -> TimeAxis | None:
    """The times a clearance between ``frames`` evaluates at when given none: every
    keyframe and joint sample time on their paths from the root; None if nothing moves."""
    plan = _plan(tree, list(frames), None, None, "clamp")
    return None if plan.offsets is None else TimeAxis(plan.offsets, plan.reference_time)


def _plan(tree: TreeDescription, frames: list[str], times: Any, time_ref: Any,
          extrapolation: str) -> QueryPlan:
    """The plan of a clearance: one timeline (the rules of ``pose()``) of every moving thing
    on the paths from the root to ``frames``, on which each frame's path is then taken."""
    sources = {source.name: source for frame in frames
               for source in prepare_path(tree, frame, tree.root).sources}
    return plan_query(tree, tree.root, tree.root, times, time_ref, extrapolation,
                      sources.values())


def _placed_shapes(rotation: FloatArray, translation: FloatArray, shapes: list[CollisionShape],
                   owners: NDArray[np.intp]) -> tuple[FloatArray, FloatArray]:
    """Every shape in the root at every sample: ``(S, n, 3, 3)`` and ``(S, n, 3)``."""
    shape_rotation = np.array([shape.rotation for shape in shapes])
    shape_translation = np.array([shape.translation for shape in shapes])
    frame_rotation = rotation[owners]
    placed_rotation = np.einsum("snij,sjk->snik", frame_rotation, shape_rotation)
    placed_translation = (np.einsum("snij,sj->sni", frame_rotation, shape_translation)
                          + translation[owners])
    return placed_rotation, placed_translation


def _require_placed(shapes: list[CollisionShape], translation: FloatArray,
                    offsets: NDArray[np.int64] | None) -> None:
    """A :class:`GeometryError` naming the frame and time of a shape placed at a position
    that is not finite or beyond :data:`LARGEST_COORDINATE` metres from the root."""
    with np.errstate(invalid="ignore"):
        wrong = ~(np.abs(translation) <= LARGEST_COORDINATE).all(axis=2)  # (S, n)
    if wrong.any():
        index, sample = (int(value[0]) for value in np.nonzero(wrong))
        shape = shapes[index]
        when = "" if offsets is None else f" at {offsets[sample] / 1e9:g} s"
        raise GeometryError(
            f"the shape is placed at {translation[index, sample].tolist()} m in the root"
            f"{when}: positions must be finite and within {LARGEST_COORDINATE:g} m to be "
            "measured", frame=shape.frame, field=shape.field)


def _inside(shape: CollisionShape, rotation: FloatArray, translation: FloatArray,
            solid_shape: CollisionShape, solid_rotation: FloatArray,
            solid_translation: FloatArray) -> bool:
    """Whether a point of each piece of ``shape`` (placed by ``rotation``, ``translation``)
    lies in the solid of ``solid_shape`` (placed likewise): whether ``shape`` is inside it,
    for shapes whose surfaces do not meet."""
    if solid_shape.solid is None:
        return False
    in_root = shape.probes @ rotation.T + translation
    return solid_shape.solid.contains((in_root - solid_translation) @ solid_rotation)


def _closest_pairs(
    shapes: list[CollisionShape], pairs: NDArray[np.intp], rotation: FloatArray,
    translation: FloatArray, distance: FloatArray, closest: NDArray[np.intp],
    point_a: FloatArray, point_b: FloatArray,
) -> None:
    """Fill the outputs (views of one chunk of ``n`` samples) with each sample's closest pair.

    ``rotation``/``translation`` place every shape in the root at every sample.
    """
    centres = np.array([shape.centre for shape in shapes])
    radii = np.array([shape.radius for shape in shapes])
    # each shape's sphere centre in the root: (S, n, 3)
    placed_centres = np.einsum("snij,sj->sni", rotation, centres) + translation
    first, second = pairs[:, 0], pairs[:, 1]
    bounds = (np.linalg.norm(placed_centres[first] - placed_centres[second], axis=2)
              - (radii[first] + radii[second])[:, None]).T  # (n, P)
    order = np.argsort(bounds, axis=1, kind="stable")
    request = coal.DistanceRequest()
    geometries = [shape.geometry for shape in shapes]
    for sample, (visit, bound) in enumerate(zip(order.tolist(), bounds.tolist(),
                                                strict=True)):
        best, best_result, best_pair = np.inf, None, 0
        for pair in visit:
            if bound[pair] >= best:
                break
            i, j = int(first[pair]), int(second[pair])
            result = coal.DistanceResult()
            found = coal.distance(
                geometries[i], coal.Transform3s(rotation[i, sample], translation[i, sample]),
                geometries[j], coal.Transform3s(rotation[j, sample], translation[j, sample]),
                request, result)
            if not np.isfinite(found):
                raise GeometryError(f"coal gives no finite distance to {shapes[j].frame!r} "
                                    f"({shapes[j].field})", frame=shapes[i].frame,
                                    field=shapes[i].field)
            placed_i = rotation[i, sample], translation[i, sample]
            placed_j = rotation[j, sample], translation[j, sample]
            if found > 0 and (_inside(shapes[i], *placed_i, shapes[j], *placed_j)
                              or _inside(shapes[j], *placed_j, shapes[i], *placed_i)):
                found = -found  # wholly inside a closed mesh: as deep as the surfaces apart
            if found < best:
                best, best_result, best_pair = found, result, pair
        assert best_result is not None  # the first pair is always computed
        distance[sample] = best
        closest[sample] = pairs[best_pair]
        point_a[sample] = best_result.getNearestPoint1()
        point_b[sample] = best_result.getNearestPoint2()
