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


__all__ = ['atomic_path', 'atomic_write']
