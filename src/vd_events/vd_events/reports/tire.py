# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""A tire's characteristic curves (``vd tire FILE``): pure slip over load, pressure, camber."""
from __future__ import annotations

from pathlib import Path

from vd_events.reports.figures import plt, save
from vd_solvers.constants import DEG


def plot_tire_curves(swept, path: Path, title: str) -> Path:
    """Draw Fx(kappa), Fy(alpha) and Mz(alpha) of each sweep (one row each) into ``path``."""
    fig, axes = plt.subplots(len(swept), 3, figsize=(13.0, 3.4 * len(swept)), dpi=100,
                             squeeze=False)
    for row, sweep in zip(axes, swept):
        for curve in sweep.curves:
            row[0].plot(curve.kappa, curve.fx / 1e3, label=curve.label)
            row[1].plot(curve.alpha / DEG, curve.fy / 1e3, label=curve.label)
            row[2].plot(curve.alpha / DEG, curve.mz, label=curve.label)
        for ax, (x, y) in zip(row, (('slip ratio kappa (-)', 'Fx (kN)'),
                                    ('slip angle alpha (deg)', 'Fy (kN)'),
                                    ('slip angle alpha (deg)', 'Mz (N m)'))):
            ax.set_xlabel(x)
            ax.set_ylabel(y)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize='small', title=sweep.title, title_fontsize='small')
    fig.suptitle(f'{title}: pure slip, TYDEX W axes (file convention)', fontsize='medium')
    return save(fig, path)


__all__ = ['plot_tire_curves']
