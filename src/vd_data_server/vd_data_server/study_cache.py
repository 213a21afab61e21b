# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A loaded and validated study kept on disk, keyed by the hash of every file it was read from.

Loading a study reads and checks the master file, every data file and the ``.tir`` files
(``load_study``); most of a command's start-up went into it and into importing the unit
library it converts with. :func:`cached_study` returns the study of an earlier load instead
when nothing it was read from has changed:

- the entry is found by the master file as named (and the working folder, the data root
  and the real path of the master file), by the sources of this package and by the
  installed packages (the folder of pint and PyYAML, whose time stamp an install changes);
- it holds the hash of the bytes of every file the load read (:mod:`vd_data_server.reads`)
  and the study; each file is hashed again, and one that differs (or is gone) makes the
  entry stale: the study is loaded again and the entry replaced;
- only a study that loaded without error is kept (an error is found again each time, with
  its message); a file that changed during the load is not kept either;
- entries are those of :mod:`vd_data_server.disk_cache` (kind ``studies``): written whole
  or not at all, so runs started together read an old entry, a new one or none; an entry
  that cannot be read is loaded again; the oldest beyond :data:`MAX_ENTRIES` are removed.
"""
from __future__ import annotations

import importlib.util
import os
from pathlib import Path
import sys

from . import disk_cache
from .reads import digest, recording
from .study import Study, load_study

#: entries kept (one per master file and working folder); the oldest go first
MAX_ENTRIES = 64
#: the kind of entry (:func:`vd_data_server.disk_cache.folder`)
KIND = 'studies'
#: format of an entry; raised when its layout changes
VERSION = 1


def cached_study(master_path: str | Path, *, data_root: str | Path | None = None) -> Study:
    """
    Return ``load_study(master_path, data_root=data_root)``, from the cache when it is fresh.

    The same study either way: the cached one is the pickled result of the same load over
    files of the same bytes.
    """
    key = _key(master_path, data_root)
    study = _fresh(disk_cache.load(KIND, key))
    if study is not None:
        return study
    with recording() as reads:
        study = load_study(master_path, data_root=data_root)
    if reads.consistent:
        disk_cache.store(KIND, key, (reads.files, study), MAX_ENTRIES)
    return study


def _key(master_path: str | Path, data_root: str | Path | None) -> str:
    """Hash of what decides the load besides the files it reads (module doc)."""
    return disk_cache.key_of(
        str(VERSION), sys.version, os.getcwd(), str(master_path), str(data_root),
        os.path.realpath(master_path), disk_cache.sources_hash(Path(__file__).resolve().parent),
        _installed())


def _installed() -> str:
    """Return the folders of the unit and YAML libraries with their time stamps."""
    # installing or removing a package changes the time stamp of its site-packages folder
    stamps = []
    for name in ('pint', 'yaml'):
        spec = importlib.util.find_spec(name)
        origin = spec.origin if spec is not None else None
        if origin:
            folder = Path(origin).parent.parent
            stamps.append(f'{folder}:{folder.stat().st_mtime_ns}')
    return ';'.join(stamps)


def _fresh(entry: object) -> Study | None:
    """Return the study of ``entry`` if every file it was read from is unchanged, else None."""
    if not (isinstance(entry, tuple) and len(entry) == 2 and isinstance(entry[1], Study)):
        return None
    files, study = entry
    for path, expected in files.items():
        try:
            if digest(Path(path).read_bytes()) != expected:
                return None
        except OSError:
            return None
    return study


__all__ = ['KIND', 'MAX_ENTRIES', 'cached_study']
