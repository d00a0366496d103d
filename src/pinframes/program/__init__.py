"""Programs a welding cell runs: moves written in order (point to point, linear, welds,
waits), planned into one joint trajectory timed within the joints' limits and checked for
clearance (:class:`WeldProgram`, :meth:`WeldProgram.plan`)."""

from .weld_program import WeldProgram

__all__ = ["WeldProgram"]
