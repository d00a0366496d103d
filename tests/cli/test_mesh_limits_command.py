"""``--max-triangles``: the command line's bound on a mesh file's triangles after instancing."""

from __future__ import annotations

from meshes import nested_instances_dae


def one_link(name: str, geometry: str) -> str:
    return (f'<robot name="{name}"><link name="{name}"><collision><geometry>{geometry}'
            '</geometry></collision></link></robot>')


def test_the_command_line_takes_max_triangles(tmp_path, run_cli):
    (tmp_path / "nested.dae").write_text(nested_instances_dae(11))  # 2,048 triangles
    (tmp_path / "bomb.urdf").write_text(one_link(
        "bomb", f'<mesh filename="{tmp_path / "nested.dae"}"/>'))
    (tmp_path / "ball.urdf").write_text(one_link("ball", '<sphere radius="0.1"/>'))
    scene = tmp_path / "cell.yaml"
    scene.write_text("pinframes_scene: 1\nframes:\n  - {name: at, parent: world, xyz: [0, 0, -1]}"
                     "\nrobots:\n  - {name: bomb, urdf: bomb.urdf, parent: world}\n"
                     "  - {name: ball, urdf: ball.urdf, parent: at}\n")
    refused = run_cli("clearance", scene, "bomb", "ball", "--max-triangles", "2000")
    assert refused.returncode != 0
    assert "bomb" in refused.stderr and "--max-triangles" in refused.stderr
    measured = run_cli("clearance", scene, "bomb", "ball", "--max-triangles", "2048")
    assert measured.returncode == 0, measured.stderr
