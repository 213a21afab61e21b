# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The files a load read, with the hash of the bytes it read: what a cached study depends on.

Every reader of user data (``yamlio.read_bytes``, ``tir.read_tir``, the reduced-stiffness
files of ``master``) calls :func:`note_read` with the bytes it got. Inside
:func:`recording`, those land in a :class:`Reads`; outside, noting costs nothing. The hash is
of the bytes the load used, not of the file read again later, so a file edited during a load
cannot pass for the one that was read.
"""
from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
import hashlib
import os
from pathlib import Path


def digest(data: bytes) -> str:
    """Return the hash a read is known by (SHA-256, hex)."""
    return hashlib.sha256(data).hexdigest()


@dataclass
class Reads:
    """
    Absolute path -> hash of the bytes read.

    ``consistent`` is False if a file read twice gave different bytes (it changed during
    the load).
    """

    files: dict[str, str] = field(default_factory=dict)
    consistent: bool = True

    def note(self, path: Path | str, data: bytes) -> None:
        key, value = os.path.abspath(path), digest(data)
        if self.files.setdefault(key, value) != value:
            self.consistent = False


_current: ContextVar[Reads | None] = ContextVar('vd_reads', default=None)


def note_read(path: Path | str, data: bytes) -> None:
    """Tell the recording in progress (if any) that ``path`` was read as ``data``."""
    reads = _current.get()
    if reads is not None:
        reads.note(path, data)


@contextmanager
def recording() -> Iterator[Reads]:
    """Record the files read inside the block (this thread / task only)."""
    reads = Reads()
    token = _current.set(reads)
    try:
        yield reads
    finally:
        _current.reset(token)


__all__ = ['Reads', 'digest', 'note_read', 'recording']
