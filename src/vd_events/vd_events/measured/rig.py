# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Live rig data (``sensor_msgs/JointState``) into the same EventOutcome as a file import.

A rig on ROS publishes its posts and load cells as joints: ``name[i]`` with
``position[i]`` (m or rad), ``velocity[i]`` and ``effort[i]`` (N or N*m). The column map
(:mod:`.columns`) names them ``JOINT.position``, ``JOINT.velocity`` or ``JOINT.effort``
(e.g. ``post_left.position: {channel: wheel_travel, side: left}``); a unit in the map is
the unit the rig publishes in (default: the channel's SI unit, as REP 103 asks). Time
is the messages' header stamp from the first message (vehicle kind); a K&C rig's
samples are its steps, in order.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import hashlib

import numpy as np

from vd_events.errors import InputError
from vd_events.measured.columns import ColumnMap, si_unit, unit_factor
from vd_solvers.results import Channel, EventOutcome, Metric

FIELDS = ('position', 'velocity', 'effort')


@dataclass
class RigRecording:
    """Samples of mapped joints, converted to SI channels as they arrive."""

    cmap: ColumnMap
    source: str  # the topic
    rows: list[list[float]] = field(default_factory=list)
    stamps: list[float] = field(default_factory=list)
    incomplete: int = 0  # messages that lacked a mapped joint

    def __post_init__(self) -> None:
        self._specs = []
        for key, spec in self.cmap.columns.items():
            joint, _, what = key.rpartition('.')
            if what not in FIELDS or not joint:
                raise InputError(self.cmap.path, f'columns.{key}: a rig column is '
                                 f'JOINT.position, JOINT.velocity or JOINT.effort')
            target = si_unit(self.cmap.kind, spec.channel) or ''
            factor, offset = unit_factor(spec.unit if spec.unit is not None else target, target)
            self._specs.append((joint, what, spec.channel, factor * spec.sign, offset * spec.sign))

    @property
    def channels(self) -> list[str]:
        return [s[2] for s in self._specs]

    def add(self, stamp: float, names, position, velocity, effort) -> bool:
        """One JointState's mapped values; False (and counted) if a mapped joint is missing."""
        arrays = {'position': position, 'velocity': velocity, 'effort': effort}
        index = {n: i for i, n in enumerate(names)}
        row = []
        for joint, what, _channel, factor, offset in self._specs:
            i = index.get(joint)
            values = arrays[what]
            if i is None or i >= len(values) or not np.isfinite(values[i]):
                self.incomplete += 1
                return False
            row.append(float(values[i]) * factor + offset)
        if self.stamps and self.cmap.kind == 'vehicle' and stamp <= self.stamps[-1]:
            self.incomplete += 1
            return False
        self.rows.append(row)
        self.stamps.append(stamp)
        return True

    def outcome(self) -> EventOutcome:
        """Return the recording so far as an EventOutcome (model rig or test, measured)."""
        if len(self.rows) < 2:
            raise InputError(self.source, f'{len(self.rows)} complete sample(s) received: '
                             'nothing to record')
        data = np.array(self.rows)
        channels = {c: Channel(si_unit(self.cmap.kind, c) or '', data[:, k])
                    for k, c in enumerate(self.channels)}
        if self.cmap.kind == 'vehicle':
            t = np.array(self.stamps)
            channels['time'] = Channel('s', t - t[0])
        digest = hashlib.sha256(data.tobytes()).hexdigest()
        notes = (f'measured live: {self.source} (sensor_msgs/JointState)',
                 f'column map: {self.cmap.path}',
                 *(f'{k}: {v}' for k, v in self.cmap.provenance.items()),
                 f'{self.incomplete} message(s) without every mapped joint left out')
        model = 'rig' if self.cmap.kind == 'kc' else 'test'
        return EventOutcome(event=self.cmap.event, configuration=self.cmap.configuration,
                            model=model, fidelity='measured', axle=self.cmap.axle,
                            data_hash=digest,
                            metrics={'samples': Metric(float(len(self.rows)), '-')},
                            channels=channels, notes=notes)


__all__ = ['RigRecording', 'FIELDS']
