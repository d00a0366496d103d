"""What every subcommand's parser starts with: its name, help and description among the
others, the options every command takes (``parents``), the tree file it reads and the
function that runs it."""

from __future__ import annotations

import argparse
from collections.abc import Callable

__all__ = ["Subparsers", "subcommand_parser"]

Subparsers = argparse._SubParsersAction
"""What ``argparse.ArgumentParser.add_subparsers`` returns."""

TREE_FILE_HELP = "scene, frames.yaml, ASDF or URDF file"


def subcommand_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser],
                      name: str, run: Callable[[argparse.Namespace], int], *, help: str,
                      description: str, tree_file: str | None = "FILE",
                      ) -> argparse.ArgumentParser:
    """The parser of subcommand ``name``, which ``run`` carries out: with the options of
    ``parents`` and, unless ``tree_file`` is None, the positional ``file`` (shown as
    ``tree_file``) that it reads a tree from."""
    parser = subparsers.add_parser(name, parents=parents, help=help, description=description)
    if tree_file is not None:
        parser.add_argument("file", metavar=tree_file, help=TREE_FILE_HELP)
    parser.set_defaults(run=run)
    return parser
