"""Precise error types of the data side.

Every message names the file and the key (and the configuration where one is
involved) so that a user can go straight to the line that is wrong.
"""
from __future__ import annotations


class DataError(Exception):
    """Invalid vehicle data, master file, override or tire property file.

    ``str(err)`` is one or more lines of the form ``file: key: message``.
    """

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None) -> None:
        self.file = file
        self.key = key
        self.detail = message
        parts = [p for p in (file, key) if p]
        super().__init__(": ".join([*parts, message]))


class DataErrors(DataError):
    """Several independent problems found in one validation pass."""

    def __init__(self, errors: list[DataError]) -> None:
        self.errors = list(errors)
        Exception.__init__(self, "\n".join(str(e) for e in self.errors))
        self.file = None
        self.key = None
        self.detail = str(self)
