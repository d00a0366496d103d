"""Bad API calls raise located pinframes errors and leave the tree exactly as it was."""

from __future__ import annotations

import copy
import warnings
from typing import Any

import pytest

from hardening.api_cases import CALLS, Call, sample_tree
from pinframes import FrameTree, Pose
from pinframes.errors import JointWithoutSamplesWarning, PinframesError


def pose_state(pose: Pose) -> tuple:
    times = None if pose.times is None else pose.times.tolist()
    return (pose.translation.tolist(), pose.rotation.tolist(), times, pose.reference_time)


def snapshot(tree: FrameTree) -> dict[str, Any]:
    """Everything a tree holds, as plain values, plus one query through all its parts."""
    frames = {}
    for name in tree.frames:
        local = None if name == tree.root else pose_state(tree.local_pose(name))
        frames[name] = (tree.parent(name), tree.children(name), local, tree.joint_of(name),
                        copy.deepcopy(tree.frame_metadata(name)))
    tracks = {}
    for name in tree.joints:
        track = tree.joint_track(name)
        tracks[name] = None if track is None else (track.times.tolist(), track.reference,
                                                   track.values.tolist())
    return {
        "root": tree.root, "name": tree.name, "reference_time": tree.reference_time,
        "frames": frames, "order": tree.frames, "joints": tree.joints, "tracks": tracks,
        "subsystems": list(tree.subsystems), "metadata": copy.deepcopy(tree.metadata),
        "query": pose_state(_pose_quietly(tree, "arm/c", "world")),
    }


def _pose_quietly(tree, frame, relative_to):
    """The pose for the record: a joint without samples warns, which is not what is compared."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        return tree.pose(frame, relative_to)


@pytest.mark.parametrize("case", CALLS, ids=lambda case: case.id)
def test_bad_call_raises_a_located_error_and_leaves_the_tree_unchanged(case: Call):
    tree = sample_tree()
    before = snapshot(tree)
    with pytest.raises(PinframesError) as info:
        case.call(tree)
    error = info.value
    assert type(error) is case.error, f"{type(error).__name__}: {error}"
    # the frame, or the joint for errors about a robot joint (a URDF joint, a trajectory column)
    subject = error.frame if error.frame is not None else error.joint
    assert (subject, error.field) == (case.frame, case.field), str(error)
    assert case.message in error.message, str(error)
    assert snapshot(tree) == before


def test_the_snapshot_sees_every_kind_of_change():
    # The comparison above is only worth something if each part of a tree shows in it.
    changes = [
        lambda t: t.set_local_pose("table", Pose([0.0, 0.0, 0.0])),
        lambda t: t.rename("table", "bench"),
        lambda t: t.set_joint_track("arm/j1", None),
        lambda t: t.subsystems.clear(),
        lambda t: t.frame_metadata("table").update(note=1),
        lambda t: t.add("x", "world"),
    ]
    for change in changes:
        tree = sample_tree()
        before = snapshot(tree)
        change(tree)
        assert snapshot(tree) != before
