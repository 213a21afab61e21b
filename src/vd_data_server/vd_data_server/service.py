# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The data server's ROS-free core: load, watch, edit, reload.

The node (``data_server_node.py``) only turns this into topics and services.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
import os
from pathlib import Path
from typing import Any

from .errors import DataError
from .master import load_master
from .study import Study, load_study

#: how edits made over ROS (the set_override service, here in the default namespace)
#: are labelled in messages and value sources
EDIT_SOURCE = 'ROS edit /vd/set_override'


def _load(master_file: Path, edits: Mapping[str, Mapping[str, Any]],
          source: str = EDIT_SOURCE) -> Study:
    """
    Load the study at the node boundary: any failure of the input is a DataError.

    So a running data server keeps its last good data (RecursionError, MemoryError, a
    bug triggered by odd input are reported like a bad value, never kill the node).
    """
    try:
        return load_study(master_file, extra_overrides=edits, extra_source=source)
    except DataError:
        raise
    except Exception as err:  # noqa: BLE001 - the node boundary
        raise DataError(f'cannot load: {type(err).__name__}: {err}',
                        file=str(master_file)) from None


@dataclass(frozen=True)
class ReloadOutcome:
    changed: bool  # new data to publish
    errors: tuple[str, ...]  # non-empty: the reload failed, the previous data stays


class DataService:
    """
    Hold the current study, reload it on changes and apply validated overrides.

    It reloads when a file under the data root or the master file changes.
    """

    def __init__(self, master_file: str | Path, edit_source: str = EDIT_SOURCE) -> None:
        self.master_file = Path(master_file)
        self.edit_source = edit_source
        self.edits: dict[str, dict[str, Any]] = {}
        self.study: Study | None = None
        self.errors: tuple[str, ...] = ()
        self._signature: tuple | None = None

    @property
    def data_root(self) -> Path | None:
        return self.study.master.data_root if self.study else None

    def load(self, loaded: Study | None = None) -> ReloadOutcome:
        """
        (Re)load everything now. On failure the previous study is kept.

        ``loaded``: the study of this master file (without edits) as the caller has just
        loaded it, used instead of loading it again (an embedded run's data server); a
        study of another file is not used.
        """
        signature = self._files_signature()
        try:
            if loaded is None or self.edits or (
                    Path(loaded.master.path).resolve() != self.master_file.resolve()):
                loaded = _load(self.master_file, self.edits, self.edit_source)
            study = loaded
        except DataError as err:
            self._signature = signature
            self.errors = tuple(str(err).splitlines())
            return ReloadOutcome(False, self.errors)
        self._signature = self._files_signature(study.master.data_root)
        self.study = study
        self.errors = ()
        return ReloadOutcome(True, ())

    def poll(self) -> ReloadOutcome | None:
        """Reload if any watched file changed since the last load; None if nothing did."""
        if self._files_signature(self.data_root) == self._signature:
            return None
        return self.load()

    def set_override(self, configuration: str, key: str, value: str) -> None:
        """Apply a temporary override; raises DataError (and changes nothing) if invalid."""
        if self.study is None:
            raise DataError('no valid data loaded', file=str(self.master_file))
        if configuration not in self.study.configurations:
            raise DataError(f"configuration '{configuration}' does not exist (available: "
                            f"{', '.join(self.study.configuration_names)})",
                            file=str(self.master_file))
        edits = {name: dict(values) for name, values in self.edits.items()}
        edits.setdefault(configuration, {})[key] = value
        study = _load(self.master_file, edits, self.edit_source)
        self.edits = edits
        self.study = study

    def _files_signature(self, root: Path | None = None) -> tuple:
        entries: list[tuple[str, int, int]] = []
        paths = [self.master_file]
        if root is None:
            try:
                root = load_master(self.master_file).data_root
            except DataError:
                root = None
        for path in paths:
            entries.append(_stat(path))
        if root is not None and root.is_dir():
            # links to folders are not followed: a loop would never end, and files
            # outside the data root are never read anyway (master.inside)
            for folder, _, files in os.walk(root, followlinks=False):
                for name in files:
                    entries.append(_stat(Path(folder) / name))
        return tuple(sorted(entries))

    def configurations(self) -> Mapping[str, Any]:
        return self.study.configurations if self.study else {}


def _stat(path: Path) -> tuple[str, int, int]:
    try:
        st = path.stat()
    except OSError:
        return (str(path), -1, -1)
    return (str(path), st.st_mtime_ns, st.st_size)
