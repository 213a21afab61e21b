# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
EventOutcomes into a bag without a ROS graph, with the messages a solver publishes.

The messages come from ``vd_solvers.conversions`` (the one place they are built), the
bag from :class:`vd_events.bag.BagWriter` (atomic: written as ``DIR.partial``, renamed
when complete), so a bag of imported measurements reads like one of ``vd run --bag``:
per family the topics ``/vd/<family>/result`` and ``/vd/<family>/state`` (full vehicle:
``VehicleState``, plus ``/vd/vehicle/odom`` and ``/tf`` when the pose is known; K&C: ``/tf``
of the wheels when the wheel centres are known), and
``/vd/provenance``. Log time = header stamp.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
import dataclasses
from pathlib import Path

import numpy as np

from vd_solvers import __version__
from vd_solvers.results import Channel, EventOutcome

#: model -> topic family (the solver that would have produced it)
FAMILIES = {'vehicle': 'vehicle', 'test': 'vehicle', 'kc': 'kc', 'rig': 'kc',
            'bicycle': 'steady_state', 'two_track': 'steady_state'}
POSE = ('x', 'y', 'yaw')


def _time(ns: int):
    from builtin_interfaces.msg import Time

    return Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def _ns(stamp) -> int:
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def _padded(outcome: EventOutcome, names: Sequence[str], fill: float) -> EventOutcome:
    """``outcome`` with every channel of ``names`` (``fill`` where it has none)."""
    n = outcome.n_steps
    channels = dict(outcome.channels)
    for name in names:
        if name not in channels:
            channels[name] = Channel('', np.full(n, fill))
    return dataclasses.replace(outcome, channels=channels)


def outcome_messages(outcome: EventOutcome, stamp_ns: int) -> list[tuple[str, object]]:
    """(topic, message) of one outcome, in publishing order (provenance first)."""
    from vd_solvers.conversions import (
        VEHICLE_FIELDS,
        VEHICLE_WHEELS,
        WHEEL_FIELDS,
        outcome_analytical_states,
        outcome_kc_states,
        outcome_kc_transforms,
        outcome_odometry,
        outcome_to_msg,
        outcome_transforms,
        outcome_vehicle_states,
    )

    family = FAMILIES.get(outcome.model, outcome.model)
    stamp = _time(stamp_ns)
    out: list[tuple[str, object]] = []
    if family == 'vehicle':
        wheels = [f'{prefix}_{w}' for prefix, _ in WHEEL_FIELDS.values() for w in VEHICLE_WHEELS]
        # a log has no wheel loads or torque: NaN in the typed state says "not measured"
        states = outcome_vehicle_states(_padded(outcome, [*VEHICLE_FIELDS, *wheels],
                                                float('nan')), stamp)
        out += [('/vd/vehicle/state', m) for m in states]
        if all(k in outcome.channels for k in POSE):
            # unmeasured roll, pitch, sideslip: 0 in the pose (docs/testdata.md)
            posed = _padded(outcome, ('roll', 'pitch', 'sideslip', 'speed', 'yaw_rate'), 0.0)
            out += [('/tf', m) for m in outcome_transforms(posed, stamp)]
            out += [('/vd/vehicle/odom', m) for m in outcome_odometry(posed, stamp)]
    else:
        states = outcome_kc_states if family == 'kc' else outcome_analytical_states
        if family == 'kc':  # the wheels' frames when the rig file has the wheel centres
            out += [('/tf', m) for m in outcome_kc_transforms(outcome, stamp)]
        out += [(f'/vd/{family}/state', m) for m in states(outcome, stamp)]
    out.append((f'/vd/{family}/result', outcome_to_msg(outcome, stamp)))
    return out


def write_outcomes(bag: Path, items: Sequence[tuple[EventOutcome, int]],
                   custom_data: Mapping[str, str], master_file: str = '') -> Path:
    """Write every (outcome, start stamp ns) to the new bag ``bag``; return its path."""
    from vd_data_server.qos import RESULTS, STATES
    from vd_interfaces.msg import Provenance

    from .bag import BagWriter, log_time

    messages = []
    for outcome, stamp_ns in items:
        provenance = Provenance(stamp=_time(stamp_ns), configuration=outcome.configuration,
                                master_file=master_file, data_hash=outcome.data_hash,
                                model=outcome.model, fidelity=outcome.fidelity,
                                event=outcome.event, software_version=__version__)
        messages.append(('/vd/provenance', provenance))
        messages += outcome_messages(outcome, stamp_ns)
    writer = BagWriter(bag, custom_data)
    try:
        for topic, msg in messages:
            # the QoS the solvers offer, so a replay latches like the live graph
            qos = RESULTS if topic.endswith(('/result', '/provenance')) else STATES
            writer.write(topic, msg, log_time(msg, 0), [qos])
        return writer.close()
    except BaseException:
        writer.abort()
        raise


__all__ = ['write_outcomes', 'outcome_messages', 'FAMILIES']
