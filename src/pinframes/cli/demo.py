"""``pinframes demo``: the torch path of the bundled welding cell, as numbers, CSV and PNG."""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from ..errors import FileFormatError, UnsupportedFeatureError, WriteError
from ..kinematics import Velocity, WeldProcess
from ..plotting import new_figure, plot_frames, plotting_available, robot_frames, save_figure
from ..tree import FrameTree
from ..values.pose import Pose
from ..view import write_view
from ._cell_clearance import clearance_lines
from ._demo_bag import BAG_FILE, write_demo_bag
from ._demo_process import DEFAULT_SEAM, demo_process, plot_process, process_table
from ._evaluate import pose_in_chunks, pose_velocity, terminal_stderr
from ._files import read_tree, require_frames
from ._output import output_poses
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["PathSummary", "add_parser", "bundled_scene", "run", "summarize"]

POSES_FILE = "torch_poses.csv"
PLOT_FILE = "torch_path.png"
VIEW_FILE = "cell.html"
TARGET_FRAME = "torch_target"
"""The bundled cell's design torch pose over the seam: the demo solves the robot onto it."""


def bundled_scene() -> Path:
    """The welding cell scene shipped inside the package (``pinframes/models``)."""
    return Path(str(resources.files("pinframes") / "models" / "welding_cell" / "scene.yaml"))


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``demo`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "demo", run,
        help="torch path of the bundled welding cell",
        description="Load the bundled welding cell (robot, positioner, workpiece), compute "
        "the pose of the torch tip relative to the workpiece at every sample of the motion, "
        "and the welding process along the seam (travel speed, torch angles, offset), "
        f"print a summary and write the poses ({POSES_FILE}), a plot ({PLOT_FILE}; needs "
        f"pinframes[plot]), an animated 3-D page of the whole run ({VIEW_FILE}; needs "
        f"pinframes[view]) and the run as a ROS recording ({BAG_FILE}, MCAP; needs "
        "pinframes[ros]).", tree_file=None)
    parser.add_argument("--out", metavar="DIR", default=".",
                        help="folder for the CSV, PNG and HTML files (default: the current folder; "
                        "created if missing, but not its parent folders)")
    parser.add_argument("--scene", metavar="FILE",
                        help="another tree file: scene, frames.yaml, ASDF or URDF (default: "
                        "the bundled welding cell)")
    parser.add_argument("--tool", default="torch_tcp", metavar="FRAME",
                        help="the tool frame (default: torch_tcp)")
    parser.add_argument("--workpiece", default="workpiece", metavar="FRAME",
                        help="the frame the tool poses are expressed in (default: workpiece)")
    parser.add_argument("--seam", metavar="FRAME",
                        help=f"the seam frame of the welding process (default: {DEFAULT_SEAM} "
                        "when the scene has it, else no process)")


@dataclass(frozen=True)
class PathSummary:
    """How the tool tip moved relative to the workpiece.

    Attributes
    ----------
    samples : int
        Number of poses.
    start_s, end_s : float
        First and last time, seconds after the reference time.
    path_length_m : float
        Length of the tip's path in the workpiece frame, metres (sum of straight steps
        between samples).
    mean_speed_m_s, max_speed_m_s : float
        Path length over the time span, and the highest exact speed at a sample
        (:meth:`FrameTree.velocity`, not a finite difference), metres per second.
    """

    samples: int
    start_s: float
    end_s: float
    path_length_m: float
    mean_speed_m_s: float
    max_speed_m_s: float

    def table(self) -> str:
        """The summary as an aligned two-column text table."""
        rows = [
            ("samples", f"{self.samples}"),
            ("time span", f"{self.start_s:.3f} s .. {self.end_s:.3f} s "
                          f"({self.end_s - self.start_s:.3f} s)"),
            ("seam length travelled", f"{1000 * self.path_length_m:.1f} mm"),
            ("mean travel speed", f"{1000 * self.mean_speed_m_s:.2f} mm/s"),
            ("max travel speed", f"{1000 * self.max_speed_m_s:.2f} mm/s"),
        ]
        width = max(len(name) for name, _ in rows)
        return "\n".join(f"{name.ljust(width)}  {value}" for name, value in rows) + "\n"


def summarize(pose: Pose, velocity: Velocity) -> PathSummary:
    """Travel of the origin of ``pose`` (time-dependent) and its ``velocity`` at the same
    samples."""
    seconds = pose.keyframes.times / 1e9
    length = float(np.linalg.norm(np.diff(pose.translation, axis=0), axis=1).sum())
    span = float(seconds[-1] - seconds[0])
    return PathSummary(
        samples=len(pose), start_s=float(seconds[0]), end_s=float(seconds[-1]),
        path_length_m=length, mean_speed_m_s=length / span if span > 0 else 0.0,
        max_speed_m_s=float(np.linalg.norm(velocity.linear, axis=1).max()))


def run(args: argparse.Namespace) -> int:
    """Compute, print the summary, write the files."""
    scene = Path(args.scene) if args.scene else bundled_scene()
    tree = read_tree(scene)
    require_frames(tree, scene, args.tool, args.workpiece)
    pose = pose_in_chunks(tree, args.tool, args.workpiece, None, progress=terminal_stderr())
    if not pose.is_time_dependent or len(pose) < 2:
        raise FileFormatError(f"{args.tool!r} does not move relative to {args.workpiece!r}",
                              file=scene)
    velocity = pose_velocity(tree, pose, args.tool, args.workpiece)
    summary = summarize(pose, velocity)
    process = demo_process(tree, scene, args.tool, args.workpiece, args.seam)
    out = Path(args.out)
    try:
        out.mkdir(exist_ok=True)  # the output folder itself, never its parents
    except OSError as exc:
        raise WriteError(f"cannot create the output folder: {exc.strerror}", file=out) from None
    output_poses(pose, "csv", str(out / POSES_FILE), frame=args.tool,
                relative_to=args.workpiece)
    written = [out / POSES_FILE]
    missing = []
    if plotting_available():
        _plot(tree, pose, velocity, summary, args.tool, args.workpiece, out / PLOT_FILE,
              process)
        written.append(out / PLOT_FILE)
    else:
        missing.append(f'no plot: pip install "pinframes[plot]" adds matplotlib, and the demo '
                       f"then also draws the cell and the path ({PLOT_FILE})")
    try:
        write_view(tree, out / VIEW_FILE, paths={args.tool: args.workpiece})
        written.append(out / VIEW_FILE)
    except UnsupportedFeatureError as exc:  # meshcat is not installed: the page is optional
        missing.append(f"no 3-D page: {exc}")
    bag, bag_line = write_demo_bag(tree, out)
    if bag is not None:
        written.append(bag)
    else:
        missing.append(bag_line)
    print(f"{args.tool} relative to {args.workpiece} ({scene.name})")
    table = summary.table()
    sys.stdout.write(table)
    if process is not None:
        sys.stdout.write(process_table(process, len("seam length travelled")))
    sys.stdout.write(clearance_lines(tree))
    sys.stdout.write(_reached_row(tree, args.tool, table))
    if bag is not None:
        print(bag_line)
    print(f"pinframes: wrote {', '.join(map(str, written))}", file=sys.stderr)
    for line in missing:
        print(f"pinframes: {line}", file=sys.stderr)
    return 0


def _reached_row(tree: FrameTree, tool: str, table: str) -> str:
    """A row for the summary ``table``: of the samples at which ``solve_joints`` puts
    ``tool`` on the cell's ``torch_target``, how many it reaches ("" without that frame or
    without robot joints)."""
    if TARGET_FRAME not in tree or tool not in tree or not tree.joints:
        return ""  # no target, or no joints to solve (the cell written as ASDF keeps none)
    solution = tree.solve_joints(tool, TARGET_FRAME)
    name, value = table.splitlines()[0].split("  ", 1)
    column = len(name) + len(value) - len(value.lstrip())  # where the table's values start
    return (f"{'IK samples reached'.ljust(column)}  {int(solution.reached.sum())} of "
            f"{len(solution)} ({tool} on {TARGET_FRAME}, solve_joints)\n")


def _plot(tree: FrameTree, pose: Pose, velocity: Velocity, summary: PathSummary, tool: str,
          workpiece: str, path: Path, process: WeldProcess | None) -> None:
    figure = new_figure(13.0, 6.5 if process is None else 11.0)
    grid = figure.add_gridspec(2 if process is None else 4, 2, width_ratios=(1.15, 1.0))
    cell = figure.add_subplot(grid[:, 0], projection="3d")
    robot = robot_frames(tree)
    labelled = [frame for frame in tree.frames if frame not in robot and frame != tool]
    plot_frames(tree, ax=cell, labels=labelled, skeleton=robot | {tool})
    cell.set_title(f"{tree.name or 'cell'}: frames at the start, paths of moving frames")
    seconds = pose.keyframes.times / 1e9
    millimetres = 1000 * pose.translation
    tip = figure.add_subplot(grid[0, 1])
    scatter = tip.scatter(millimetres[:, 0], millimetres[:, 1], c=seconds, s=4, cmap="viridis")
    tip.plot(millimetres[:, 0], millimetres[:, 1], color="0.6", linewidth=0.6, zorder=0)
    tip.set_aspect("equal", adjustable="datalim")
    tip.set_xlabel(f"x in {workpiece} [mm]")
    tip.set_ylabel(f"y in {workpiece} [mm]")
    tip.set_title(f"{tool} path in the {workpiece} frame (x-y plane)")
    figure.colorbar(scatter, ax=tip, label="time [s]")
    speed = figure.add_subplot(grid[1, 1])
    speed.plot(seconds, 1000 * np.linalg.norm(velocity.linear, axis=1), color="tab:blue",
               linewidth=2.0, label="exact, per sample")
    speed.axhline(1000 * summary.mean_speed_m_s, color="tab:orange", linestyle="--",
                  label=f"mean {1000 * summary.mean_speed_m_s:.1f} mm/s")
    speed.set_ylim(0.0, 1000 * summary.max_speed_m_s * 1.25)
    speed.set_xlabel("time [s]")
    speed.set_ylabel("travel speed [mm/s]")
    speed.set_title(f"{tool} speed relative to the {workpiece}")
    speed.legend(loc="upper right")
    if process is not None:
        plot_process(figure, speed, grid[2, 1], grid[3, 1], process)
    save_figure(figure, path)

