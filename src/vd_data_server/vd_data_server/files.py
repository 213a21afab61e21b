# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Files written whole or not at all: the one atomic-write helper of vd.

Every file vd writes for a user (a report page, a figure, a sweep table, a master file
edited by the workbench) is written under a temporary name in the same folder and renamed
over the target in one ``os.replace``: a reader sees the old file or the new one, never a
half-written one, and an interrupted write leaves no file that looks finished.
"""
from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
import fcntl
import os
from pathlib import Path


@contextmanager
def atomic_path(path: Path | str) -> Iterator[Path]:
    """
    Yield a temporary path beside ``path``; on success it replaces ``path``.

    For writers that want a file name (matplotlib's ``savefig``, pyarrow): what they
    write becomes ``path`` only when the block ends without an exception; otherwise the
    temporary file is removed and ``path`` is untouched.
    """
    path = Path(path)
    tmp = path.with_name(f'.{path.name}.partial')
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def atomic_write(path: Path | str, data: str | bytes) -> Path:
    """Write ``data`` (text as UTF-8) to ``path`` atomically; return ``path``."""
    path = Path(path)
    with atomic_path(path) as tmp:
        if isinstance(data, str):
            tmp.write_text(data, encoding='utf-8')
        else:
            tmp.write_bytes(data)
    return path


@contextmanager
def locked(path: Path | str) -> Iterator[None]:
    """
    Hold an exclusive ``flock`` on the file ``path`` for the block (read-modify-write).

    Every vd writer of a file someone edits (the workbench, ``vd import xlsx``,
    ``vd optimize``) reads, changes and replaces it inside this block, so two of them can
    never interleave and lose an update. A writer replaces the file (a new inode) while
    others wait on the old one: a waiter that gets the lock of a replaced file takes the
    lock of the new file instead. The wait ends when the holder's short write ends (or
    its process dies, which releases the lock).
    """
    while True:
        fd = os.open(path, os.O_RDONLY)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            if os.fstat(fd).st_ino == os.stat(path).st_ino:
                break
        except BaseException:
            os.close(fd)
            raise
        os.close(fd)
    try:
        yield
    finally:
        os.close(fd)


def numbered_folder(parent: Path | str) -> Path:
    """
    Create and return a new folder ``parent/N``, N one more than the highest number there.

    For default output folders: each call gets a folder of its own (two at once get two
    numbers: ``mkdir`` fails for the second taker of a number), so a later run never
    overwrites nor collides with an earlier one.
    """
    parent = Path(parent)
    parent.mkdir(parents=True, exist_ok=True)
    taken = [int(p.name) for p in parent.iterdir() if p.name.isdigit()]
    number = max(taken, default=0) + 1
    while True:
        folder = parent / f'{number:03d}'
        try:
            folder.mkdir()
            return folder
        except FileExistsError:
            number += 1


__all__ = ['atomic_path', 'atomic_write', 'locked', 'numbered_folder']
