"""SRDF files that ask for exponential or quadratic work: groups resolved once, a link whose
every pair is disabled kept as one rule, repeats merged; names defined twice warned about."""

from __future__ import annotations

import itertools
import warnings
from pathlib import Path

import pytest

import pinframes
from hardening.capped import run_capped
from pinframes.errors import SrdfWarning
from pinframes.tree.robot_semantics import semantic_robots


def chain_urdf(folder: Path, links: int) -> Path:
    """A chain of ``links`` links ``l0`` .. joined by revolute joints ``j1`` ..."""
    joints = "".join(
        f'<joint name="j{n}" type="revolute"><parent link="l{n - 1}"/><child link="l{n}"/>'
        f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for n in range(1, links))
    link_elements = "".join(f'<link name="l{n}"/>' for n in range(links))
    path = folder / "chain.urdf"
    path.write_text(f'<robot name="chain">{link_elements}{joints}</robot>')
    return path


READ = """
import pinframes
tree = pinframes.read_urdf(sys.argv[2], srdf=sys.argv[3])
from pinframes.tree.robot_semantics import semantic_robots
(robot,) = semantic_robots(tree)
print("READ", {name: len(joints) for name, joints in robot.semantics.groups.items()
               if name in ("g0", "g39")}, robot.semantics.disabled_pair_count())
"""


def test_groups_naming_their_subgroup_twice_per_level_are_resolved_once(tmp_path):
    # 40 levels, each naming the one below twice: 2**40 walks of g0 before groups were
    # resolved once (2.6 kB that never finished)
    urdf = chain_urdf(tmp_path, 4)
    levels = ['<group name="g0"><joint name="j2"/><chain base_link="l0" tip_link="l1"/></group>']
    levels += [f'<group name="g{n}"><group name="g{n - 1}"/><group name="g{n - 1}"/></group>'
               for n in range(1, 40)]
    srdf = tmp_path / "nested.srdf"
    srdf.write_text(f'<robot name="chain">{"".join(levels)}</robot>')
    assert len(srdf.read_bytes()) < 3000
    outcome = run_capped(READ, str(urdf), str(srdf))
    assert outcome == "READ {'g0': 2, 'g39': 2} 0", outcome


def test_every_pair_of_thousands_of_links_is_one_rule_each(tmp_path):
    # 4,500 links, each <disable_default_collisions>, and one of them 20,000 times: 10
    # million pairs kept one by one (2.6 GB, then a MemoryError) and 20,000 loops over
    # every link before; now 4,500 rules, the count from the rule
    links = 4500
    urdf = chain_urdf(tmp_path, links)
    rules = [f'<disable_default_collisions link="l{n}"/>' for n in range(links)]
    rules += ['<disable_default_collisions link="l7"/>'] * 20_000
    srdf = tmp_path / "everything.srdf"
    srdf.write_text(f'<robot name="chain">{"".join(rules)}</robot>')
    outcome = run_capped(READ, str(urdf), str(srdf))
    assert outcome == f"READ {{}} {links * (links - 1) // 2}", outcome


def test_disabled_links_pairs_and_exceptions_answer_as_the_pairs_would(tmp_path):
    urdf = chain_urdf(tmp_path, 6)
    srdf = tmp_path / "rules.srdf"
    srdf.write_text('<robot name="chain"><disable_default_collisions link="l1"/>'
                    '<disable_default_collisions link="l1"/>'
                    '<disable_collisions link1="l3" link2="l4"/>'
                    '<disable_collisions link1="l4" link2="l3"/>'
                    '<enable_collisions link1="l1" link2="l5"/>'
                    '<enable_collisions link1="l0" link2="l2"/></robot>')
    tree = pinframes.read_urdf(urdf, srdf=srdf)
    (robot,) = semantic_robots(tree)
    # by hand: l1 with every other link but l5, and l3-l4
    expected = {frozenset(("l1", other)) for other in ("l0", "l2", "l3", "l4")}
    expected.add(frozenset(("l3", "l4")))
    names = [f"l{n}" for n in range(6)]
    found = {frozenset(pair) for pair in itertools.combinations(names, 2)
             if robot.semantics.disables(*pair)}
    assert found == expected
    assert robot.semantics.disabled_pair_count() == len(expected)


def test_a_group_or_state_defined_twice_is_named_in_the_warning(tmp_path):
    urdf = chain_urdf(tmp_path, 4)
    srdf = tmp_path / "twice.srdf"
    srdf.write_text('<robot name="chain"><group name="arm"><joint name="j1"/></group>'
                    '<group name="arm"><joint name="j2"/><joint name="j3"/></group>'
                    '<group_state name="home" group="arm"><joint name="j2" value="0.1"/>'
                    '</group_state><group_state name="home" group="arm">'
                    '<joint name="j2" value="0.2"/></group_state></robot>')
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tree = pinframes.read_urdf(urdf, srdf=srdf)
    (message,) = [str(w.message) for w in caught if issubclass(w.category, SrdfWarning)]
    assert str(srdf) in message
    assert "the 2 groups named 'arm'" in message and "the 2 group_states named 'home'" in message
    (robot,) = semantic_robots(tree)
    assert robot.semantics.groups["arm"] == ("j2", "j3")  # the last definition, as before
    assert robot.semantics.states["home"].values == {"j2": pytest.approx(0.2)}
