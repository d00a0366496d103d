"""`Memo`: what a tree version, or a path of it, has worked out once, kept by the kind of
thing and a key, so that each room reads back the type it stored."""

from __future__ import annotations

import contextlib
from collections.abc import Hashable
from typing import TypeVar

__all__ = ["Memo"]

T = TypeVar("T")

_LIMIT = 8192
"""Entries a memo keeps (the oldest goes first)."""


class Memo:
    """Values worked out once: ``memo.get(PreparedPath, key)`` is the ``PreparedPath``
    kept under ``key``, or None. At most ``_LIMIT`` entries: past it the oldest goes first."""

    __slots__ = ("_entries",)

    def __init__(self) -> None:
        self._entries: dict[tuple[type, Hashable], object] = {}

    def get(self, kind: type[T], key: Hashable) -> T | None:
        """The ``kind`` kept under ``key``, or None."""
        value = self._entries.get((kind, key))
        return value if isinstance(value, kind) else None

    def keep(self, kind: type[T], key: Hashable, value: T) -> T:
        """Keep ``value`` (a ``kind``) under ``key``; return it."""
        # Queries may run in several threads at once: two of them may pick the same oldest
        # entry, or one may insert while another iterates, so eviction tolerates both races
        # (the memo may then exceed its limit by a few entries) instead of taking a lock.
        if len(self._entries) >= _LIMIT:
            with contextlib.suppress(KeyError, RuntimeError, StopIteration):
                self._entries.pop(next(iter(self._entries)))
        self._entries[(kind, key)] = value
        return value
