"""Clearance along a motion: ``FrameTree.clearance`` beside a plain Pinocchio + coal loop.

Case (issue 28): the bundled welding cell with the UR5 of example-robot-data (collision
meshes) in place of its welding robot, on the robot's riser; 10,000 joint samples over the
cell's 20 s while the positioner turns; the smallest distance between the UR5's links and
the cell's fixtures, faceplate and pipe at every sample (the UR5's base stands on the riser:
that pair is excluded on both sides). Most pairs are far apart.

The reference shares no code with pinframes: it reads ``scene.yaml`` with PyYAML, builds the
UR5 with ``pin.buildModelFromUrdf`` + ``pin.buildGeomFromUrdf`` and the cell parts with
``pin.buildGeomFromUrdf`` on their own URDFs, interpolates the positioner with numpy, and per
sample places the cell parts, runs ``pin.updateGeometryPlacements`` and
``pin.computeDistances`` over every UR5-cell pair and takes the smallest. ``max|diff|`` is the
largest difference of the two distance series (metres). Both thread settings, each in a child
process (see ``_machine.py``).

Run: ``python benchmarks/bench_clearance.py [--quick]``.
"""

from __future__ import annotations

import json
from importlib import metadata
from pathlib import Path

import coal
import numpy as np
import pinocchio as pin
import yaml

import _reference as ref
from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings
from pinframes import read_scene

CELL = Path(__file__).resolve().parents[1] / "models" / "welding_cell"
PARTS = {"fixtures": "world", "faceplate": "positioner", "pipe": "workpiece"}
SAMPLES = 10_000


def ur5_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "ur5_robot.urdf":
            return Path(file.locate())
    raise SystemExit("example-robot-data is not installed (pip install '.[test]')")


def joint_motion(samples: int) -> tuple[np.ndarray, np.ndarray]:
    """Times (s) and smooth UR5 joint values (rad), the arm swinging over the riser."""
    times = np.linspace(0.0, 20.0, samples)
    phase = 2 * np.pi * times / 20.0
    values = np.stack([0.9 * np.sin(phase), -1.2 + 0.5 * np.sin(2 * phase),
                       1.4 * np.sin(phase + 1.0), -1.5 + 0.8 * np.cos(phase),
                       1.0 * np.sin(3 * phase), 2.0 * np.cos(phase)], axis=1)
    return times, values


def pinframes_case(samples: int):
    tree = read_scene(CELL / "scene.yaml")
    tree.remove("robot/base_link", recursive=True)  # the welding robot, its torch and tools
    tree.attach_urdf(ur5_urdf(), "robot_base", prefix="ur5/")
    times, values = joint_motion(samples)
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    tree.set_joint_trajectory(times, values, names)

    def run():
        return tree.clearance("ur5/*", list(PARTS), times=times,
                              exclude=[("ur5/base_link", "fixtures")]).distance
    return run


def cell_part(part: str, frames: dict) -> list:
    """The collision objects of a cell part: from its frame's ``geometry`` entry in
    scene.yaml (boxes and cylinders, read with PyYAML), else from its URDF (Pinocchio)."""
    if "geometry" in frames.get(part, {}):
        pieces = []
        for index, entry in enumerate(frames[part]["geometry"]):
            if "box" in entry:
                shape = coal.Box(*entry["box"]["size"])
            else:
                shape = coal.Cylinder(entry["cylinder"]["radius"], entry["cylinder"]["length"])
            placement = pin.SE3(pin.rpy.rpyToMatrix(*entry.get("rpy", [0.0, 0.0, 0.0])),
                                np.array(entry.get("xyz", [0.0, 0.0, 0.0])))
            pieces.append(pin.GeometryObject(f"{part}_{index}", 0, placement, shape))
        return pieces
    urdf = CELL / "geometry" / f"{part}.urdf"
    return list(pin.buildGeomFromUrdf(pin.buildModelFromUrdf(str(urdf)), str(urdf),
                                      pin.GeometryType.COLLISION).geometryObjects)


class PinocchioLoop:
    """The reference: Pinocchio's own model and geometry, one computeDistances per sample."""

    def __init__(self, samples: int) -> None:
        scene = yaml.safe_load((CELL / "scene.yaml").read_text())
        frames = {frame["name"]: frame for frame in scene["frames"]}
        urdf = ur5_urdf()
        self.model = pin.buildModelFromUrdf(str(urdf))
        self.geometry = pin.buildGeomFromUrdf(self.model, str(urdf), pin.GeometryType.COLLISION,
                                              package_dirs=[str(urdf.parents[4])])
        robot_objects = self.geometry.ngeoms
        self.parts = []  # (object id, its pose in its cell frame, the cell frame)
        for part, frame in PARTS.items():
            for piece in cell_part(part, frames):
                placement = piece.placement.homogeneous
                piece.parentJoint, piece.parentFrame = 0, 0
                self.parts.append((self.geometry.addGeometryObject(piece), placement, frame))
        base_link = next(i for i, obj in enumerate(self.geometry.geometryObjects)
                         if obj.name.startswith("base_link"))
        for i in range(robot_objects):
            for j, _, frame in self.parts:
                if not (i == base_link and frame == "world"):  # the UR5 stands on the riser
                    self.geometry.addCollisionPair(pin.CollisionPair(i, j))
        self.data, self.geometry_data = self.model.createData(), pin.GeometryData(self.geometry)
        self.times, values = joint_motion(samples)
        self.q = np.zeros((samples, self.model.nq))
        for joint_id in range(1, self.model.njoints):
            self.q[:, self.model.joints[joint_id].idx_q] = values[:, joint_id - 1]
        # the cell frames in the robot's base, per sample (numpy SLERP of the positioner)
        base = np.eye(4)
        base[:3, 3] = frames["robot_base"]["xyz"]
        positioner_base = np.eye(4)
        positioner_base[:3, :3] = ref.matrices_from_quaternions(
            np.array([frames["positioner_base"]["quaternion"]]))[0]
        positioner_base[:3, 3] = frames["positioner_base"]["xyz"]
        keys = frames["positioner"]["keyframes"]
        turning = ref.interpolate(self.times, np.array([k["time"] for k in keys]),
                                  np.zeros((len(keys), 3)),
                                  np.array([k["quaternion"] for k in keys]))
        workpiece = np.eye(4)
        workpiece[:3, 3] = frames["workpiece"]["xyz"]
        in_base = np.linalg.inv(base)
        positioner = in_base @ positioner_base @ turning
        self.cell = {"world": np.broadcast_to(in_base, positioner.shape),
                     "positioner": positioner, "workpiece": positioner @ workpiece}

    def __call__(self) -> np.ndarray:
        model, data, geometry, geometry_data = (self.model, self.data, self.geometry,
                                                self.geometry_data)
        self.pairs = len(geometry.collisionPairs)
        objects = geometry.geometryObjects
        distances = np.empty(len(self.times))
        for k, q in enumerate(self.q):
            for index, placement, frame in self.parts:
                objects[index].placement = pin.SE3(self.cell[frame][k] @ placement)
            pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
            pin.computeDistances(geometry, geometry_data)
            distances[k] = min(result.min_distance
                               for result in geometry_data.distanceResults)
        self.last = distances
        return distances


def coal_calls_per_sample(run, samples: int) -> float:
    """How many pairs pinframes measured with coal per sample (one untimed run)."""
    counted = [0]
    measure = coal.distance

    def counting(*args):
        counted[0] += 1
        return measure(*args)

    coal.distance = counting
    try:
        run()
    finally:
        coal.distance = measure
    return counted[0] / samples


def child(quick: bool) -> None:
    samples = 2_000 if quick else SAMPLES
    ours, loop = pinframes_case(samples), PinocchioLoop(samples)
    case = f"UR5 in the welding cell, {samples:,} samples"
    # the reference takes minutes per run: its warm-up and 2 timed rounds, its last answer kept
    rows = interleaved(case, {"pinframes": ours, "Pinocchio + coal loop": loop}, 2,
                       reference="Pinocchio + coal loop")
    error = float(np.max(np.abs(ours() - loop.last)))
    measured = {"pinframes": coal_calls_per_sample(ours, samples),
                "Pinocchio + coal loop": float(loop.pairs)}
    for entry in rows:
        entry["error"] = error if entry["method"] == "pinframes" else None
        entry["note"] = (f"{entry['seconds'] / samples * 1e6:.1f} us/sample, "
                         f"{measured[entry['method']]:.2f} pairs measured/sample")
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "2,000 samples")
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []),
                reference="Pinocchio + coal loop")


if __name__ == "__main__":
    main()
