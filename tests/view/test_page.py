"""The page's content: the animation tracks and placements it carries, checked with numpy."""

from __future__ import annotations

import base64
import json
import re

import numpy as np
import pytest
import umsgpack

from pinframes import FrameTree, Pose
from pinframes.errors import InvalidTimeError, UnsupportedFeatureError
from pinframes.view import view_html
from pinframes.view._scene import node_path


def page_data(page: str) -> dict:
    """The embedded settings, with the meshcat commands decoded."""
    found = re.search(r'<script type="application/json" id="pinframes-data">(.*?)</script>',
                      page, re.S)
    assert found is not None
    data = json.loads(found.group(1))
    data["commands"] = [umsgpack.unpackb(base64.b64decode(c)) for c in data["commands"]]
    return data


def floats(ext) -> np.ndarray:
    assert ext.type == 0x17  # meshcat's viewer reads this code as a Float32Array
    return np.frombuffer(ext.data, dtype=np.float32)


def turning_tree() -> FrameTree:
    """``arm`` turns 90 degrees about world z in 2 s; ``tip`` sits 1 m along its x axis."""
    half = np.pi / 4
    tree = FrameTree(root="world")
    tree.add("arm", "world", Pose(translation=[0.0, 0.0, 0.5],
                                  rotation=[[0, 0, 0, 1], [0, 0, np.sin(half), np.cos(half)]],
                                  times=[0.0, 2.0]))
    tree.add("tip", "arm", Pose(translation=[1.0, 0.0, 0.0]))
    tree.add("post", "world", Pose(translation=[2.0, 3.0, 0.0]))
    return tree


def tracks(data: dict) -> dict[str, dict]:
    (animation,) = [c for c in data["commands"] if c["type"] == "set_animation"]
    return {a["path"]: {t["name"]: t for t in a["clip"]["tracks"]}
            for a in animation["animations"]}


def test_moving_frames_get_tracks_that_follow_the_circle():
    times = np.linspace(0.0, 2.0, 9)
    data = page_data(view_html(turning_tree(), times=times, paths={"tip": "world"}))
    angles = np.pi / 2 * times / 2.0
    found = tracks(data)
    assert set(found) == {node_path("arm"), node_path("tip")}  # "post" does not move
    tip = found[node_path("tip")]
    np.testing.assert_allclose(floats(tip[".position"]["times"]), times, atol=1e-6)
    expected = np.stack([np.cos(angles), np.sin(angles), np.full_like(angles, 0.5)], axis=1)
    np.testing.assert_allclose(floats(tip[".position"]["values"]).reshape(-1, 3), expected,
                               atol=1e-6)
    quaternions = np.stack([0 * angles, 0 * angles, np.sin(angles / 2), np.cos(angles / 2)], 1)
    np.testing.assert_allclose(floats(tip[".quaternion"]["values"]).reshape(-1, 4),
                               quaternions, atol=1e-6)
    (line,) = [c for c in data["commands"] if c["type"] == "set_object"
               and c["path"].endswith("/paths/path:tip")]
    geometry = line["object"]["geometries"][0]["data"]["attributes"]["position"]
    np.testing.assert_allclose(floats(geometry["array"]).reshape(-1, 3), expected, atol=1e-6)
    assert data["duration"] == pytest.approx(2.0)
    assert [label["text"] for label in data["labels"]] == ["world", "arm", "tip", "post"]


def test_static_frames_are_placed_once():
    data = page_data(view_html(turning_tree(), times=[0.0, 1.0]))
    (post,) = [c for c in data["commands"] if c["type"] == "set_transform"
               and c["path"] == node_path("post")]
    matrix = np.array(post["matrix"]).reshape(4, 4).T  # column-major, as three.js reads it
    np.testing.assert_allclose(matrix, [[1, 0, 0, 2], [0, 1, 0, 3], [0, 0, 1, 0],
                                        [0, 0, 0, 1]])


def test_default_times_are_the_samples_of_the_moving_frames():
    data = page_data(view_html(turning_tree()))
    times = floats(tracks(data)[node_path("arm")][".position"]["times"])
    np.testing.assert_allclose(times, [0.0, 2.0])


def test_a_static_tree_has_no_animation():
    tree = FrameTree(root="world")
    tree.add("a", "world", Pose(translation=[1.0, 0.0, 0.0]))
    data = page_data(view_html(tree))
    assert not [c for c in data["commands"] if c["type"] == "set_animation"]
    assert data["duration"] == 0.0


def test_too_many_times_are_refused():
    with pytest.raises(InvalidTimeError, match="larger step"):
        view_html(turning_tree(), times=np.linspace(0.0, 2.0, 20_001))


def test_the_page_needs_nothing_from_the_network():
    page = view_html(turning_tree())
    assert "MeshCat" in page and "pinframes-data" in page
    assert not re.search(r"""(src|href)\s*=\s*["']https?:""", page)


def test_without_meshcat_the_page_is_refused_with_the_extra_to_install(monkeypatch):
    import pinframes.view._page as page_module

    monkeypatch.setattr(page_module.importlib.util, "find_spec", lambda name: None)
    with pytest.raises(UnsupportedFeatureError, match=r"pinframes\[view\]"):
        view_html(turning_tree())


def test_absolute_times_start_at_their_timestamp():
    tree = FrameTree(root="world", reference_time="2024-03-01T08:00:00")
    tree.add("cart", "world", Pose(translation=[[0.0, 0, 0], [3.0, 0, 0]], times=[10.0, 13.0]))
    data = page_data(view_html(tree))
    assert data["start"].startswith("2024-03-01T08:00:10")
    assert data["duration"] == pytest.approx(3.0)
    positions = floats(tracks(data)[node_path("cart")][".position"]["values"]).reshape(-1, 3)
    np.testing.assert_allclose(positions, [[0, 0, 0], [3, 0, 0]])
