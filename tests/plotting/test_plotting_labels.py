"""Frame names in the matplotlib plots: short, and never printed over each other.

Overlap is judged on the labels matplotlib actually drew (their rendered extents), on the
bundled cell and on Duckietown maps with dozens of tiles.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from conftest import SHARED_DATA
from pinframes import read_frames_yaml, read_scene
from pinframes.cli import main

pytest.importorskip("matplotlib")
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text
from mpl_toolkits.mplot3d import proj3d

from pinframes.plotting import new_figure, plot_frames

MAPS = sorted((SHARED_DATA / "duckietown-maps").glob("*/frames.yaml"))
CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell" / "scene.yaml"


def drawn_labels(tree):
    figure = new_figure()
    ax = figure.add_subplot(projection="3d")
    plot_frames(tree, ax=ax)
    canvas = FigureCanvasAgg(figure)
    canvas.draw()
    renderer = canvas.get_renderer()
    labels = []
    for text in ax.texts:  # a 3-D text has its screen place only while drawn: redo that here
        x, y, _ = proj3d.proj_transform(*text.get_position_3d(), ax.get_proj())
        flat = Text(x, y, text.get_text(), fontsize=text.get_fontsize(),
                    verticalalignment=text.get_verticalalignment(),
                    horizontalalignment=text.get_horizontalalignment(),
                    transform=ax.transData, figure=figure)
        labels.append((text.get_text().strip(), flat.get_window_extent(renderer)))
    return labels


def assert_apart(labels) -> None:
    for (a, box_a), (b, box_b) in itertools.combinations(labels, 2):
        width = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
        height = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
        assert width <= 0 or height <= 0, f"{a!r} overlaps {b!r}"


@pytest.mark.skipif(not MAPS, reason="the Duckietown maps are not in shared/data")
@pytest.mark.parametrize("path", MAPS[:4], ids=lambda p: p.parent.name)
def test_duckietown_map_labels_are_short_and_apart(path):
    tree = read_frames_yaml(path)
    labels = drawn_labels(tree)
    assert labels and all("/" not in text for text, _ in labels)  # map_1/tile_0_7 -> tile_0_7
    assert_apart(labels)


def test_bundled_cell_labels_are_apart():
    labels = drawn_labels(read_scene(CELL))
    assert any(text.startswith("world") for text, _ in labels)
    assert_apart(labels)


@pytest.mark.skipif(not MAPS, reason="the Duckietown maps are not in shared/data")
def test_plot_title_names_the_file_not_its_whole_path(tmp_path, monkeypatch):
    captured = {}
    import pinframes.cli.plot as plot_command

    original = plot_command.save_figure

    def keep(figure, path):
        captured["title"] = figure.axes[0].get_title()
        original(figure, path)

    monkeypatch.setattr(plot_command, "save_figure", keep)
    assert main(["plot", str(MAPS[0]), "-o", str(tmp_path / "map.png")]) == 0
    assert captured["title"].startswith(f"{MAPS[0].parent.name}/frames.yaml: frames in world")
    assert str(SHARED_DATA) not in captured["title"]
