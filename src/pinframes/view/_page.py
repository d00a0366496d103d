"""One self-contained HTML page that animates a frame tree over time (meshcat's viewer).

The page inlines meshcat's viewer bundle (three.js and its controls, shipped in the meshcat
package), the scene as msgpack-encoded meshcat commands, and a small script of ours
(``page.js``) for the time slider, play/pause, the time shown, and frame names that can be
switched on and off. It loads nothing from the network and needs no server.
"""

from __future__ import annotations

import base64
import html
import importlib.util
import json
import os
from collections.abc import Iterable, Mapping, Sequence
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InvalidTimeError, ReferenceTimeError, UnsupportedFeatureError
from ..formats.atomic import atomic_write
from ..formats.limits import Limits, checked_limits
from ..formats.urdf import URDF_METADATA_KEY
from ..tree import FrameTree
from ..values.pose import Pose
from ..values.timeconv import TimeAxis, format_timestamp_iso, timestamp_ns
from ._drawable import drawable_frames, drawable_geometry
from ._geometry import LinkGeometry, load_geometry
from ._scene import SceneCommands, msgpack, node_path

__all__ = ["MAX_PAGE_POSES", "MAX_PAGE_SAMPLES", "view_html", "write_view"]

MAX_PAGE_SAMPLES = 20_000
"""The most times one page animates (about 1 kB per moving frame and 30 samples)."""

MAX_PAGE_POSES = 1_000_000
"""The most poses one page holds: times x drawn frames (28 bytes each as float32, before
base64: about 37 MB of page)."""


def write_view(tree: FrameTree, path: str | os.PathLike[str], **options: Any) -> int:
    """Write :func:`view_html` of ``tree`` to ``path`` (atomically); return its size in bytes."""
    page = view_html(tree, **options).encode("utf-8")
    with atomic_write(path, "wb") as handle:
        handle.write(page)
    return len(page)


def view_html(
    tree: FrameTree,
    *,
    times: Any = None,
    time_ref: Any = None,
    relative_to: str | None = None,
    frames: Sequence[str] | None = None,
    paths: Mapping[str, str] | None = None,
    collision: bool = False,
    package_dirs: Iterable[str | os.PathLike[str]] = (),
    geometry: Sequence[LinkGeometry] | None = None,
    title: str | None = None,
    limits: Limits | None = None,
    clearance: tuple[Any, Any] | None = None,
    clearance_exclude: Iterable[tuple[str, str]] = (),
) -> str:
    """An animated 3-D page of ``tree``: geometry, frames and paths over ``times``.

    Parameters
    ----------
    tree : FrameTree
    times, time_ref : optional
        The times to animate, as :meth:`FrameTree.pose` takes them (default: every keyframe
        and joint sample of the drawn frames, at most :data:`MAX_PAGE_SAMPLES`).
    relative_to : str, optional
        The frame the scene is drawn in (default: the root), z up; metres.
    frames : sequence of str, optional
        Frames drawn with their axes and names (default: all).
    paths : mapping of str to str, optional
        Paths drawn as lines: ``{frame: frame_drawn_in}``; a path drawn in a moving frame
        moves with it (the tool path on a turning workpiece). Default: the path of each
        drawn frame without children that moves, in ``relative_to``.
    collision : bool
        Draw the URDF ``<collision>`` geometry instead of the ``<visual>`` geometry.
    package_dirs : iterable of path
        Folders to look for ``package://`` and relative mesh names in (see
        :func:`load_geometry`).
    geometry : sequence of LinkGeometry, optional
        Geometry already loaded (default: :func:`load_geometry` of the tree).
    title : str, optional
        The page's title (default: the tree's name).
    limits : Limits, optional
        Bounds on the mesh files read (see :func:`load_geometry`).
    clearance : (a, b), optional
        Mark the closest pair of :meth:`FrameTree.clearance` ``(a, b)`` (collision geometry,
        at the page's times): a dot on each closest point, the segment between them, and
        the distance and the two frames beside the time shown.
    clearance_exclude : iterable of (str, str)
        Pairs the clearance leaves out (``exclude=`` of :meth:`FrameTree.clearance`).

    Frames and geometry that are not finite or lie farther than
    :data:`~pinframes.view._drawable.MAX_DRAWN_DISTANCE_M` from ``relative_to`` are left out
    with a :class:`GeometryWarning`; more than :data:`MAX_PAGE_SAMPLES` times, or more than
    :data:`MAX_PAGE_POSES` poses (times x drawn frames), are an ``InvalidTimeError`` before
    any pose is computed. Any frame name gives a working page.
    """
    relative_to = tree.root if relative_to is None else relative_to
    limits = checked_limits(limits)
    frames = list(tree.frames if frames is None else frames)
    for frame in frames:
        tree.path(frame, relative_to)  # raises for unknown frames
    if geometry is None:
        geometry = load_geometry(tree, collision=collision, package_dirs=package_dirs,
                                 limits=limits)
    drawn = {relative_to, *frames} | {piece.frame for piece in geometry}  # paths hang in
    # relative_to's group by default
    order = [frame for frame in tree.frames if frame in drawn]
    values, time_ref = _page_times(tree, order, relative_to, times, time_ref)
    _check_page_size(values, len(order))  # before any pose is computed
    poses = {frame: _pose(tree, frame, relative_to, values, time_ref) for frame in order}
    seconds, start = _animation_seconds(poses.values())
    matrices = drawable_frames({frame: _matrices(pose, len(seconds))
                                for frame, pose in poses.items()})
    geometry = drawable_geometry(geometry, matrices)
    order = [frame for frame in order if frame in matrices]
    extent = _extent(matrices, geometry)
    scene = SceneCommands()
    axis_length = 0.06 * extent[2]
    for frame in order:
        scene.add_frame(frame, matrices[frame], seconds,
                        axis_length * (0.5 if _is_link(tree, frame) else 1.0))
    for index, piece in enumerate(geometry):
        scene.add_geometry(index, piece)
    if paths is None:
        paths = {frame: relative_to for frame in frames
                 if frame in matrices and not tree.children(frame) and len(seconds) > 1
                 and np.ptp(matrices[frame][:, :3, 3], axis=0).max() > 1e-9}
    for frame, drawn_in in paths.items():
        if drawn_in not in poses:
            raise UnsupportedFeatureError(f"a path drawn in {drawn_in!r} needs that frame "
                                          "drawn too", frame=frame, field="paths")
        if frame in matrices and drawn_in in matrices:  # else the frames' warning says why
            scene.add_path(frame, drawn_in, _pose(tree, frame, drawn_in, values, time_ref)
                           .translation.reshape(-1, 3))
    marked = None
    if clearance is not None:
        marked = _closest_pair(tree, clearance, clearance_exclude, package_dirs, relative_to,
                               values, time_ref, seconds, limits)
        scene.add_closest_pair(*marked[:2], seconds, 0.006 * extent[2])
    commands = list(scene.commands)
    if (animation := scene.animation_command()) is not None:
        commands.append(animation)
    labels = [{"text": frame, "path": node_path(frame), "link": _is_link(tree, frame)}
              for frame in frames if frame in matrices]
    return _html(title or tree.name or "pinframes", commands, {
        "labels": labels, "start": start, "duration": float(seconds[-1]),
        "centre": extent[0].tolist(), "radius": float(extent[2]),
        "drawnIn": relative_to, "clearance": None if marked is None else marked[2]})


def _closest_pair(tree: FrameTree, sides: tuple[Any, Any],
                  exclude: Iterable[tuple[str, str]],
                  package_dirs: Iterable[str | os.PathLike[str]], relative_to: str,
                  values: Any, time_ref: Any, seconds: np.ndarray, limits: Limits
                  ) -> tuple[np.ndarray, np.ndarray, dict[str, Any]]:
    """The clearance's closest points per page sample, in the drawing frame, and what the
    page shows beside the time: per sample the distance (mm) and the pair."""
    a, b = sides
    result = tree.clearance(a, b, times=values, time_ref=time_ref, exclude=list(exclude),
                            package_dirs=package_dirs, limits=limits)
    root_in_drawing = _pose(tree, tree.root, relative_to, values, time_ref)
    # (T, 3): one point per time through a moving pose, or each point through a static one
    points = [root_in_drawing.transform_points(points, per_time=True)
              for points in (result.point_a, result.point_b)]
    names, pairs = np.unique(result.closest, return_inverse=True)
    return points[0], points[1], {
        "seconds": seconds.tolist(), "names": names.tolist(),
        "pairs": pairs.reshape(-1, 2).tolist(),
        "distanceMm": np.round(1000 * result.distance, 3).tolist()}


def _check_page_size(values: Any, frames: int) -> None:
    """Refuse more times than :data:`MAX_PAGE_SAMPLES`, or more poses (times x drawn frames)
    than :data:`MAX_PAGE_POSES`, before any is computed."""
    count = 1 if values is None else int(np.asarray(values, dtype=object).size)
    if count > MAX_PAGE_SAMPLES:
        raise InvalidTimeError(f"{count:,} times are more than a page animates "
                               f"({MAX_PAGE_SAMPLES:,}); choose fewer (a larger step)",
                               field="times")
    if count * frames > MAX_PAGE_POSES:
        raise InvalidTimeError(
            f"{count:,} times x {frames:,} frames are {count * frames:,} poses, more than a "
            f"page holds ({MAX_PAGE_POSES:,}); choose fewer times (a larger step) or fewer "
            "frames (frames=..., --frames)", field="times")


def _page_times(tree: FrameTree, frames: list[str], relative_to: str, times: Any,
                time_ref: Any) -> tuple[Any, Any]:
    """The times to query (None: static) and the time_ref to query them with."""
    if times is not None:
        if isinstance(times, TimeAxis):
            return times.as_numpy(), time_ref
        return times, time_ref
    axes = [axis for frame in frames
            if (axis := tree.sample_times(frame, relative_to)) is not None]
    if not axes:
        return None, None
    if len({axis.reference is None for axis in axes}) > 1:
        raise ReferenceTimeError("some frames have reference times and some have none, so "
                                 "their times cannot be shown together")
    if axes[0].reference is None:
        return np.unique(np.concatenate([a.offsets for a in axes])).astype("m8[ns]"), None
    stamps = np.unique(np.concatenate([a.offsets + timestamp_ns(a.reference) for a in axes
                                       if a.reference is not None]))
    return stamps.astype("M8[ns]"), None


def _pose(tree: FrameTree, frame: str, relative_to: str, values: Any, time_ref: Any) -> Pose:
    if values is None:
        return tree.pose(frame, relative_to=relative_to)
    return tree.pose(frame, relative_to=relative_to, times=values, time_ref=time_ref)


def _animation_seconds(poses: Iterable[Pose]) -> tuple[np.ndarray, str]:
    """Seconds from the first sample, and that sample's time as text for the page."""
    for pose in poses:
        times = pose.times
        if times is not None:
            nanoseconds = times.astype(np.int64)
            seconds = (nanoseconds - nanoseconds[0]) / 1e9
            if pose.reference_time is not None:
                first = pose.reference_time + times[0]
                return seconds, format_timestamp_iso(first.astype("M8[ns]"))
            return seconds, f"{nanoseconds[0] / 1e9:g} s"
    return np.zeros(1), "static"


def _matrices(pose: Pose, count: int) -> np.ndarray:
    """Shape (count, 4, 4): the pose per sample (a static pose repeated)."""
    matrices = pose.matrix.reshape(-1, 4, 4)
    return np.broadcast_to(matrices, (count, 4, 4)) if len(matrices) == 1 else matrices


def _extent(matrices: dict[str, np.ndarray], geometry: Sequence[LinkGeometry]
            ) -> tuple[np.ndarray, np.ndarray, float]:
    """Centre, half size and radius (metres) of everything drawn at the first time."""
    points = [m[:, :3, 3] for m in matrices.values()]
    for piece in geometry:
        corners = np.array([piece.vertices.min(axis=0), piece.vertices.max(axis=0)])
        placed = matrices[piece.frame][0] @ piece.pose_in_frame
        points.append(corners @ placed[:3, :3].T + placed[:3, 3])
    stacked = np.concatenate(points)
    low, high = stacked.min(axis=0), stacked.max(axis=0)
    return (low + high) / 2, (high - low) / 2, max(float(np.linalg.norm(high - low)) / 2, 0.1)


def _is_link(tree: FrameTree, frame: str) -> bool:
    return URDF_METADATA_KEY in tree.frame_metadata(frame)


def _html(title: str, commands: list[dict[str, Any]], settings: dict[str, Any]) -> str:
    """The page: meshcat's viewer, the commands, our controls."""
    encoded = [base64.b64encode(msgpack().packb(command)).decode("ascii")
               for command in commands]
    data = _script_json({"commands": encoded, **settings})
    page = resources.files(__package__)
    script = (page / "page.js").read_text(encoding="utf-8")
    style = (page / "page.css").read_text(encoding="utf-8")
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title><style>{style}</style></head><body>"
            f"<div id=\"meshcat-pane\"></div>"
            f"<script>{_viewer_bundle()}</script>"
            f"<script type=\"application/json\" id=\"pinframes-data\">{data}</script>"
            f"<script>{script}</script></body></html>\n")


def _script_json(value: Any) -> str:
    """``value`` as strict JSON (no NaN or Infinity, which ``JSON.parse`` refuses) that is
    safe inside a ``<script>`` element: ``<``, ``>`` and ``&`` as ``\\u`` escapes, so no
    frame name can end the element or open an HTML comment in it (``<!--<script>``)."""
    text = json.dumps(value, allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _viewer_bundle() -> str:
    """meshcat's viewer (three.js inside), from the installed meshcat package."""
    spec = importlib.util.find_spec("meshcat")  # found, not imported (that starts zmq)
    if spec is None or not spec.submodule_search_locations:
        raise UnsupportedFeatureError('the 3-D page needs meshcat: pip install '
                                      '"pinframes[view]"')
    bundle = Path(spec.submodule_search_locations[0]) / "viewer" / "dist" / "main.min.js"
    return bundle.read_text(encoding="utf-8").replace("</script", "<\\/script")


