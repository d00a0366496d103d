"""The chain case in weldx's CoordinateSystemManager, timed by itself (median of repeats).

Run by bench_queries.py with the interpreter named by ``PINFRAMES_WELDX_PYTHON`` (weldx needs
``asdf<6``, so it lives in a venv of its own):
``python _weldx_chain.py INPUT.npz OUTPUT.npz REPEATS``. INPUT holds ``edge{i}_matrix`` for a
static edge or ``edge{i}_times/_translations/_quaternions`` for a moving one (seconds, metres,
x y z w), and ``query_times``; OUTPUT gets the (N, 4, 4) result and the median in seconds.
"""

import statistics
import sys
import time

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation
from weldx import Q_, CoordinateSystemManager, LocalCoordinateSystem, Time


def main() -> None:
    source, target, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3])
    data = np.load(source)
    csm = CoordinateSystemManager("world")
    parent, index = "world", 0
    while f"edge{index}_matrix" in data or f"edge{index}_times" in data:
        name = f"f{index}"
        if f"edge{index}_matrix" in data:
            matrix = data[f"edge{index}_matrix"]
            lcs = LocalCoordinateSystem(orientation=matrix[:3, :3],
                                        coordinates=Q_(matrix[:3, 3], "m"))
        else:
            lcs = LocalCoordinateSystem(
                orientation=Rotation.from_quat(data[f"edge{index}_quaternions"]).as_matrix(),
                coordinates=Q_(data[f"edge{index}_translations"], "m"),
                time=Time(pd.to_timedelta(data[f"edge{index}_times"], unit="s")))
        csm.add_cs(name, parent, lcs)
        parent, index = name, index + 1
    query = Time(pd.to_timedelta(data["query_times"], unit="s"))

    def run():
        return csm.get_cs(parent, "world", time=query)

    run()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = run()
        samples.append(time.perf_counter() - start)
    out = np.zeros((len(data["query_times"]), 4, 4))
    out[:, :3, :3] = np.asarray(result.orientation.data)
    out[:, :3, 3] = result.coordinates.data.to("m").magnitude
    out[:, 3, 3] = 1.0
    np.savez(target, matrix=out, seconds=statistics.median(samples))


if __name__ == "__main__":
    main()
