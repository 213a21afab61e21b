# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""What several verbs share: the study they name, their namespace, their progress bar."""
from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path
import sys
from typing import Any, TypeVar

from vd_data_server.paths import default_master
from vd_data_server.ros.names import DEFAULT_NAMESPACE, check_namespace
from vd_data_server.study import Study
from vd_data_server.study_cache import cached_study
from vd_events.orchestration.requests import RunRequest

T = TypeVar('T')


def master_path(master: str | None) -> Path:
    """Return ``--master``, or the bundled sample study."""
    return Path(master) if master else default_master()


def study(master: str | None) -> tuple[Path, Study]:
    """
    Return the path and the loaded study of ``--master``.

    Cached while its files are unchanged (``vd_data_server.study_cache``).
    """
    path = master_path(master)
    return path, cached_study(path)


def namespace(args: argparse.Namespace) -> str:
    """Return ``--namespace`` checked, or the default ``/vd``."""
    return check_namespace(args.namespace) if args.namespace is not None else DEFAULT_NAMESPACE


class ProgressBar:
    """
    A rich progress bar on the terminal (stderr) for the runs' action feedback.

    One task per run; a context manager, so the bar is closed however the runs end.
    """

    def __init__(self) -> None:
        # imported here: without a terminal (--json, scripts) there is no bar to import
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn

        self.progress = Progress(TextColumn('{task.description}'), BarColumn(),
                                 TaskProgressColumn(), TextColumn('{task.fields[stage]}'),
                                 console=Console(stderr=True), transient=False)
        self.tasks: dict[RunRequest, Any] = {}

    def __call__(self, request: RunRequest, fraction: float, stage: str) -> None:
        if request not in self.tasks:
            self.tasks[request] = self.progress.add_task(
                f'{request.configuration} / {request.event} / {request.model}', total=1.0,
                stage=stage)
        self.progress.update(self.tasks[request], completed=fraction, stage=stage)

    def __enter__(self):
        self.progress.start()
        return self

    def __exit__(self, *exc) -> None:
        self.progress.stop()


def progress_bar(args: argparse.Namespace) -> ProgressBar | None:
    """Return a progress bar on a terminal without ``--json``, else None."""
    return ProgressBar() if sys.stderr.isatty() and not args.json else None


def with_progress(progress: ProgressBar | None, work: Callable[[], T]) -> T:
    """Run ``work()`` with the progress bar (if any) shown."""
    if progress is None:
        return work()
    with progress:
        return work()


__all__ = ['master_path', 'study', 'namespace', 'ProgressBar', 'progress_bar', 'with_progress']
