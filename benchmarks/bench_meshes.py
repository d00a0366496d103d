"""Reading real robot meshes: pinframes' one mesh reader beside coal's loader (assimp).

Cases: the KUKA files in tests/data/kuka_experimental (Apache-2.0): the KR210 L150's visual
base (COLLADA in inches, 2,631 triangles), the LBR iiwa 14's visual base (COLLADA that goes
on after ``</COLLADA>``, 18,470 triangles), the KR210's seven collision STLs; and a COLLADA
file of 3 kB whose nodes instance each other 2**16 times (65,536 triangles), which pinframes
refuses under ``max_triangles=50_000`` before building anything and assimp builds, and
reads under the default bound (each node visited once, its instances placed with numpy).

The reference is ``coal.MeshLoader().load`` (assimp), what ``pinocchio.buildGeomFromUrdf``
reads meshes with; it shares no code with pinframes' COLLADA path. ``max|diff|`` is the
largest difference of the two bounding boxes, metres (the COLLADA unit applied to assimp's
vertices by hand; assimp leaves it out). pinframes' STL path *is* assimp (the same loader,
the triangles copied out): its ratio is the cost of that copy. Both thread settings, each in
a child process (see ``_machine.py``).

Run: ``python benchmarks/bench_meshes.py [--quick]``.
"""

from __future__ import annotations

import json
import lzma
import sys
import tempfile
from pathlib import Path

import coal
import numpy as np

from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings
from pinframes.errors import GeometryError
from pinframes.kinematics.collision.mesh_reader import read_mesh

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "kuka_experimental"
sys.path.insert(0, str(DATA.parents[1]))
from meshes import nested_instances_dae  # noqa: E402  (tests/meshes.py: the test's file)

REFERENCE = "assimp (coal's loader)"


def unpacked(name: str, folder: Path) -> Path:
    target = folder / name  # both robots' files are called base_link.dae
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_bytes(lzma.decompress((DATA / (name + ".xz")).read_bytes()))
    return target


def bounding_box_difference(path: Path, unit: float) -> float:
    """Largest difference between our box and assimp's box times the file's unit."""
    ours, _ = read_mesh(path).merged()
    theirs = np.asarray(coal.MeshLoader().load(str(path), np.ones(3)).vertices()) * unit
    return float(max(np.abs(ours.min(axis=0) - theirs.min(axis=0)).max(),
                     np.abs(ours.max(axis=0) - theirs.max(axis=0)).max()))


def child(quick: bool) -> None:
    rounds = 5 if quick else 25
    folder = Path(tempfile.mkdtemp())
    kr210 = unpacked("kuka_kr210_support/meshes/kr210l150/visual/base_link.dae", folder)
    iiwa = unpacked("kuka_lbr_iiwa_support/meshes/lbr_iiwa_14_r820/visual/base_link.dae",
                    folder)
    stls = sorted((DATA / "kuka_kr210_support/meshes/kr210l150/collision").glob("*.stl"))
    nested = folder / "nested.dae"
    nested.write_text(nested_instances_dae(16))

    def assimp(*paths: Path):
        return lambda: [coal.MeshLoader().load(str(path), np.ones(3)) for path in paths]

    def refused() -> None:
        try:
            read_mesh(nested, max_triangles=50_000)
        except GeometryError:
            return
        raise AssertionError("the nested file was read")

    rows = []
    for case, ours, theirs, error in (
            ("KR210 visual base (DAE, inches)", lambda: read_mesh(kr210), assimp(kr210),
             bounding_box_difference(kr210, 0.0254)),
            ("iiwa visual base (DAE, trailing bytes)", lambda: read_mesh(iiwa), assimp(iiwa),
             bounding_box_difference(iiwa, 1.0)),
            ("KR210 collision, 7 STL files", lambda: [read_mesh(p) for p in stls],
             assimp(*stls), max(bounding_box_difference(p, 1.0) for p in stls)),
            ("nested instances, 65,536 triangles", refused, assimp(nested), None),
            ("nested instances, 65,536 triangles, read", lambda: read_mesh(nested),
             assimp(nested), bounding_box_difference(nested, 1.0))):
        measured = interleaved(case, {"pinframes read_mesh": ours, REFERENCE: theirs}, rounds,
                               reference=REFERENCE)
        for entry in measured:
            entry["error"] = error if entry["method"] != REFERENCE else None
            if case.endswith("triangles") and entry["method"] != REFERENCE:
                entry["note"] = "refused: max_triangles=50,000"
        rows += measured
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "5 rounds instead of 25")
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference=REFERENCE)


if __name__ == "__main__":
    main()
