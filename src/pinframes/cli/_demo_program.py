"""The demo's program lines: the bundled cell's ``program:`` section planned (home, the
approach, the seam, the retract, home again), its cycle time and moves, and the motion
written beside the other files."""

from __future__ import annotations

from pathlib import Path

from ..formats.joint_trajectory_writer import write_joint_trajectory
from ..formats.scene.program_section import PROGRAM_METADATA_KEY, scene_program
from ..tree import FrameTree

__all__ = ["PROGRAM_FILE", "program_lines"]

PROGRAM_FILE = "program_run.csv"


def program_lines(tree: FrameTree, scene: Path, out: Path, column: int
                  ) -> tuple[str, Path | None]:
    """Rows for the demo's summary (names padded to ``column``) and the motion file
    written, or ("", None) for a scene without a program."""
    if PROGRAM_METADATA_KEY not in tree.metadata:
        return "", None
    program = scene_program(tree, scene)
    motion = program.plan()
    path = out / PROGRAM_FILE
    write_joint_trajectory(motion, path, tree=tree)
    seam = max(motion.moves, key=lambda record: record.duration_s)
    collisions = ", ".join(f"{found.move} ({found.frame_a} - {found.frame_b})"
                           for found in motion.collisions) or "none"
    rows = [("program cycle time", f"{motion.cycle_time:.3f} s, {len(motion.moves)} moves "
             f"({' / '.join(record.name for record in motion.moves)})"),
            ("program longest move", f"{seam.name} {seam.duration_s:.3f} s"),
            ("program collisions", collisions)]
    return "".join(f"{name.ljust(column)}  {value}\n" for name, value in rows), path
