"""3-D plots of frame trees: each frame's axes at one time and the paths of moving frames.

Needs matplotlib (``pip install "pinframes[plot]"``). Figures are made without pyplot, so
plotting works the same without a display and never changes matplotlib's global state.
"""

from __future__ import annotations

import os
from collections.abc import Collection, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ReferenceTimeError, UnsupportedFeatureError
from .formats.atomic import atomic_write
from .formats.urdf import URDF_METADATA_KEY
from .tree import FrameTree
from .values.timeconv import TimeAxis, timestamp_ns

if TYPE_CHECKING:
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d import Axes3D as Axes

__all__ = ["plot_frames"]  # new_figure, figure_format, save_figure, robot_frames: for the CLI

_AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")
_PATH_SAMPLES = 400


def plotting_available() -> bool:
    """True when matplotlib can be imported (``pip install "pinframes[plot]"``)."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def new_figure(width: float = 8.0, height: float = 7.0) -> Figure:
    """A matplotlib figure not tied to pyplot (raises a clear error without matplotlib)."""
    try:
        from matplotlib.figure import Figure
        from mpl_toolkits import mplot3d  # noqa: F401  (registers the 3-D projection)
    except ImportError:
        raise UnsupportedFeatureError(
            'plotting needs matplotlib: pip install "pinframes[plot]"') from None
    return Figure(figsize=(width, height), layout="constrained")


def figure_format(figure: Figure, path: str | os.PathLike[str]) -> str:
    """The image format the suffix of ``path`` names (``png``, ``jpg``, ``svg``, ``pdf``...);
    an :class:`UnsupportedFeatureError` listing the formats matplotlib writes otherwise."""
    formats = figure.canvas.get_supported_filetypes()
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in formats:
        raise UnsupportedFeatureError(
            f"cannot tell an image format from the suffix {Path(path).suffix or '(none)'!r}; "
            f"name the file with one of: {', '.join('.' + name for name in sorted(formats))}",
            file=os.fspath(path))
    return suffix


def save_figure(figure: Figure, path: str | os.PathLike[str], dpi: int = 120) -> None:
    """Write ``figure`` to ``path`` in the format its suffix names, atomically."""
    image_format = figure_format(figure, path)
    with atomic_write(path, "wb") as handle:
        figure.savefig(handle, format=image_format, dpi=dpi)


def plot_frames(
    tree: FrameTree,
    frames: Sequence[str] | None = None,
    relative_to: str | None = None,
    *,
    ax: Axes | None = None,
    time_index: int = 0,
    axis_length: float | None = None,
    labels: bool | Collection[str] = True,
    skeleton: Collection[str] | None = None,
) -> Axes:
    """Draw ``frames`` of ``tree`` in ``relative_to`` on a 3-D axes.

    Each frame gets its x, y, z axes (red, green, blue) at one time and, when it moves
    relative to ``relative_to``, its origin's path over the whole time span of the
    selected frames (sampled finely, so that turning frames draw arcs, not chords).

    Parameters
    ----------
    tree : FrameTree
    frames : sequence of str, optional
        Frames to draw (default: all).
    relative_to : str, optional
        The frame the plot is drawn in (default: the root); axes labelled in metres.
    ax : matplotlib 3-D Axes, optional
        Where to draw (default: a new figure).
    time_index : int
        Which of the finely sampled times the axes are drawn at (0: the first, -1: last).
    axis_length : float, optional
        Length of the drawn axes, metres (default: 8 % of the plot's extent).
    labels : bool or collection of str
        Write frame names next to their origins: all, none, or these.
    skeleton : collection of str, optional
        Frames to join to their (drawn) parent with a grey bar (default: the frames of
        URDF robots, which then show as arms).
    """
    relative_to = tree.root if relative_to is None else relative_to
    skeleton = robot_frames(tree) if skeleton is None else set(skeleton)
    frames = list(tree.frames if frames is None else frames)
    for frame in frames:
        tree.path(frame, relative_to)  # raises for unknown frames
    if ax is None:
        ax = new_figure().add_subplot(projection="3d")
    from matplotlib.lines import Line2D

    times = _common_times(tree, frames, relative_to)
    poses = {frame: tree.pose(frame, relative_to=relative_to, times=times)
             if times is not None else tree.pose(frame, relative_to=relative_to)
             for frame in frames}
    points = np.concatenate([np.atleast_2d(pose.translation) for pose in poses.values()])
    extent = float(np.max(np.ptp(points, axis=0))) if points.shape[0] > 1 else 1.0
    length = axis_length if axis_length is not None else max(0.08 * extent, 1e-3)
    texts: list[tuple[np.ndarray, list[str]]] = []
    for frame, pose in poses.items():
        translation = np.atleast_2d(pose.translation)
        rotation = pose.rotation.reshape(-1, 3, 3)
        moves = np.ptp(translation, axis=0).max() > 1e-9 if translation.shape[0] > 1 else False
        if moves:
            ax.plot(*translation.T, color="0.35", linewidth=1.0)
        origin = translation[time_index if translation.shape[0] > 1 else 0]
        axes = rotation[time_index if rotation.shape[0] > 1 else 0]
        for column, colour in enumerate(_AXIS_COLOURS):
            tip = origin + length * axes[:, column]
            ax.plot(*np.stack([origin, tip]).T, color=colour, linewidth=1.5)
        if labels is True or (labels and frame in labels):
            _add_label(texts, origin, frame, length)
        parent = tree.parent(frame)
        if frame in skeleton and parent in poses:
            parent_translation = np.atleast_2d(poses[parent].translation)
            start = parent_translation[time_index if parent_translation.shape[0] > 1 else 0]
            ax.plot(*np.stack([start, origin]).T, color="0.6", linewidth=2.5, zorder=0)
    _equal_axes(ax, points, length)
    hidden = _place_labels(ax, texts, _short_names(frames))
    legend = [Line2D([], [], color=colour, label=f"{axis} axis")
              for axis, colour in zip("xyz", _AXIS_COLOURS, strict=True)]
    legend.append(Line2D([], [], color="0.35", linewidth=1.0, label="path of a moving frame"))
    if hidden:
        legend.append(Line2D([], [], linestyle="none",
                             label=f"{hidden} names not shown (they would overlap)"))
    ax.legend(handles=legend, loc="upper left", fontsize=7)
    ax.set_xlabel(f"x in {relative_to} [m]")
    ax.set_ylabel(f"y in {relative_to} [m]")
    ax.set_zlabel(f"z in {relative_to} [m]")
    return ax


def robot_frames(tree: FrameTree) -> set[str]:
    """The frames that came from URDF robots (their links)."""
    return {frame for frame in tree.frames if URDF_METADATA_KEY in tree.frame_metadata(frame)}


def _add_label(texts: list[tuple[np.ndarray, list[str]]], origin: np.ndarray, frame: str,
               length: float) -> None:
    """Frames whose origins coincide share one label instead of overprinting."""
    for position, names in texts:
        if np.linalg.norm(position - origin) < 0.05 * length:
            names.append(frame)
            return
    texts.append((origin, [frame]))


def _short_names(frames: list[str]) -> dict[str, str]:
    """Each frame's last ``/`` part (``map_1/tile_0_7`` -> ``tile_0_7``) where that is unique."""
    tails = [frame.rsplit("/", 1)[-1] for frame in frames]
    return {frame: tail if tails.count(tail) == 1 else frame
            for frame, tail in zip(frames, tails, strict=True)}


def _place_labels(ax: Axes, texts: list[tuple[np.ndarray, list[str]]],
                  short: dict[str, str], fontsize: float = 7.0) -> int:
    """Write the labels that do not overlap one already written; return how many did.

    Labels of frames higher in the tree (fewer ``/`` in the name) go first. Overlap is judged
    on the screen: each label's box is estimated from its length and the font size.
    """
    from mpl_toolkits.mplot3d import proj3d

    figure = ax.get_figure()
    assert figure is not None
    figure.draw_without_rendering()  # the layout settles: screen positions are final
    points_to_pixels = figure.dpi / 72.0
    height = 1.3 * fontsize * points_to_pixels
    placed: list[tuple[float, float, float, float]] = []
    hidden = 0
    for origin, names in sorted(texts, key=lambda item: min(n.count("/") for n in item[1])):
        text = " " + ", ".join(short[name] for name in names)
        x2, y2, _ = proj3d.proj_transform(*origin, ax.get_proj())
        x, y = ax.transData.transform((x2, y2))
        box = (x, y - height / 2, x + 0.6 * fontsize * points_to_pixels * len(text),
               y + height / 2)
        if any(box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3]
               for b in placed):
            hidden += 1
            continue
        placed.append(box)
        ax.text(*origin, text, fontsize=fontsize, color="0.15", verticalalignment="center")
    return hidden


def _common_times(tree: FrameTree, frames: list[str], relative_to: str) -> Any:
    """Finely spaced times over the span of all moving things behind ``frames``."""
    axes: list[TimeAxis] = [axis for frame in frames
                            if (axis := tree.sample_times(frame, relative_to)) is not None]
    if not axes:
        return None
    absolute = {axis.reference is not None for axis in axes}
    if len(absolute) > 1:
        raise ReferenceTimeError("some paths have reference times and some have none, so "
                                 "their times cannot be drawn together")
    ends = np.array([(_ns(axis, 0), _ns(axis, -1)) for axis in axes])
    grid = np.unique(np.linspace(ends[:, 0].min(), ends[:, 1].max(), _PATH_SAMPLES)
                     .round().astype(np.int64))
    if absolute == {True}:
        return grid.astype("datetime64[ns]")
    return grid.astype("timedelta64[ns]")


def _ns(axis: TimeAxis, index: int) -> int:
    base = 0 if axis.reference is None else timestamp_ns(axis.reference)
    return base + int(axis.offsets[index])


def _equal_axes(ax: Axes, points: np.ndarray, margin: float) -> None:
    """Same scale on x, y and z, so that frames and paths keep their shapes."""
    low, high = points.min(axis=0) - margin, points.max(axis=0) + margin
    centre, half = (low + high) / 2, float(np.max(high - low)) / 2
    for setter, middle in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, strict=True):
        setter(middle - half, middle + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))
