"""A weldx 0.2.3 file tags its units with the ASDF standard's unit tag, which asdf leaves to
asdf-astropy: pinframes reads the unit's text itself, so asdf's warning about the tag is not
the user's business (no ``pinframes: warning:`` line)."""

from __future__ import annotations

import warnings

import numpy as np

from pinframes import read_asdf

WELDX_0_2_3 = """\
#ASDF 1.0.0
#ASDF_STANDARD 1.5.0
%YAML 1.1
%TAG ! tag:stsci.edu:asdf/
%TAG !weldx! tag:weldx.bam.de:weldx/
--- !core/asdf-1.1.0
asdf_library: !core/software-1.0.0 {author: The ASDF Developers, homepage: 'http://github.com/asdf-format/asdf',
  name: asdf, version: 2.8.3}
history:
  extensions:
  - !core/extension_metadata-1.0.0 {extension_class: weldx.asdf.extension.WeldxExtension,
    software: !core/software-1.0.0 {name: weldx, version: 0.2.3}}
csm: !weldx!core/transformations/coordinate_system_hierarchy-1.0.0
  name: cell
  root_system_name: base
  subsystems: []
  coordinate_systems:
  - !weldx!core/transformations/coordinate_transformation-1.0.0
    name: table
    reference_system: base
    transformation: !weldx!core/transformations/local_coordinate_system-1.0.0
      coordinates: !weldx!core/variable-1.0.0
        name: coordinates
        dimensions: [c]
        dtype: <f8
        unit: !unit/unit-1.0.0 {unit}
        data: !core/ndarray-1.0.0
          data: [1.5, 0.0, 0.8]
          datatype: float64
          shape: [3]
...
"""


def test_a_unit_tag_of_weldx_0_2_3_is_read_without_a_warning(run_cli, tmp_path):
    path = tmp_path / "cell.asdf"
    path.write_text(WELDX_0_2_3.replace("{unit}", "m"))
    result = run_cli("pose", path, "table", "-r", "base")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    row = result.stdout.splitlines()[1].split(",")
    np.testing.assert_allclose([float(value) for value in row[1:4]], [1.5, 0.0, 0.8])


def test_the_tagged_unit_is_the_one_used(tmp_path):
    path = tmp_path / "cell.asdf"
    path.write_text(WELDX_0_2_3.replace("{unit}", "mm"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree = read_asdf(path)
    np.testing.assert_allclose(tree.pose("table", relative_to="base").translation,
                               [0.0015, 0.0, 0.0008])
