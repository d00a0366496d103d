"""Kawasaki's duAro SRDF closes a comment with ``--!>``, which XML forbids and MoveIt reads
(TinyXML2 ends a comment at the next ``-->``): pinframes reads it too, with one warning."""

from __future__ import annotations

import warnings
from pathlib import Path

import lxml.etree
import pytest

import pinframes
from pinframes.tree.robot_semantics import disabled_frame_pairs, group_state_values

DUARO = Path(__file__).resolve().parents[1] / "data" / "kawasaki"


def _duaro() -> pinframes.FrameTree:
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", ".*1 comment", UserWarning)
        return pinframes.read_urdf(DUARO / "duaro.urdf", srdf=DUARO / "khi_duaro.srdf")


def test_the_duaro_srdf_is_read_with_one_warning_naming_the_line():
    with pytest.warns(UserWarning, match=r"khi_duaro\.srdf: 1 comment.*line 59") as caught:
        pinframes.read_urdf(DUARO / "duaro.urdf", srdf=DUARO / "khi_duaro.srdf")
    assert len([found for found in caught if "comment" in str(found.message)]) == 1


def test_its_disabled_pairs_are_those_libxml2_recovers():
    tree = _duaro()
    recovered = lxml.etree.parse(str(DUARO / "khi_duaro.srdf"),
                                 lxml.etree.XMLParser(recover=True))
    expected = {frozenset((element.get("link1"), element.get("link2")))
                for element in recovered.iter("disable_collisions")}
    assert {frozenset(pair) for pair in disabled_frame_pairs(tree, tree.frames)} == expected
    assert len(expected) == 128


def test_its_group_states_are_read():
    tree = _duaro()
    home = group_state_values(tree, "upper_arm_home", tree.frames)
    recovered = lxml.etree.parse(str(DUARO / "khi_duaro.srdf"),
                                 lxml.etree.XMLParser(recover=True))
    (state,) = [element for element in recovered.iter("group_state")
                if element.get("name") == "upper_arm_home"]
    expected = {joint.get("name"): float(joint.get("value")) for joint in state.iter("joint")}
    assert home == pytest.approx(expected)

