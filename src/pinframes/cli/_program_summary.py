"""A planned program as text: a line per move, the cycle time, the longest and shortest
moves and the collisions (``pinframes program`` and ``pinframes demo``)."""

from __future__ import annotations

from ..values.motion import Motion

__all__ = ["motion_summary"]


def motion_summary(motion: Motion, step: float) -> str:
    """The summary of ``motion`` (sampled every ``step`` seconds), lines ending in
    newlines."""
    width = max(len(record.name) for record in motion.moves)
    lines = [f"{'move'.ljust(width)}  {'kind':<9} {'start s':>8} {'time s':>8}  speed"]
    for record in motion.moves:
        speed = ""
        if record.requested_speed is not None and record.reached_speed is not None:
            speed = (f"{1000 * record.requested_speed:.1f} mm/s asked, "
                     f"{1000 * record.reached_speed:.1f} mm/s reached")
        lines.append(f"{record.name.ljust(width)}  {record.kind:<9} {record.start_s:8.3f} "
                     f"{record.duration_s:8.3f}  {speed}".rstrip())
    timed = [record for record in motion.moves if record.duration_s > 0]
    longest = max(timed, key=lambda record: record.duration_s, default=None)
    shortest = min(timed, key=lambda record: record.duration_s, default=None)
    lines.append(f"cycle time      {motion.cycle_time:.3f} s ({len(motion.moves)} moves, "
                 f"{len(motion)} samples every {1000 * step:g} ms)")
    if longest is not None and shortest is not None:
        lines.append(f"slowest move    {longest.name} ({longest.duration_s:.3f} s)")
        lines.append(f"fastest move    {shortest.name} ({shortest.duration_s:.3f} s)")
    if not motion.all_reached:
        missed = int((~motion.reached).sum())
        lines.append(f"not reached     {missed} of {len(motion)} samples (the tool off its "
                     "path there)")
    if motion.collisions:
        for found in motion.collisions:
            lines.append(f"collision       {found.move}: {found.frame_a} - {found.frame_b} "
                         f"{1000 * found.distance:.1f} mm at {found.time_s:.3f} s")
    else:
        lines.append("collisions      none")
    return "\n".join(lines) + "\n"
