# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The reports' figures: one way to make, label and save a plot (matplotlib, no screen).

Every report page (``vd report``, ``vd study``, ``vd compare``, sweeps, the sine with
dwell) draws through :func:`new_figure` and saves through :func:`save_figure` or
:func:`save`, so the figures look alike and are written atomically.
"""
from __future__ import annotations

import base64
from pathlib import Path

import matplotlib

matplotlib.use('Agg')  # files only: no display is needed (or present on a CI machine)
import matplotlib.pyplot as plt  # noqa: E402 - after the backend is chosen

from vd_data_server.files import atomic_path  # noqa: E402

#: size and resolution of a report figure
FIGSIZE = (6.4, 4.2)
DPI = 110
#: line styles cycle with the colours, so identical curves stay visible on top of each other
LINE_STYLES = ('-', '--', ':', '-.')


def new_figure(figsize: tuple[float, float] = FIGSIZE, dpi: int = DPI):
    """Return (figure, axes) of one report plot."""
    return plt.subplots(figsize=figsize, dpi=dpi)


def save_figure(fig, ax, path: Path, xlabel: str, ylabel: str, title: str,
                legend: str = 'small') -> Path:
    """Label, grid and title ``ax`` the reports' way; write ``fig`` to ``path``, close it."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=legend)
    ax.set_title(title, fontsize='medium')
    return save(fig, path)


def save(fig, path: Path, dpi: int | None = None) -> Path:
    """Lay ``fig`` out, write it to ``path`` (PNG, atomically) and close it."""
    fig.tight_layout()
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format='png', **({'dpi': dpi} if dpi else {}))
    plt.close(fig)
    return path


def data_uri(path: Path) -> str:
    """Return a PNG file as a data URI (a page that embeds its figures opens offline)."""
    return 'data:image/png;base64,' + base64.b64encode(Path(path).read_bytes()).decode('ascii')


__all__ = ['new_figure', 'save_figure', 'save', 'data_uri', 'LINE_STYLES', 'plt']
