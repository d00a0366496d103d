"""pinframes' weldx schemas: well-formed, complete, bound only inside ``bound_schemas``, and
accepting what weldx itself wrote (so that reading weldx's files can validate)."""

from __future__ import annotations

import warnings
from pathlib import Path

import asdf
import asdf.schema
import pytest
import yaml

from conftest import SHARED_DATA
from pinframes.asdf._extension import EXTENSION_URI, MANIFEST, SCHEMA_FOLDER, bound_schemas

WELDX_FILES = SHARED_DATA / "weldx-files"
SAMPLES = ["static_tree.asdf", "absolute_time.asdf", "time_delta.asdf", "legacy_static.asdf",
           "legacy_time.asdf", "legacy_subsystems.asdf"]
MANIFEST_TAGS = yaml.safe_load(MANIFEST.read_text(encoding="utf-8"))["tags"]


def sample(name: str) -> Path:
    path = WELDX_FILES / name
    if not path.is_file():
        pytest.skip("shared sample data not present")
    return path


def open_validated(path: Path) -> None:
    """Open ``path`` with pinframes' schemas bound (validation on read)."""
    with bound_schemas(), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # tags without converters here, weldx not installed
        with asdf.open(path, lazy_load=False, memmap=False):
            pass


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
        assert asdf.get_config().validate_on_read
    assert EXTENSION_URI not in {e.extension_uri for e in asdf.get_config().extensions}


@pytest.mark.parametrize("name", SAMPLES)
def test_weldx_written_files_validate(name):
    open_validated(sample(name))


@pytest.mark.parametrize(("name", "good", "bad"), [
    ("static_tree.asdf", b"direction: fwd", b"direction: up"),
    ("legacy_static.asdf", b"reference_system: fixture", b"reference_sys: fixture"),
    ("time_delta.asdf", b"dimensions: [time, c]", b"dimensions: [c, time]"),
])
def test_files_breaking_the_schemas_are_refused_on_read(tmp_path, name, good, bad):
    text = sample(name).read_bytes()
    assert good in text
    broken = tmp_path / name
    broken.write_bytes(text.replace(good, bad, 1))
    with pytest.raises(asdf.ValidationError):
        open_validated(broken)
