"""Text from files, shown on a terminal without acting on it.

Frame, joint and topic names come from the files read, and tf2 takes any name: an escape
sequence (``\\x1b[2J`` clears the screen), a NUL, a newline or a right-to-left override in
one would act on the terminal or forge lines of the output. Such characters are shown as
their escapes (``\\x1b``, ``\\x00``, ``\\n``, ``\\u202e``); every other character as it is.
"""

from __future__ import annotations

__all__ = ["printable"]


def printable(text: str) -> str:
    """``text`` with each character that does not print (``str.isprintable``) replaced by
    its Python escape."""
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else repr(char)[1:-1] for char in text)
