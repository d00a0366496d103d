"""Seeing a frame tree: robot geometry from URDFs and an animated 3-D page of a whole run."""

from ..errors import GeometryWarning
from ..kinematics.collision.mesh_files import PACKAGE_PATH_VARIABLE
from ._geometry import LinkGeometry, load_geometry
from ._page import MAX_PAGE_POSES, MAX_PAGE_SAMPLES, view_html, write_view

__all__ = ["MAX_PAGE_POSES", "MAX_PAGE_SAMPLES", "PACKAGE_PATH_VARIABLE", "GeometryWarning",
           "LinkGeometry", "load_geometry", "view_html", "write_view"]
