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
- an entry is written under a temporary name of its own and renamed over the entry, so runs
  started together read an old entry, a new one or none, never half of one; an entry that
  cannot be read is loaded again.

Entries live in ``$XDG_CACHE_HOME/vd/studies`` (``~/.cache/vd/studies``); the oldest beyond
:data:`MAX_ENTRIES` are removed. A folder that cannot be written only means no cache.
"""
from __future__ import annotations

import hashlib
import importlib.util
import os
from pathlib import Path
import pickle
import sys
import tempfile

from .reads import digest, recording
from .study import Study, load_study

#: entries kept (one per master file and working folder); the oldest go first
MAX_ENTRIES = 64
#: format of an entry; raised when its layout changes
VERSION = 1


def cache_folder() -> Path:
    """Return the folder of the entries (module doc)."""
    base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'), '.cache')
    return Path(base) / 'vd' / 'studies'


def cached_study(master_path: str | Path, *, data_root: str | Path | None = None) -> Study:
    """
    Return ``load_study(master_path, data_root=data_root)``, from the cache when it is fresh.

    The same study either way: the cached one is the pickled result of the same load over
    files of the same bytes.
    """
    entry = cache_folder() / f'{_key(master_path, data_root)}.pickle'
    study = _read(entry)
    if study is not None:
        return study
    with recording() as reads:
        study = load_study(master_path, data_root=data_root)
    if reads.consistent:
        _write(entry, reads.files, study)
    return study


def _key(master_path: str | Path, data_root: str | Path | None) -> str:
    """Hash of what decides the load besides the files it reads (module doc)."""
    parts = [str(VERSION), sys.version, os.getcwd(), str(master_path), str(data_root),
             os.path.realpath(master_path), _sources(), _installed()]
    return hashlib.sha256('\0'.join(parts).encode()).hexdigest()[:32]


def _sources() -> str:
    """Hash of this package's Python sources: code that reads differently, keys differently."""
    h = hashlib.sha256()
    for path in sorted(Path(__file__).resolve().parent.rglob('*.py')):
        h.update(str(path).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


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


def _read(entry: Path) -> Study | None:
    """Return the study of ``entry`` if every file it was read from is unchanged, else None."""
    try:
        data = entry.read_bytes()
    except OSError:
        return None
    try:
        files, study = pickle.loads(data)  # noqa: S301 - the user's own cache folder
    except Exception:  # noqa: BLE001 - a damaged or foreign entry is loaded again
        return None
    for path, expected in files.items():
        try:
            if digest(Path(path).read_bytes()) != expected:
                return None
        except OSError:
            return None
    return study if isinstance(study, Study) else None


def _write(entry: Path, files: dict[str, str], study: Study) -> None:
    data = pickle.dumps((files, study), protocol=pickle.HIGHEST_PROTOCOL)
    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        # a name of this writer's own: two runs writing one entry never mix their bytes
        fd, tmp = tempfile.mkstemp(dir=entry.parent, prefix=f'.{entry.stem}.', suffix='.tmp')
        try:
            with os.fdopen(fd, 'wb') as stream:
                stream.write(data)
            os.replace(tmp, entry)
        except BaseException:
            os.unlink(tmp)
            raise
        _prune(entry.parent)
    except OSError:
        pass  # no writable cache folder: the next run loads the files again


def _prune(folder: Path) -> None:
    entries = []
    for path in folder.glob('*.pickle'):
        try:
            entries.append((path.stat().st_mtime_ns, path))
        except OSError:  # removed by another run meanwhile
            continue
    for _, path in sorted(entries)[:-MAX_ENTRIES]:
        path.unlink(missing_ok=True)


__all__ = ['MAX_ENTRIES', 'cache_folder', 'cached_study']
