"""What the URDF reader's limits cost on real robots, and how fast hostile URDFs are refused.

(a) The largest URDFs of example-robot-data: parsing under the limits (elements counted and
nesting measured as expat produces them) beside ``xml.etree.ElementTree.fromstring`` of the
same text, timed in alternating rounds (the ratio is the median of per-round ratios), and
the whole ``read_urdf``. (b) Hostile files generated here: the time until the pinframes
error, beside what a plain ``fromstring`` of the same text costs. Run from the repository
root: ``python benchmarks/bench_urdf_limits.py``.
"""

from __future__ import annotations

import statistics
import tempfile
import time
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Callable
from importlib import metadata
from pathlib import Path

from _machine import describe_machine
from pinframes import read_urdf
from pinframes.errors import PinframesError
from pinframes.formats.urdf._bounded_xml import parse_bounded_xml

ROUNDS = 15


def _robots() -> list[Path]:
    """The three largest URDFs of example-robot-data, and the UR5."""
    for file in metadata.files("example-robot-data") or []:
        if file.name == "ur5_robot.urdf":
            ur5 = Path(file.locate())
            break
    else:
        raise SystemExit("example-robot-data is not installed (pip install '.[test]')")
    files = sorted(ur5.parents[2].glob("**/*.urdf"), key=lambda path: path.stat().st_size)
    return [*files[-3:], ur5]


def _seconds(call: Callable[..., object], *args: object) -> float:
    start = time.perf_counter()
    try:
        call(*args)
    except (PinframesError, ET.ParseError):
        pass
    return time.perf_counter() - start


def real_robots() -> None:
    print(f"{'robot':<28} {'elements':>8} {'fromstring ms':>14} {'bounded ms':>11} "
          f"{'ratio':>6} {'read_urdf ms':>13}")
    for path in _robots():
        text = path.read_text(encoding="utf-8")
        plain, bounded, whole, ratios = [], [], [], []
        for _ in range(ROUNDS):
            plain.append(_seconds(ET.fromstring, text))
            bounded.append(_seconds(parse_bounded_xml, text, str(path)))
            whole.append(_seconds(read_urdf, path))
            ratios.append(bounded[-1] / plain[-1])
        elements = sum(1 for _ in ET.fromstring(text).iter())
        print(f"{path.name:<28} {elements:>8,} {statistics.median(plain) * 1e3:>14.2f} "
              f"{statistics.median(bounded) * 1e3:>11.2f} {statistics.median(ratios):>6.2f} "
              f"{statistics.median(whole) * 1e3:>13.2f}")


def _entity_bomb() -> str:
    entities = ['<!ENTITY e0 "' + "<a/>" * 8 + '">'] + [
        f'<!ENTITY e{level} "{f"&e{level - 1};" * 8}">' for level in range(1, 7)]
    return (f"<!DOCTYPE robot [{''.join(entities)}]><robot name='r'><link name='l'>&e6;"
            "</link></robot>")


def _robot(inner: str) -> str:
    return f"<robot name='r'><link name='l'>{inner}</link></robot>"


def hostile_files() -> None:
    cases = {
        "entity bomb (8**7 elements)": _entity_bomb(),
        "1,000,000 levels deep": _robot("<a>" * 1_000_000 + "</a>" * 1_000_000),
        "1,200,000 elements": _robot("<a/>" * 1_200_000),
    }
    print(f"\n{'hostile file':<28} {'bytes':>10} {'refused in s':>13} {'fromstring s':>13}")
    with tempfile.TemporaryDirectory() as folder:
        for name, text in cases.items():
            path = Path(folder) / "robot.urdf"
            path.write_text(text, encoding="utf-8")
            refused = statistics.median(_seconds(read_urdf, path) for _ in range(3))
            plain = statistics.median(_seconds(ET.fromstring, text) for _ in range(3))
            print(f"{name:<28} {len(text):>10,} {refused:>13.3f} {plain:>13.3f}")


def main() -> None:
    print(describe_machine())
    warnings.simplefilter("ignore")  # robots without joint samples, unnamed robots
    real_robots()
    hostile_files()


if __name__ == "__main__":
    main()
