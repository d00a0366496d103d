"""Real robot packages in tests/data, and the ``xacro`` command run as ROS runs it.

The reference expansion is the ``xacro`` package's own command line, in a child process.
ROS 2's xacro answers ``$(find PKG)`` from the ament index (``ament_index_python``, which is
not on the package index), so the child gets a stand-in ``ament_index_python`` that maps the
package names to the folders given here, as an ament install's share folders would.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data"
UR_DESCRIPTION = DATA / "ur_description"
UR_XACRO = UR_DESCRIPTION / "urdf" / "ur.urdf.xacro"
MOTOMAN = DATA / "motoman"
MA2010_XACRO = MOTOMAN / "motoman_ma2010_support" / "urdf" / "ma2010.xacro"
MA2010_SRDF = MOTOMAN / "motoman_ma2010_moveit_config" / "config" / "motoman_ma2010.srdf"
D500_XACRO = MOTOMAN / "motoman_motopos_d500_support" / "urdf" / "motopos_d500.xacro"
CELL = DATA / "ma2010_cell"

_AMENT_STAND_IN = textwrap.dedent('''
    import json, os

    class PackageNotFoundError(KeyError):
        pass

    def get_package_share_directory(package_name, print_warning=True):
        shares = json.loads(os.environ["TEST_AMENT_SHARES"])
        if package_name not in shares:
            raise PackageNotFoundError(package_name)
        return shares[package_name]
''')


def packages_below(folder: Path) -> dict[str, str]:
    """Package name -> folder, for every ``package.xml`` below ``folder``."""
    return {manifest.parent.name: str(manifest.parent)
            for manifest in folder.rglob("package.xml")}


def xacro_command(path: Path, arguments: dict[str, str], packages: dict[str, str],
                  scratch: Path) -> str:
    """What ``xacro PATH NAME:=VALUE ...`` prints, ``$(find)`` answered from ``packages``."""
    stand_in = scratch / "ament_index_python"
    stand_in.mkdir(parents=True, exist_ok=True)
    (stand_in / "__init__.py").write_text("")
    (stand_in / "packages.py").write_text(_AMENT_STAND_IN)
    environment = dict(os.environ, PYTHONPATH=str(scratch),
                       TEST_AMENT_SHARES=json.dumps(packages))
    command = [sys.executable, "-c", "import sys, xacro; sys.argv[0] = 'xacro'; xacro.main()",
               str(path), *(f"{name}:={value}" for name, value in arguments.items())]
    finished = subprocess.run(command, capture_output=True, text=True, env=environment,
                              check=False, timeout=120)
    assert finished.returncode == 0, finished.stderr
    return finished.stdout
