"""pinframes' weldx schemas: well-formed, complete, bound only inside ``bound_schemas``, and
accepting what weldx itself wrote (so that reading weldx's files can validate)."""

from __future__ import annotations

from pathlib import Path

import asdf
import asdf.schema
import pytest
import yaml

import pinframes
from conftest import SHARED_DATA
from pinframes.formats.asdf._decode import open_raw_tree
from pinframes.formats.asdf._extension import (
    EXTENSION_URI,
    MANIFEST,
    SCHEMA_FOLDER,
    bound_schemas,
    validate_hierarchy,
)

WELDX_FILES = SHARED_DATA / "weldx-files"
SAMPLES = ["static_tree.asdf", "absolute_time.asdf", "time_delta.asdf", "legacy_static.asdf",
           "legacy_time.asdf", "legacy_subsystems.asdf"]
MANIFEST_TAGS = yaml.safe_load(MANIFEST.read_text(encoding="utf-8"))["tags"]


def sample(name: str) -> Path:
    path = WELDX_FILES / name
    if not path.is_file():
        pytest.skip("shared sample data not present")
    return path


def validate_file(path: Path) -> None:
    """Check the hierarchy under ``csm`` in ``path`` against pinframes' schemas."""
    with open_raw_tree(path) as tree:
        validate_hierarchy(tree["csm"])


def test_every_schema_file_is_in_the_manifest_and_well_formed():
    files = {str(p.relative_to(SCHEMA_FOLDER / "weldx").with_suffix(""))
             for p in (SCHEMA_FOLDER / "weldx").rglob("*.yaml")}
    listed = {entry["schema_uri"].removeprefix("asdf://pinframes/schemas/weldx/")
              for entry in MANIFEST_TAGS}
    assert files == listed
    with bound_schemas():
        for entry in MANIFEST_TAGS:
            loaded = asdf.schema.load_schema(entry["schema_uri"])
            asdf.schema.check_schema(loaded)
            assert loaded["id"] == entry["schema_uri"]
            version = entry["tag_uri"].rsplit("-", 1)[1]
            assert entry["schema_uri"].endswith(version)


def test_the_schemas_are_bound_only_inside_the_block():
    assert EXTENSION_URI not in {e.extension_uri for e in asdf.get_config().extensions}
    with bound_schemas():
        assert EXTENSION_URI in {e.extension_uri for e in asdf.get_config().extensions}
    assert EXTENSION_URI not in {e.extension_uri for e in asdf.get_config().extensions}


@pytest.mark.parametrize("name", SAMPLES)
def test_weldx_written_files_validate(name):
    validate_file(sample(name))


@pytest.mark.filterwarnings("ignore::asdf.exceptions.AsdfBlockIndexWarning")  # edited text
@pytest.mark.parametrize(("name", "good", "bad", "frame", "field"), [
    ("static_tree.asdf", b"direction: fwd", b"direction: up", "fixture",
     "graph/root_node/edges/0/direction"),
    ("legacy_static.asdf", b"reference_system: fixture", b"reference_sys: fixture", "base",
     "coordinate_systems/0"),
    ("time_delta.asdf", b"dimensions: [time, c]\n", b"dimensions: [c, time]\n", "arm",
     "graph/root_node/edges/0/attributes/transformation/coordinates"),
])
def test_hierarchies_breaking_the_schemas_are_refused(tmp_path, name, good, bad, frame, field):
    text = sample(name).read_bytes()
    assert good in text
    broken = tmp_path / name
    broken.write_bytes(text.replace(good, bad, 1))
    with pytest.raises(pinframes.FileFormatError, match="breaks its weldx schema") as caught:
        validate_file(broken)
    assert (caught.value.frame, caught.value.field) == (frame, field)


@pytest.mark.filterwarnings("ignore::asdf.exceptions.AsdfBlockIndexWarning")
def test_read_asdf_checks_the_schemas_after_its_own_checks(tmp_path):
    text = sample("static_tree.asdf").read_bytes()
    broken = tmp_path / "defined.asdf"
    broken.write_bytes(text.replace(b"defined: true", b"defined: maybe", 1))
    with pytest.raises(pinframes.FileFormatError, match=r"defined.*'maybe' is not of type"):
        pinframes.read_asdf(broken)
