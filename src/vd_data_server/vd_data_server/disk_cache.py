# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What vd keeps on disk between commands because it can be computed again: the user's cache.

Entries are pickles in ``$XDG_CACHE_HOME/vd/<kind>`` (``~/.cache/vd/<kind>``), named by the
hash of what decides their content (the caller's key). An entry is written under a temporary
name of its writer's own and renamed over the entry, so processes writing one entry together
leave a whole one; one that cannot be read is no entry. The oldest beyond a kind's limit are
removed. A folder that cannot be written only means no cache: nothing here raises OSError.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path
import pickle
import tempfile
from typing import Any


def folder(kind: str) -> Path:
    """Return the folder of the entries of ``kind`` (module doc)."""
    base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'), '.cache')
    return Path(base) / 'vd' / kind


def key_of(*parts: str) -> str:
    """Return the name of the entry of ``parts`` (a hash)."""
    return hashlib.sha256('\0'.join(parts).encode()).hexdigest()[:32]


def sources_hash(*packages: Path) -> str:
    """Return a hash of the Python sources under ``packages``: other code, other entries."""
    h = hashlib.sha256()
    for package in packages:
        for path in sorted(package.rglob('*.py')):
            h.update(str(path).encode())
            h.update(path.read_bytes())
    return h.hexdigest()


def load(kind: str, key: str) -> Any:
    """Return the object of the entry ``key`` of ``kind``, or None (none, or unreadable)."""
    try:
        data = (folder(kind) / f'{key}.pickle').read_bytes()
    except OSError:
        return None
    try:
        return pickle.loads(data)  # noqa: S301 - the user's own cache folder
    except Exception:  # noqa: BLE001 - a damaged or foreign entry is no entry
        return None


def store(kind: str, key: str, value: Any, keep: int) -> None:
    """Write ``value`` as the entry ``key`` of ``kind``; keep the newest ``keep`` entries."""
    data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    where = folder(kind)
    try:
        where.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=where, prefix=f'.{key}.', suffix='.tmp')
        try:
            with os.fdopen(fd, 'wb') as stream:
                stream.write(data)
            os.replace(tmp, where / f'{key}.pickle')
        except BaseException:
            os.unlink(tmp)
            raise
        _prune(where, keep)
    except OSError:
        pass  # no writable cache folder: the next command computes it again


def _prune(where: Path, keep: int) -> None:
    entries = []
    for path in where.glob('*.pickle'):
        try:
            entries.append((path.stat().st_mtime_ns, path))
        except OSError:  # removed by another process meanwhile
            continue
    for _, path in sorted(entries)[:-keep]:
        path.unlink(missing_ok=True)


__all__ = ['folder', 'key_of', 'load', 'sources_hash', 'store']
