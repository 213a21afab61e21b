# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The errors of vd_events: what a run, a bag, a domain, a command line or a log can refuse.

Each message names what it is about (configuration and event, bag path, file, line and
column). ``vd`` prints any of them as one line and exits 2 (:class:`Interrupted`: 130);
bad data files raise ``vd_data_server.errors.DataError``, of which :class:`InputError`
is the measured-data kind.
"""
from __future__ import annotations

from pathlib import Path

from vd_data_server.errors import DataError


class EventsError(Exception):
    """Base of the errors of vd_events."""


class RunError(EventsError):
    """A run could not start or did not finish (message names configuration and event)."""


class Interrupted(RunError):
    """Ctrl-C or SIGTERM during a run: what was written is removed, and the message says so."""


class BagError(EventsError):
    """The bag path cannot be used (exists, unwritable, not a bag)."""


class DomainError(EventsError):
    """No ROS domain could be claimed (message says which and why)."""


class UsageError(EventsError):
    """Bad command-line input (unknown event, model, configuration, bag path...)."""


class InputError(DataError):
    """Bad measured input: names the file, the line and the column where known."""

    def __init__(self, file: str | Path, message: str, *, line: int | None = None,
                 column: int | None = None, name: str | None = None) -> None:
        where = []
        if line is not None:
            where.append(f'line {line}')
        if column is not None:
            where.append(f'column {column}' + (f' {name!r}' if name else ''))
        elif name:
            where.append(f'column {name!r}')
        super().__init__(message, file=str(file), key=', '.join(where) or None)


__all__ = ['EventsError', 'RunError', 'Interrupted', 'BagError', 'DomainError', 'UsageError',
           'InputError', 'DataError']
