"""Values: poses, rotations, times, robot joints and their trajectories, subsystems.

Immutable things and the maths on them; nothing here knows about trees or files.
"""
