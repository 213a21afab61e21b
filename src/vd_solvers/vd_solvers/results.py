# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The result of one event on one configuration, whatever the model.

Every solver returns an :class:`EventOutcome`; the nodes turn it into a
``vd_interfaces/EventResult``, the recorder into a bag, ``vd run --json`` into
the JSON contract of ARCHITECTURE §5.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from vd_data_server.model import Configuration

#: the fidelities of the K&C data a result is computed from: the rigid parts, or the
#: flexible components of the configuration's flex groups
FIDELITIES = ('rigid', 'flexible')
#: the models that have flexible components (the full vehicle passes it to its K&C maps)
FLEXIBLE_MODELS = ('kc', 'vehicle')


def run_fidelity(model: str, config: Configuration | None, asked: str = '') -> str:
    """
    Return the K&C fidelity a run of ``model`` on ``config`` gets.

    ``asked`` (``--fidelity``, a goal's or a plan's ``fidelity``) when given; else
    'flexible' for a configuration whose ``flexible`` switch is on and a model with
    flexible components (FLEXIBLE_MODELS: the K&C model and the full vehicle, whose
    suspension maps are K&C runs), else 'rigid'. Every model that reads the
    configuration follows its switch; ``config`` None (not known yet) is rigid.
    """
    if asked:
        return asked
    flexible = config is not None and config.flexible and model in FLEXIBLE_MODELS
    return 'flexible' if flexible else 'rigid'


@dataclass(frozen=True)
class Metric:
    value: float
    unit: str  # SI; display units are applied at the edges (vd_events/reports/display.py)
    source: str = ''


@dataclass(frozen=True)
class Channel:
    unit: str
    values: np.ndarray  # shape (n_steps,)


@dataclass(frozen=True)
class EventOutcome:
    event: str
    configuration: str
    model: str
    fidelity: str
    axle: str
    data_hash: str
    metrics: Mapping[str, Metric]
    channels: Mapping[str, Channel]
    notes: Sequence[str] = field(default_factory=tuple)

    @property
    def n_steps(self) -> int:
        return max((len(c.values) for c in self.channels.values()), default=0)

    def to_json(self, bag: str | None = None) -> dict[str, Any]:
        """Return the ``vd run --json`` contract (SI values with their units)."""
        return {
            'event': self.event, 'configuration': self.configuration, 'model': self.model,
            'fidelity': self.fidelity, 'axle': self.axle, 'data_hash': self.data_hash,
            'metrics': {k: {'value': _num(m.value), 'unit': m.unit, 'source': m.source}
                        for k, m in self.metrics.items()},
            'channels': {k: {'unit': c.unit, 'values': [_num(v) for v in c.values]}
                         for k, c in self.channels.items()},
            'notes': list(self.notes),
            'bag': bag,
        }


def _num(value: float) -> float | None:
    value = float(value)
    return value if np.isfinite(value) else None
