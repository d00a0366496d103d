"""Generate a campaign of recorded runs of the bundled welding cell (for pinframes batch).

Run from the repository root::

    PYTHONPATH=src python models/welding_cell/make_campaign.py --runs 200 --samples 10000 \\
        --out /tmp/campaign

Each run is a folder ``run_NNNN`` holding ``scene.yaml`` (the bundled ``scene.yaml`` with
its own reference time, one minute after the previous run's) and ``motion.csv``: the
bundled weld motion resampled to ``--samples`` joint samples over its 20 s, each joint
offset by a small sine of its own amplitude (up to 0.05 rad), frequency and phase, drawn
from ``--seed``. The same arguments give the same files.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import yaml

from pinframes import read_joint_trajectory

HERE = Path(__file__).resolve().parent
START = np.datetime64("2024-03-01T08:00:00", "s")


def make_campaign(out: Path, runs: int, samples: int, seed: int = 0) -> list[Path]:
    """Write ``runs`` run folders into ``out``; return their scene files."""
    scene = yaml.safe_load((HERE / "scene.yaml").read_text(encoding="utf-8"))
    for robot in scene["robots"]:  # the welding robot, and the cell's geometry
        robot["urdf"] = str((HERE / robot["urdf"]).resolve())
    scene["robots"][0]["trajectory"] = "motion.csv"
    times, positions, names = read_joint_trajectory(HERE / "robot_motion.csv")
    seconds = np.asarray(times, dtype=float)  # time_s column: seconds
    grid = np.linspace(seconds[0], seconds[-1], samples)
    base = np.column_stack([np.interp(grid, seconds, column) for column in positions.T])
    rng = np.random.default_rng(seed)
    scenes = []
    for index in range(runs):
        folder = out / f"run_{index:04d}"
        folder.mkdir(parents=True, exist_ok=True)
        amplitude, frequency, phase = (rng.uniform(0.0, 0.05, len(names)),
                                       rng.uniform(0.05, 0.5, len(names)),
                                       rng.uniform(0.0, 2 * np.pi, len(names)))
        motion = base + amplitude * np.sin(2 * np.pi * frequency * grid[:, None] + phase)
        table = np.column_stack([grid, motion])
        np.savetxt(folder / "motion.csv", table, delimiter=",", fmt="%.12g",
                   header="time_s," + ",".join(names), comments="")
        scene["reference_time"] = str(START + np.timedelta64(60 * index, "s"))
        (folder / "scene.yaml").write_text(yaml.safe_dump(scene, sort_keys=False),
                                           encoding="utf-8")
        scenes.append(folder / "scene.yaml")
    return scenes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True, help="folder to write the runs in")
    parser.add_argument("--runs", type=int, default=200, help="number of runs")
    parser.add_argument("--samples", type=int, default=10_000, help="joint samples per run")
    parser.add_argument("--seed", type=int, default=0, help="seed of the variations")
    args = parser.parse_args()
    make_campaign(args.out, args.runs, args.samples, args.seed)


if __name__ == "__main__":
    main()
