"""``pinframes process``: the welding process of a hand-built plate seam and of the bundled
cell, as CSV, with its summary line and errors."""

import io
import textwrap

import numpy as np
import pandas

from pinframes.cli.demo import bundled_scene

HEADER = ("time_s,travel_speed_m_s,travel_angle_deg,work_angle_deg,offset_along_m,"
          "offset_across_m,offset_normal_m,slope_deg,rotation_deg,position")

PLATE = """\
    pinframes_scene: 1
    frames:
      - {name: plate, parent: world, xyz: [1.0, 0.0, 0.0]}
      - name: seam                       # 0.2 m straight along the plate's x, 10 mm/s
        parent: plate
        curve: {points: [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]], normals: [0, 0, 1], speed: 0.01}
      - name: torch                      # 1 mm beside and 12 mm above the seam, 10 deg push
        parent: world
        rpy: [0, 2.9670597283903604, 0]
        keyframes:
          - {time: 0, xyz: [1.0, 0.001, 0.012]}
          - {time: 20, xyz: [1.2, 0.001, 0.012]}
    tools:
      - {name: contact_tip, parent: torch, xyz: [0, 0, -0.015]}
    """


def plate_scene(tmp_path):
    path = tmp_path / "plate.yaml"
    path.write_text(textwrap.dedent(PLATE))
    return path


def read_process(text, header=HEADER):
    """The numeric columns, and the positions."""
    assert text.splitlines()[0] == header
    frame = pandas.read_csv(io.StringIO(text))
    return frame.drop(columns="position").to_numpy(dtype=float), frame["position"].tolist()


def test_plate_seam_by_hand(run_cli, tmp_path):
    """The torch keeps pace with the seam point: 10 mm/s, 10 degrees push (Ry(170 deg) turns
    z to (sin 10, 0, -cos 10)), square across; the wire meets the plate 12 mm / cos 10 deg
    below the tip, 15 mm more from the contact tip."""
    result = run_cli("process", plate_scene(tmp_path), "--torch", "torch", "--seam", "seam",
                     "--contact-tip", "contact_tip")
    assert result.returncode == 0, result.stderr
    rows, positions = read_process(result.stdout, HEADER + ",ctwd_m")
    np.testing.assert_allclose(rows[:, 0], [0.0, 10.0, 20.0])
    # a flat plate: slope 0, face up (rotation 0), flat position PA
    expected = [0.01, 10.0, 90.0, 0.0, 0.001, 0.012, 0.0, 0.0,
                0.012 / np.cos(np.radians(10)) + 0.015]
    np.testing.assert_allclose(rows[:, 1:], [expected] * 3, atol=1e-12)
    assert positions == ["PA"] * 3
    summary = result.stderr.splitlines()[0]
    assert summary == ("pinframes: torch along seam: 3 samples; travel speed 10.00 .. 10.00 mm/s; "
                       "travel angle 10.00 .. 10.00 deg; work angle 90.00 .. 90.00 deg; "
                       "offset along 0.000 .. 0.000 mm; offset across 1.000 .. 1.000 mm; "
                       "offset normal 12.000 .. 12.000 mm; slope 0.00 .. 0.00 deg; "
                       "rotation 0.00 .. 0.00 deg; ctwd 27.19 .. 27.19 mm; positions PA 3 of 3")


def test_up_turns_the_plate_overhead(run_cli, tmp_path):
    """With up along -z of the world the plate's face looks down: rotation 180, PE."""
    result = run_cli("process", plate_scene(tmp_path), "--torch", "torch", "--seam", "seam",
                     "--up", "0", "0", "-1")
    assert result.returncode == 0, result.stderr
    rows, positions = read_process(result.stdout)
    np.testing.assert_allclose(np.abs(rows[:, 8]), 180.0, atol=1e-12)
    assert positions == ["PE"] * 3 and "positions PE 3 of 3" in result.stderr
    for up in (["0", "0", "0"], ["0", "nan", "1"]):
        result = run_cli("process", plate_scene(tmp_path), "--torch", "torch", "--seam", "seam",
                         "--up", *up)
        assert result.returncode == 1 and "field '--up'" in result.stderr


def test_grid_to_a_file_and_the_workpiece_option(run_cli, tmp_path):
    out = tmp_path / "process.csv"
    result = run_cli("process", plate_scene(tmp_path), "--torch", "torch", "--seam", "seam",
                     "--workpiece", "world", "--start", "5", "--stop", "6", "--step", "250ms",
                     "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    rows, _ = read_process(out.read_text())
    np.testing.assert_allclose(rows[:, 0], [5.0, 5.25, 5.5, 5.75, 6.0])
    np.testing.assert_allclose(rows[:, 1], 0.01, atol=1e-12)  # the plate does not move
    assert "5 samples" in result.stderr


def test_bundled_cell(run_cli):
    """The design: 10 degrees push, 90 degrees work, pi * 0.10955 m / 20 s = 17.2 mm/s."""
    result = run_cli("process", bundled_scene(), "--torch", "torch_tcp", "--seam", "seam_point",
                     "--workpiece", "workpiece")
    assert result.returncode == 0, result.stderr
    rows, positions = read_process(result.stdout)
    assert rows.shape == (2001, 9)
    np.testing.assert_allclose(rows[:, 1], np.pi * 0.10955 / 20, rtol=1e-3)
    np.testing.assert_allclose(rows[:, 2], 10.0, atol=1e-4)
    np.testing.assert_allclose(rows[:, 3], 90.0, atol=1e-4)
    assert "travel speed 17.2" in result.stderr and "work angle 90.00 .. 90.00 deg" in result.stderr
    # the positioner keeps the weld point on top of the pipe: flat all along
    assert positions == ["PA"] * 2001 and "positions PA 2001 of 2001" in result.stderr


def test_a_static_torch_gives_one_row_without_a_time(run_cli, tmp_path):
    path = tmp_path / "static.yaml"
    path.write_text("pinframes_scene: 1\nframes:\n- {name: seam, parent: world}\n"
                    "- {name: torch, parent: seam, xyz: [0, 0, 0.01], rpy: [3.14159, 0, 0]}\n")
    result = run_cli("process", path, "--torch", "torch", "--seam", "seam")
    assert result.returncode == 0, result.stderr
    rows, positions = read_process(result.stdout)
    assert rows.shape == (1, 9) and np.isnan(rows[0, 0]) and rows[0, 1] == 0.0
    assert positions == ["PA"]


def test_errors_name_the_file_and_frame(run_cli, tmp_path):
    path = plate_scene(tmp_path)
    result = run_cli("process", path, "--torch", "torhc", "--seam", "seam")
    assert result.returncode == 1
    assert result.stderr.startswith(f"pinframes: error: {path}: frame 'torhc'")
    assert "did you mean" in result.stderr
    result = run_cli("process", path, "--seam", "seam")
    assert result.returncode == 2 and "--torch" in result.stderr
    out = tmp_path / "never.csv"
    result = run_cli("process", path, "--torch", "torch", "--seam", "seam", "--times", "x",
                     "-o", out)
    assert result.returncode == 1 and not out.exists()
