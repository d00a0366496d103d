"""Closed-form inverse kinematics of 6-axis arms of two families: the ortho-parallel arm with
a spherical wrist (OPW) and the UR-type arm (three parallel axes, an offset wrist).
:mod:`.arm_shapes` recognises the family from the joints' axes, :mod:`.opw` and
:mod:`.ur_type` give every solution of many poses at once, :mod:`.configurations` names
the branches and :mod:`.solutions` is what ``FrameTree.ik_solutions`` returns."""
