"""Malformed input files, as data: what each reader gets and the error it must raise.

Each case names its reader (a key of ``readers.READERS``), the file content (text, bytes, or
``MISSING`` / ``FOLDER`` for a path that is no file), the error class, the ``frame`` and
``field`` the error must carry (None: it must carry none), a fragment of its message, which
file it must name (default: the file read) and other files to put beside it.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field

import numpy as np

from hardening.fuzz import small_asdf_file
from pinframes.errors import (
    FileFormatError,
    FrameExistsError,
    InvalidPoseError,
    InvalidTimeError,
    ReadError,
    UnsupportedFeatureError,
)
from weldx_asdf.asdf_texts import (
    asdf_text,
    digraph_hierarchy,
    digraph_node,
    lcs,
    legacy_hierarchy,
    time_values,
)

MISSING = "<no file at this path>"
FOLDER = "<a folder at this path>"
GARBAGE = bytes(range(256)) * 4
LATIN_1 = "frames:\n  café: {pose: {x: 1}}\n".encode("latin-1")


@dataclass(frozen=True)
class Case:
    id: str
    reader: str
    content: str | bytes
    error: type[Exception]
    frame: str | None
    field: str | None
    message: str
    file: str | None = ""  # "" means the file the case reads
    extra: dict[str, str | bytes] = field(default_factory=dict)


def urdf(body: str, links: str = "a b c") -> str:
    """A robot named ``r`` with the given links and ``body`` (joints)."""
    declared = "".join(f'<link name="{name}"/>' for name in links.split())
    return f'<robot name="r">{declared}{body}</robot>'


def joint(name: str, parent: str, child: str, kind: str = "revolute", inner: str = "") -> str:
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
            f'<child link="{child}"/><axis xyz="0 0 1"/>{inner}</joint>')


ARM = urdf(joint("j1", "a", "b") + joint("j2", "b", "c"))


def npz(**arrays) -> bytes:
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)
    return buffer.getvalue()


def scene(body: str) -> str:
    return "pinframes_scene: 1\n" + body


FRAMES_YAML = [
    Case("syntax-error", "frames.yaml", "frames:\n  a: {pose: {x: 1}\n  b: {}\n",
         FileFormatError, None, None, "YAML syntax error at line 3"),
    Case("truncated", "frames.yaml", "frames:\n  a:\n    pose: {x: 1, y:",
         FileFormatError, None, None, "YAML syntax error"),
    Case("empty", "frames.yaml", "", FileFormatError, None, None, "got nothing"),
    Case("only-comments", "frames.yaml", "# a map\n", FileFormatError, None, None,
         "got nothing"),
    Case("top-level-list", "frames.yaml", "- a\n- b\n", FileFormatError, None, None,
         "expected a mapping"),
    Case("frames-is-a-list", "frames.yaml", "frames: [a, b]\n", FileFormatError, None,
         "frames", "expected a mapping of keys"),
    Case("frame-is-a-number", "frames.yaml", "frames:\n  a: 3\n", FileFormatError, "a", None,
         "expected a mapping"),
    Case("pose-field-text", "frames.yaml", "frames:\n  a: {pose: {x: abc}}\n",
         FileFormatError, "a", "pose.x", "expected a number"),
    Case("pose-field-nan", "frames.yaml", "frames:\n  a: {pose: {y: .nan}}\n",
         FileFormatError, "a", "pose.y", "finite"),
    Case("pose-field-infinite", "frames.yaml", "frames:\n  a: {pose: {yaw: 1.0e+400}}\n",
         FileFormatError, "a", "pose.yaw", "finite"),
    Case("pose-field-huge-integer", "frames.yaml", f"frames:\n  a: {{pose: {{z: {10**400}}}}}\n",
         FileFormatError, "a", "pose.z", "finite"),
    Case("twist-field-list", "frames.yaml", "frames:\n  a: {twist: {v_x: [1]}}\n",
         FileFormatError, "a", "twist.v_x", "expected a number"),
    Case("pose-is-a-list", "frames.yaml", "frames:\n  a: {pose: [1, 2, 3]}\n",
         FileFormatError, "a", "pose", "expected a mapping"),
    Case("relative-to-cycle", "frames.yaml",
         "frames:\n  a: {relative_to: b}\n  b: {relative_to: a}\n",
         FileFormatError, "a", "relative_to", "relative_to cycle"),
    Case("relative-to-itself", "frames.yaml", "frames:\n  a: {relative_to: a}\n",
         FileFormatError, "a", "relative_to", "itself"),
    Case("relative-to-number", "frames.yaml", "frames:\n  a: {relative_to: 7}\n",
         FileFormatError, "a", "relative_to", "expected a frame key"),
    Case("unknown-unit", "frames.yaml", "frames:\n  a: {unit: furlongs}\n",
         FileFormatError, "a", "unit", "furlongs"),
    Case("tiles-without-tile-maps", "frames.yaml", "frames:\n  m/t: {unit: tiles}\n",
         FileFormatError, "m/t", "unit", "tile_maps.yaml"),
    Case("bad-tile-maps", "frames.yaml", "frames:\n  m/t: {unit: tiles}\n",
         FileFormatError, "m", "tile_size.x", "expected a number", file="tile_maps.yaml",
         extra={"tile_maps.yaml": "tile_maps:\n  m: {tile_size: {x: wide, y: 1}}\n"}),
    Case("duplicate-key", "frames.yaml", "frames:\n  a: {}\n  b: {}\n  a: {}\n",
         FileFormatError, "a", None, "duplicate key 'a' at line 4"),
    Case("empty-key-segment", "frames.yaml", "frames:\n  a//b: {}\n", FileFormatError,
         "a//b", None, "non-empty string"),
    Case("key-is-the-root", "frames.yaml", "frames:\n  world: {}\n", FileFormatError,
         "world", None, "root frame"),
    Case("include-tag", "frames.yaml", "frames: !include other.yaml\n", FileFormatError,
         None, "frames", "unsupported YAML tag"),
    Case("python-tag", "frames.yaml", "frames: !!python/object:os.system {}\n",
         FileFormatError, None, "frames", "unsupported YAML tag"),
    Case("version-is-a-list", "frames.yaml", "version: [1]\nframes: {}\n", FileFormatError,
         None, "version", "expected a string or a number"),
    Case("deeply-nested", "frames.yaml", "frames: {a: {pose: " + "[" * 5000 + "]" * 5000 + "}}",
         FileFormatError, None, None, "nested"),
    Case("binary-garbage", "frames.yaml", GARBAGE, ReadError, None, None, "not UTF-8"),
    Case("latin-1", "frames.yaml", LATIN_1, ReadError, None, None, "not UTF-8 text (byte 13)"),
    Case("nul-character", "frames.yaml", "frames:\n  a\x00: {}\n", FileFormatError, None,
         None, "#x0000"),
    Case("missing", "frames.yaml", MISSING, ReadError, None, None, "no such file"),
    Case("folder", "frames.yaml", FOLDER, ReadError, None, None, "is a folder"),
]

URDF = [
    Case("malformed-xml", "urdf", '<robot name="r"><link name="a"></robot>', FileFormatError,
         None, None, "malformed XML"),
    Case("truncated", "urdf", ARM[:60], FileFormatError, None, None, "malformed XML"),
    Case("empty", "urdf", "", FileFormatError, None, None, "malformed XML"),
    Case("not-a-robot", "urdf", "<sdf/>", FileFormatError, None, "robot", "<sdf>"),
    Case("unknown-joint-type", "urdf", urdf(joint("j1", "a", "b", "hinge"), "a b"),
         FileFormatError, "j1", "type", "unknown joint type 'hinge'"),
    Case("link-without-name", "urdf", '<robot name="r"><link/></robot>', FileFormatError,
         None, "link.name", "without 'name'"),
    Case("joint-without-parent", "urdf",
         urdf('<joint name="j1" type="fixed"><child link="b"/></joint>', "a b"),
         FileFormatError, "j1", "parent.link", "missing <parent link"),
    Case("unknown-child-link", "urdf", urdf(joint("j1", "a", "ghost"), "a"),
         FileFormatError, "j1", "child.link", "'ghost' is not defined"),
    Case("duplicate-link", "urdf", urdf("", "a a"), FileFormatError, "a", "name",
         "duplicate link"),
    Case("duplicate-joint", "urdf", urdf(joint("j", "a", "b") + joint("j", "b", "c")),
         FileFormatError, "j", "name", "duplicate joint"),
    Case("two-parents", "urdf", urdf(joint("j1", "a", "c") + joint("j2", "b", "c")),
         FileFormatError, "j2", "child.link", "two parents"),
    Case("link-cycle", "urdf",
         urdf(joint("j1", "a", "b") + joint("j2", "b", "c") + joint("j3", "c", "b")),
         FileFormatError, "j3", "child.link", "two parents"),
    Case("closed-loop", "urdf", urdf(joint("j1", "b", "c") + joint("j2", "c", "b"), "a b c"),
         FileFormatError, None, "link", "cycle"),
    Case("several-roots", "urdf", urdf(joint("j1", "a", "b")), FileFormatError, None, "link",
         "several links without a parent: a, c"),
    # a mimic of an unknown joint loads as an independent joint with a warning (or, with
    # strict=True, is refused): tests/urdf/test_every_example_robot.py
    Case("mimic-itself", "urdf", urdf(joint("j1", "a", "b", inner='<mimic joint="j1"/>'), "a b"),
         FileFormatError, "j1", "mimic.joint", "mimic cycle"),
    Case("mimic-cycle", "urdf",
         urdf(joint("j1", "a", "b", inner='<mimic joint="j2"/>')
              + joint("j2", "b", "c", inner='<mimic joint="j1"/>')),
         FileFormatError, "j1", "mimic.joint", "mimic cycle: j1 -> j2 -> j1"),
    Case("mimic-of-fixed", "urdf",
         urdf(joint("j1", "a", "b", "fixed") + joint("j2", "b", "c", inner='<mimic joint="j1"/>')),
         FileFormatError, "j2", "mimic.joint", "fixed"),
    Case("mimic-multiplier-text", "urdf",
         urdf(joint("j1", "a", "b") + joint("j2", "b", "c", inner='<mimic joint="j1" '
                                            'multiplier="twice"/>')),
         FileFormatError, "j2", "mimic.multiplier", "expected a finite number"),
    Case("origin-two-numbers", "urdf",
         urdf(joint("j1", "a", "b", inner='<origin xyz="1 2"/>'), "a b"),
         FileFormatError, "j1", "origin.xyz", "three finite numbers"),
    Case("origin-nan", "urdf", urdf(joint("j1", "a", "b", inner='<origin rpy="nan 0 0"/>'), "a b"),
         FileFormatError, "j1", "origin.rpy", "three finite numbers"),
    Case("origin-overflow", "urdf",
         urdf(joint("j1", "a", "b", inner='<origin xyz="1e400 0 0"/>'), "a b"),
         FileFormatError, "j1", "origin.xyz", "three finite numbers"),
    Case("limit-text", "urdf", urdf(joint("j1", "a", "b", inner='<limit lower="low"/>'), "a b"),
         FileFormatError, "j1", "limit.lower", "expected a finite number"),
    Case("zero-axis", "urdf",
         urdf('<joint name="j1" type="prismatic"><parent link="a"/><child link="b"/>'
              '<axis xyz="0 0 0"/></joint>', "a b"),
         FileFormatError, "j1", "axis.xyz", "must not be zero"),
    Case("entity-bomb", "urdf",
         '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">'
         + "".join(f'<!ENTITY {chr(98 + i)} "' + f"&{chr(97 + i)};" * 10 + '">'
                   for i in range(8))
         + ']><robot name="&i;"><link name="a"/></robot>',
         FileFormatError, None, "DOCTYPE", "entities defined in one can expand"),
    Case("deeply-nested-link", "urdf",
         '<robot name="r"><link name="a">' + "<v>" * 3000 + "</v>" * 3000 + "</link></robot>",
         FileFormatError, None, "v", "nested more than 1,000 levels deep"),
    Case("binary-garbage", "urdf", GARBAGE, ReadError, None, None, "not UTF-8"),
    Case("missing", "urdf", MISSING, ReadError, None, None, "no such file"),
    Case("folder", "urdf", FOLDER, ReadError, None, None, "is a folder"),
    Case("attach-malformed", "attach_urdf", "<robot", FileFormatError, None, None,
         "malformed XML"),
    Case("attach-link-named-like-the-root", "attach_urdf", urdf("", "world"),
         FrameExistsError, "world", None, "another prefix"),
    Case("attach-mimic-cycle", "attach_urdf",
         urdf(joint("j1", "a", "b", inner='<mimic joint="j2"/>')
              + joint("j2", "b", "c", inner='<mimic joint="j1"/>')),
         FileFormatError, "j1", "mimic.joint", "mimic cycle"),
    Case("attach-missing", "attach_urdf", MISSING, ReadError, None, None, "no such file"),
]

SCENE = [
    Case("empty", "scene", "", FileFormatError, None, None, "not a pinframes scene"),
    Case("syntax-error", "scene", "pinframes_scene: 1\nframes: [\n", FileFormatError, None,
         None, "YAML syntax error"),
    Case("newer-version", "scene", "pinframes_scene: 2\n", UnsupportedFeatureError, None,
         "pinframes_scene", "version 2"),
    Case("unknown-top-key", "scene", scene("robot: []\n"), FileFormatError, None, None,
         "unknown key(s) robot"),
    Case("frames-not-a-list", "scene", scene("frames: {a: 1}\n"), FileFormatError, None,
         "frames", "expected a list"),
    Case("frame-not-a-mapping", "scene", scene("frames: [table]\n"), FileFormatError, None,
         "frames[0]", "expected a mapping"),
    Case("frame-without-parent", "scene", scene("frames: [{name: a}]\n"), FileFormatError,
         "a", "frames[0].parent", "missing"),
    Case("unknown-parent", "scene", scene("frames: [{name: a, parent: ghost}]\n"),
         FileFormatError, "a", "frames[0].parent", "'ghost' is neither in the scene"),
    Case("parent-cycle", "scene",
         scene("frames: [{name: a, parent: b}, {name: b, parent: a}]\n"),
         FileFormatError, "a", "frames[0].parent", "neither in the scene"),
    Case("duplicate-frame", "scene",
         scene("frames: [{name: a, parent: world}, {name: a, parent: world}]\n"),
         FrameExistsError, "a", "frames[1]", "already has a frame"),
    Case("unknown-frame-key", "scene", scene("frames: [{name: a, parent: world, xzy: []}]\n"),
         FileFormatError, None, "frames[0]", "unknown key(s) xzy"),
    Case("xyz-two-numbers", "scene", scene("frames: [{name: a, parent: world, xyz: [1, 2]}]\n"),
         FileFormatError, "a", "frames[0].xyz", "list of 3 numbers"),
    Case("xyz-nan", "scene", scene("frames: [{name: a, parent: world, xyz: [.nan, 0, 0]}]\n"),
         FileFormatError, "a", "frames[0].xyz", "finite"),
    Case("xyz-huge-integer", "scene",
         scene(f"frames: [{{name: a, parent: world, xyz: [{10**400}, 0, 0]}}]\n"),
         FileFormatError, "a", "frames[0].xyz", "finite"),
    Case("rpy-and-quaternion", "scene",
         scene("frames: [{name: a, parent: world, rpy: [0, 0, 0], quaternion: [0, 0, 0, 1]}]\n"),
         FileFormatError, "a", "frames[0].rpy", "not both"),
    Case("quaternion-not-unit", "scene",
         scene("frames: [{name: a, parent: world, quaternion: [0, 0, 0, 2]}]\n"),
         FileFormatError, "a", "frames[0].quaternion", "unit norm"),
    Case("quaternion-zero", "scene",
         scene("frames: [{name: a, parent: world, quaternion: [0, 0, 0, 0]}]\n"),
         FileFormatError, "a", "frames[0].quaternion", "unit norm"),
    Case("keyframes-not-increasing", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{time: 1}, {time: 0}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "strictly increasing"),
    Case("keyframes-duplicate-time", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{time: 1}, {time: 1.0}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "strictly increasing"),
    Case("keyframe-without-time", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{xyz: [0, 0, 0]}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes[0].time", "missing"),
    Case("keyframe-time-text", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{time: soon}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "cannot read a time"),
    Case("keyframe-time-overflows-ns", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{time: 1.0e+300}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "292 years"),
    Case("keyframe-duration-overflows-ns", "scene",
         scene("frames: [{name: a, parent: world, keyframes: [{time: 1e300s}]}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "292 years"),
    Case("keyframe-integer-overflows-ns", "scene",
         scene(f"frames: [{{name: a, parent: world, keyframes: [{{time: {10**30}}}]}}]\n"),
         FileFormatError, "a", "frames[0].keyframes.time", "292 years"),
    Case("reference-time-garbage", "scene", scene("reference_time: yesterday\n"),
         FileFormatError, None, "reference_time", "cannot read a time"),
    Case("reference-time-out-of-range", "scene", scene("reference_time: 9999-12-31\n"),
         FileFormatError, None, "reference_time", "292 years"),
    Case("reference-time-without-keyframes", "scene",
         scene("frames: [{name: a, parent: world, reference_time: 2024-01-01}]\n"),
         FileFormatError, "a", "frames[0].reference_time", "needs keyframes"),
    Case("root-not-a-string", "scene", scene("root: 5\n"), FileFormatError, None, "root",
         "non-empty string"),
    Case("layer-missing-file", "scene", scene("layers: [{file: gone.frames.yaml}]\n"),
         FileFormatError, None, "layers[0].file", "no such file"),
    # layers are told by content: a frames.yaml named layer.txt is a layer, a URDF is not
    Case("layer-wrong-kind", "scene", scene("layers: [{file: layer.txt}]\n"),
         FileFormatError, None, "layers[0].file", "frames.yaml (.yaml) or ASDF",
         extra={"layer.txt": "<robot name='r'><link name='a'/></robot>\n"}),
    Case("layer-malformed", "scene", scene("layers: [{file: layer.frames.yaml}]\n"),
         FileFormatError, "a", "pose.x", "referenced by", file="layer.frames.yaml",
         extra={"layer.frames.yaml": "frames:\n  a: {pose: {x: far}}\n"}),
    Case("layer-clashes-with-frame", "scene",
         scene("layers: [{file: layer.frames.yaml}]\nframes: [{name: a, parent: world}]\n"),
         FrameExistsError, "a", "frames[0]", "already has a frame",
         extra={"layer.frames.yaml": "frames:\n  a: {}\n"}),
    Case("robot-malformed-urdf", "scene", scene("robots: [{urdf: arm.urdf}]\n"),
         FileFormatError, None, None, "referenced by", file="arm.urdf",
         extra={"arm.urdf": "<robot"}),
    Case("robot-unknown-joint-in-trajectory", "scene",
         scene("robots: [{urdf: arm.urdf, trajectory: motion.csv}]\n"),
         FileFormatError, "j9", "header", "no joint 'j9'", file="motion.csv",
         extra={"arm.urdf": ARM, "motion.csv": "time_s,j9\n0,1\n"}),
    Case("robot-urdf-is-binary", "scene", scene("robots: [{urdf: arm.urdf}]\n"), ReadError,
         None, None, "not UTF-8", file="arm.urdf", extra={"arm.urdf": GARBAGE}),
    Case("tool-not-a-mapping", "scene", scene("tools: [tcp]\n"), FileFormatError, None,
         "tools[0]", "expected a mapping"),
    Case("binary-garbage", "scene", GARBAGE, ReadError, None, None, "not UTF-8"),
    Case("missing", "scene", MISSING, ReadError, None, None, "no such file"),
    Case("folder", "scene", FOLDER, ReadError, None, None, "is a folder"),
]

TRAJECTORY = [
    Case("empty", "csv", "", FileFormatError, None, None, "empty file"),
    Case("header-only", "csv", "time_s,j1\n", FileFormatError, None, None, "no samples"),
    Case("no-time-column", "csv", "j1,j2\n0,1\n", FileFormatError, None, "line 1",
         "first column must be the time"),
    Case("no-joint-columns", "csv", "time_s\n0\n", FileFormatError, None, "line 1",
         "no joint columns"),
    Case("duplicate-joint", "csv", "time_s,j1,j1\n0,1,2\n", FileFormatError, "j1", "line 1",
         "joint named twice"),
    Case("empty-joint-name", "csv", "time_s,,j2\n0,1,2\n", FileFormatError, None, "line 1",
         "empty"),
    Case("short-row", "csv", "time_s,j1,j2\n0,1,2\n1,1\n", FileFormatError, None, "line 3",
         "2 values, but the header has 3 columns"),
    Case("value-text", "csv", "time_s,j1\n0,up\n", FileFormatError, "j1", "line 2",
         "expected a number, got 'up'"),
    Case("value-nan", "csv", "time_s,j1\n0,1\n1,nan\n", FileFormatError, "j1", "line 3",
         "the joint value nan is not finite"),
    Case("time-text", "csv", "time_s,j1\nsoon,1\n", FileFormatError, None, "line 2",
         "expected seconds in 'time_s'"),
    Case("time-infinite", "csv", "time_s,j1\n0,1\ninf,2\n", FileFormatError, None, "line 3",
         "the time inf is not finite"),
    Case("time-overflows-ns", "csv", "time_s,j1\n0,1\n1e300,2\n", FileFormatError, None,
         "times", "292 years"),
    Case("times-decreasing", "csv", "time_s,j1\n1,0\n0,1\n", FileFormatError, None, "line 3",
         "this time is not after the one at line 2"),
    Case("times-duplicate", "csv", "time_s,j1\n0,0\n1,1\n1,2\n", FileFormatError, None,
         "line 4", "this time is not after the one at line 3"),
    Case("iso-times-duplicate", "csv",
         "time,j1\n2024-01-01T00:00:00,0\n2024-01-01T00:00:00,1\n", FileFormatError, None,
         "line 3", "strictly increasing"),
    Case("times-mixed-kinds", "csv", "time,j1\n2024-01-01T00:00:00,0\n2s,1\n",
         FileFormatError, None, "time", "mixes absolute timestamps and relative durations"),
    Case("duration-overflows-ns", "csv", "time,j1\n0s,0\n1e300s,1\n", FileFormatError,
         None, "time", "292 years"),
    Case("timestamp-out-of-range", "csv", "time,j1\n9999-12-31,0\n", FileFormatError, None,
         "time", "292 years"),
    Case("nul-character", "csv", "time_s,j1\n0,1\x00\n", FileFormatError, "j1", "line 2",
         "expected a number"),
    Case("binary-garbage", "csv", GARBAGE, ReadError, None, None, "not UTF-8"),
    Case("missing", "csv", MISSING, ReadError, None, None, "no such file"),
    Case("folder", "csv", FOLDER, ReadError, None, None, "is a folder"),
    Case("npz-garbage", "npz", GARBAGE, FileFormatError, None, None, "not a readable NPZ"),
    Case("npz-truncated", "npz",
         npz(times=[0.0, 1.0], positions=[[0.0], [1.0]], joint_names=["j1"])[:200],
         FileFormatError, None, None, "NPZ"),
    Case("npz-missing-array", "npz", npz(times=[0.0], positions=[[0.0]]), FileFormatError,
         None, None, "missing array(s) joint_names"),
    Case("npz-shape-mismatch", "npz",
         npz(times=[0.0, 1.0], positions=[[0.0, 1.0]], joint_names=["j1"]), FileFormatError,
         None, "positions", "expected numbers of shape (2, 1)"),
    Case("npz-names-are-numbers", "npz",
         npz(times=[0.0], positions=[[0.0]], joint_names=[1]), FileFormatError, None,
         "joint_names", "1-D array of strings"),
    Case("npz-object-array", "npz",
         npz(times=np.array([0.0, None], dtype=object), positions=[[0.0], [1.0]],
             joint_names=["j1"]),
         FileFormatError, None, "times", "cannot read the array"),
    Case("npz-missing", "npz", MISSING, ReadError, None, None, "no such file"),
]



def legacy_asdf(*entries, **options) -> str:
    """A 1.0.0 hierarchy ``h`` rooted at ``root``; entries are ``(name, reference, lcs)``."""
    return asdf_text(legacy_hierarchy("h", "root", entries, **options))


def legacy_lcs(**parts) -> str:
    return lcs(version="1.0.0", **parts)


def moving_legacy_asdf(coordinates, nanoseconds, **options) -> str:
    """Frame ``a`` in ``root``, its coordinates at the given times."""
    return legacy_asdf(("a", "root", legacy_lcs(
        coordinates=coordinates, time=time_values(nanoseconds, legacy=True), **options)))


def digraph_asdf(*edges, **options) -> str:
    """A 0.1.0 hierarchy ``h``: ``root`` with edges ``(lcs, child node)`` to its children."""
    return asdf_text(digraph_hierarchy(
        "h", digraph_node("root", [("bwd", transformation, child)
                                   for transformation, child in edges]), **options))


def asdf_list(text: str) -> str:
    """A legacy hierarchy whose ``coordinate_systems`` is ``text``."""
    return legacy_asdf().replace("coordinate_systems: []", f"coordinate_systems: {text}")


STATIC_ASDF = legacy_asdf(("a", "root", legacy_lcs(coordinates=[1, 2, 3])))
LEGACY_ENTRY = "!legacy!core/transformations/coordinate_transformation-1.0.0"
LEGACY_LCS = "!legacy!core/transformations/local_coordinate_system-1.0.0"
FIELD = "coordinate_systems[0].transformation"
BLOCKS = small_asdf_file("0.1.0")
FIRST_BLOCK = BLOCKS.index(b"\xd3BLK")

ASDF = [
    Case("syntax-error", "asdf", asdf_text("csm: {a: [1, 2\n"), FileFormatError, None, None,
         "not a readable ASDF file"),
    Case("truncated", "asdf", STATIC_ASDF[:-60], FileFormatError, None, None,
         "not a readable ASDF file"),
    Case("empty", "asdf", "", FileFormatError, None, None, "not a readable ASDF file"),
    Case("binary-garbage", "asdf", GARBAGE, FileFormatError, None, None,
         "not a readable ASDF file"),
    Case("missing", "asdf", MISSING, ReadError, None, None, "no such file"),
    Case("folder", "asdf", FOLDER, ReadError, None, None, "is a folder"),
    Case("no-hierarchy", "asdf", asdf_text("csm: 1\n"), FileFormatError, None, None,
         "no weldx coordinate system hierarchy"),
    Case("several-hierarchies", "asdf",
         asdf_text(legacy_hierarchy("h", "root", []) + "\n"
                   + legacy_hierarchy("g", "root", []).replace("csm:", "other:")),
         FileFormatError, None, None, "under the keys 'csm', 'other'"),
    Case("legacy-without-root", "asdf",
         asdf_text("csm: !legacy!core/transformations/coordinate_system_hierarchy-1.0.0 "
                   "{name: h, coordinate_systems: []}"),
         FileFormatError, None, "root_system_name", "'root_system_name' is missing"),
    Case("digraph-without-graph", "asdf",
         asdf_text("csm: !weldx!core/transformations/coordinate_system_hierarchy-0.1.0 "
                   "{name: h}"),
         FileFormatError, None, "graph", "'graph' is missing"),
    Case("entry-without-name", "asdf",
         asdf_list(f"[{LEGACY_ENTRY} {{reference_system: root, "
                   f"transformation: {LEGACY_LCS} {{}}}}]"),
         FileFormatError, None, "coordinate_systems[0]", "'name' is missing"),
    Case("entries-not-a-list", "asdf", asdf_list("5"), FileFormatError, None,
         "coordinate_systems", "expected a list, got int"),
    Case("entry-not-a-mapping", "asdf", asdf_list("[5]"), FileFormatError, None,
         "coordinate_systems[0]", "expected a mapping, got int"),
    Case("coordinates-text", "asdf",
         legacy_asdf(("a", "root", f"{LEGACY_LCS} {{coordinates: !legacy!core/variable-1.0.0 "
                      "{name: coordinates, dimensions: [c], dtype: <f8, data: [a, b, c]}}")),
         FileFormatError, "a", f"{FIELD}.coordinates.data", "cannot read the numbers"),
    Case("unknown-transformation-tag", "asdf",
         legacy_asdf(("a", "root", "!legacy!core/transformations/mystery-1.0.0 {}")),
         FileFormatError, "a", FIELD, "mystery-1.0.0"),
    Case("unknown-edge-transformation-tag", "asdf",
         digraph_asdf(("!weldx!core/transformations/mystery-0.1.0 {}", digraph_node("a"))),
         FileFormatError, "a", "edge.attributes.transformation", "mystery-0.1.0"),
    Case("coordinates-nan", "asdf",
         legacy_asdf(("a", "root", legacy_lcs(coordinates=[7.5, 0, 0]).replace(
             "7.5", ".nan", 1))),
         InvalidPoseError, "a", f"{FIELD}.coordinates", "finite"),
    Case("coordinates-huge", "asdf",
         legacy_asdf(("a", "root", legacy_lcs(coordinates=[7.5, 0, 0]).replace(
             "7.5", "1e400", 1))),
         InvalidPoseError, "a", f"{FIELD}.coordinates", "finite"),
    Case("reflection", "asdf",
         legacy_asdf(("a", "root", legacy_lcs(orientations=np.diag([1, 1, -1])))),
         InvalidPoseError, "a", f"{FIELD}.orientations", "reflection"),
    Case("non-orthonormal-rotation", "asdf",
         legacy_asdf(("a", "root", legacy_lcs(orientations=[[1, 0.1, 0], [0, 1, 0],
                                                            [0, 0, 1]]))),
         InvalidPoseError, "a", f"{FIELD}.orientations", "not orthonormal"),
    Case("orientations-wrong-shape", "asdf",
         legacy_asdf(("a", "root", legacy_lcs(orientations=[1, 0, 0]))),
         InvalidPoseError, "a", f"{FIELD}.orientations", "got shape (3,)"),
    Case("times-not-increasing", "asdf", moving_legacy_asdf([[0, 0, 0], [1, 0, 0]], [2, 1]),
         InvalidTimeError, "a", f"{FIELD}.time", "strictly increasing"),
    Case("times-duplicate", "asdf", moving_legacy_asdf([[0, 0, 0], [1, 0, 0]], [1, 1]),
         InvalidTimeError, "a", f"{FIELD}.time", "strictly increasing"),
    Case("times-and-coordinates-differ", "asdf",
         moving_legacy_asdf([[0, 0, 0], [1, 0, 0]], [1, 2, 3]),
         InvalidPoseError, "a", f"{FIELD}.coordinates", "2 samples given for 3 times"),
    Case("times-beyond-int64-after-reference", "asdf",
         moving_legacy_asdf([[0, 0, 0], [1, 0, 0]], [0, 2**63 - 2],
                            reference_time="2200-01-01T00:00:00"),
         InvalidTimeError, "a", f"{FIELD}.time", "292 years"),
    Case("reference-time-garbage", "asdf", legacy_asdf(reference_time="yesterday"),
         InvalidTimeError, None, "reference_time", "cannot read a time"),
    Case("entries-in-a-cycle", "asdf",
         legacy_asdf(("a", "root", legacy_lcs()), ("b", "c", legacy_lcs()),
                     ("c", "b", legacy_lcs())),
         FileFormatError, "b", "coordinate_systems[1]", "not connected to the root"),
    Case("entry-closes-a-loop", "asdf",
         legacy_asdf(("a", "root", legacy_lcs()), ("a", "root", legacy_lcs())),
         FileFormatError, "a", "coordinate_systems[1].transformation", "closes a loop"),
    Case("duplicate-frame-name", "asdf",
         digraph_asdf((lcs(coordinates=[1, 2, 3]), digraph_node("a")),
                      (lcs(coordinates=[3, 2, 1]), digraph_node("a"))),
         FileFormatError, "a", "edge.target_node", "appears twice"),
    Case("unknown-unit", "asdf",
         digraph_asdf((lcs(coordinates=[1, 2, 3], units="furlong"), digraph_node("a"))),
         FileFormatError, "a", "edge.attributes.transformation.coordinates.units",
         "unknown length unit 'furlong'"),
    Case("unknown-subsystem-member", "asdf",
         legacy_asdf(("a", "root", legacy_lcs()), extra=(
             "subsystems:\n- !legacy!core/transformations/coordinate_system_hierarchy_subsystem"
             "-1.0.0 {name: s, root_cs: a, members: [a, ghost]}\n")),
         FileFormatError, "ghost", "subsystems.members", "'ghost'"),
    Case("time-series-coordinates", "asdf",
         digraph_asdf(("!weldx!core/transformations/local_coordinate_system-0.1.1 "
                       "{coordinates: !weldx!core/time_series-0.1.0 {expression: "
                       "!weldx!core/mathematical_expression-0.1.0 {expression: a*t}}}",
                       digraph_node("a"))),
         UnsupportedFeatureError, "a", "edge.attributes.transformation.coordinates",
         "math expression 'a*t'"),
    Case("broken-binary-block", "asdf",
         BLOCKS[:FIRST_BLOCK] + b"XBLK" + BLOCKS[FIRST_BLOCK + 4:], FileFormatError, "torch",
         "edge.attributes.transformation.orientations.data", "cannot read the numbers"),
    Case("truncated-binary-block", "asdf", BLOCKS[:FIRST_BLOCK + 80], FileFormatError,
         "torch", "edge.attributes.transformation.orientations.data",
         "cannot read the numbers"),
]

ROSBAG = [
    Case("missing", "rosbag", MISSING, ReadError, None, None, "no such file"),
    Case("garbage", "rosbag", GARBAGE, FileFormatError, None, None, "not a ROS bag"),
    Case("folder-without-metadata", "rosbag", FOLDER, FileFormatError, None, None,
         "a folder without metadata.yaml"),
    Case("ros1-magic-only", "rosbag", b"#ROSBAG V2.0\n", FileFormatError, None, None,
         "truncated or corrupt"),
    Case("ros1-garbage", "rosbag", b"#ROSBAG V2.0\n" + GARBAGE, FileFormatError, None, None,
         "truncated or corrupt"),
    Case("mcap-magic-only", "rosbag", b"\x89MCAP0\r\n", FileFormatError, None, None,
         "truncated or corrupt"),
    Case("mcap-garbage", "rosbag", b"\x89MCAP0\r\n" + GARBAGE, FileFormatError, None, None,
         "truncated or corrupt"),
    Case("sqlite-garbage", "rosbag", b"SQLite format 3\x00" + GARBAGE, FileFormatError, None,
         None, "truncated or corrupt"),
]

FILE_CASES = FRAMES_YAML + URDF + SCENE + TRAJECTORY + ASDF + ROSBAG
