"""The ``pinframes`` command line: ``pinframes SUBCOMMAND --help`` tells more.

Data goes to standard output, messages to standard error. A user error (a pinframes error
or a file that cannot be read or written) prints one line ``pinframes: error: ...`` and
exits with status 1 (``--verbose`` adds the traceback); bad arguments (a usage error) exit
with status 2. A warning prints one line ``pinframes: warning: ...``.
"""

from __future__ import annotations

import argparse
import os
import sys
import traceback
import warnings
from collections.abc import Sequence
from dataclasses import fields

from .. import __version__
from ..errors import PinframesError
from ..formats.limits import Limits, using_limits
from ..kinematics.collision.mesh_files import MODEL_PATH_VARIABLE, PACKAGE_PATH_VARIABLE
from . import batch, clearance, convert, demo, info, plot, pose, process, solve, transform, view
from ._files import xacro_argument

__all__ = ["main"]

_SUBCOMMANDS = (demo, info, pose, transform, process, solve, clearance, convert, plot, view,
                batch)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return the exit status."""
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        with using_limits(_limits(args)), warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.run(args)
    except BrokenPipeError:
        # the reader of our output went away (``pinframes pose ... | head``): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except (PinframesError, OSError) as exc:
        if args.verbose:
            traceback.print_exc()
        print(f"pinframes: error: {_one_line(exc)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("pinframes: interrupted", file=sys.stderr)
        return 130


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="pinframes",
        description="Coordinate-frame trees that move in time: inspect, query, convert, plot.",
        epilog="Run 'pinframes SUBCOMMAND --help' for the options of each subcommand.")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="print the traceback of an error (default: off)")
    parser.add_argument("--version", action="version", version=f"pinframes {__version__}")
    # accepted after the subcommand too; SUPPRESS keeps a --verbose given before it
    verbose = argparse.ArgumentParser(add_help=False)
    verbose.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                         help="print the traceback of an error (default: off)")
    for options, default in ((parser, None), (verbose, argparse.SUPPRESS)):
        _add_limit_options(options, default)
        options.add_argument("--robot-description", metavar="URDF", default=default,
                             help="for a ROS bag: the robot's URDF or xacro file, read with "
                             "--package-dir, --xacro-arg, --srdf and --xacro (default: the "
                             "last message on the bag's /robot_description)")
        _add_robot_file_options(options, default)
    subparsers = parser.add_subparsers(title="subcommands", metavar="SUBCOMMAND", required=True)
    for module in _SUBCOMMANDS:
        module.add_parser(subparsers, [verbose])
    return parser


def _add_limit_options(parser: argparse.ArgumentParser, default: object) -> None:
    """``--max-samples`` and the other bounds of :class:`pinframes.Limits`, for trusted
    files that need more than the defaults."""
    for item in fields(Limits):
        parser.add_argument("--" + item.name.replace("_", "-"), type=int, default=default,
                            metavar="N", help=f"raise the reader limit {item.name} "
                            f"(default {getattr(Limits(), item.name):,}; see README)")


def _add_robot_file_options(parser: argparse.ArgumentParser, default: object) -> None:
    """``--package-dir``, ``--xacro-arg``, ``--xacro`` and ``--srdf``: robots as ROS packages
    hold them."""
    parser.add_argument("--package-dir", action="append", default=default, metavar="DIR",
                        help="folder of ROS packages or Gazebo models (or one of them) for "
                        "$(find PKG) in xacro files and package:// and model:// meshes "
                        f"(repeatable; searched before {PACKAGE_PATH_VARIABLE}, "
                        f"{MODEL_PATH_VARIABLE} and the robot file's folders; default: none)")
    parser.add_argument("--xacro-arg", action="append", default=default, type=xacro_argument,
                        metavar="NAME:=VALUE", help="an argument of a xacro robot file "
                        "(repeatable; default: the file's own defaults)")
    parser.add_argument("--xacro", action="store_true", default=default,
                        help="expand xacro content of the robot file, its SRDF and a scene's "
                        "robots: expansion RUNS THE FILE'S CODE (xacro evaluates Python), so "
                        "give it only for files you trust (default: only a file named "
                        "*.xacro given on the command line is expanded; a scene's robot "
                        "entry needs 'xacro: true'); it runs in a child process bounded by "
                        "--max-xacro-seconds and --max-xacro-bytes, without environment "
                        "variables")
    parser.add_argument("--srdf", metavar="SRDF", default=default,
                        help="the SRDF of a URDF or xacro robot file: its disabled collision "
                        "pairs are left out of clearance, its groups and group states name "
                        "joints and seeds (default: none)")


def _limits(args: argparse.Namespace) -> Limits | None:
    given = {item.name: getattr(args, item.name) for item in fields(Limits)
             if getattr(args, item.name, None) is not None}
    return Limits(**given) if given else None


def _show_warning(message: Warning | str, category: type[Warning], filename: str,
                  lineno: int, file: object = None, line: str | None = None) -> None:
    """A warning as one line on standard error, without the source location."""
    print(f"pinframes: warning: {' '.join(str(message).split())}", file=sys.stderr)


def _one_line(exc: BaseException) -> str:
    if isinstance(exc, OSError) and not isinstance(exc, PinframesError) and exc.strerror:
        text = f"{exc.filename}: {exc.strerror}" if exc.filename else exc.strerror
    else:
        text = str(exc)
    return " ".join(text.split())
