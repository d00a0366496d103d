"""A temporary asdf configuration that leaves asdf's own one (and weldx) intact."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

__all__ = ["temporary_asdf_config"]


@contextlib.contextmanager
def temporary_asdf_config() -> Iterator[Any]:  # -> asdf.config.AsdfConfig
    """``asdf.config_context()``, entered only after asdf's own configuration has loaded the
    installed plugins.

    weldx 0.8.2's plugin hands out its converters only the first time it is loaded
    (measured): loaded first inside a temporary configuration, they would vanish with it,
    and weldx would read its own files as raw data for the rest of the process.
    """
    import asdf

    config = asdf.get_config()
    config.extensions  # noqa: B018  (loads the plugins)
    config.resource_manager  # noqa: B018
    with asdf.config_context() as temporary:
        yield temporary
