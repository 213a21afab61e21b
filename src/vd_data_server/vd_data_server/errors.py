# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Precise error types of the data side.

Every message names the file and the key (and the configuration where one is
involved) so that a user can go straight to the line that is wrong.
"""
from __future__ import annotations

from http import HTTPStatus

#: longest message of one problem (a quoted value can be a whole file), characters
MAX_MESSAGE = 500
#: most problems listed from one validation pass
MAX_ERRORS = 50


def _cut(text: str, limit: int = MAX_MESSAGE) -> str:
    if len(text) <= limit:
        return text
    return f'{text[:limit]}... (cut at the limit of {limit} characters)'


class DataError(Exception):
    """
    Invalid vehicle data, master file, override or tire property file.

    ``str(err)`` is one or more lines of the form ``file: key: message``.
    """

    def __init__(self, message: str, *, file: str | None = None, key: str | None = None) -> None:
        key = _cut(key, 200) if key else key
        message = _cut(message)
        self.file = file
        self.key = key
        self.detail = message
        parts = [p for p in (file, key) if p]
        super().__init__(': '.join([*parts, message]))


class DataErrors(DataError):
    """Several independent problems found in one validation pass."""

    def __init__(self, errors: list[DataError]) -> None:
        self.errors = list(errors)
        lines = [str(e) for e in self.errors[:MAX_ERRORS]]
        if len(self.errors) > MAX_ERRORS:
            lines.append(f'... and {len(self.errors) - MAX_ERRORS} more problems (the limit is '
                         f'{MAX_ERRORS} listed)')
        Exception.__init__(self, '\n'.join(lines))
        self.file = None
        self.key = None
        self.detail = str(self)


class WorkbenchError(Exception):
    """A request the workbench refuses: ``status`` and a message for the page."""

    def __init__(self, status: HTTPStatus, message: str) -> None:
        super().__init__(message)
        self.status = status
