# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
EventOutcomes into a bag without a ROS graph, with the messages a solver publishes.

The messages come from ``vd_solvers.conversions`` (the one place they are built), the
bag from :class:`vd_events.bags.bag.BagWriter` (atomic: written as ``DIR.partial``, renamed
when complete), so a bag of imported measurements reads like one of ``vd run --bag``:
per family the topics ``/vd/<family>/result`` and ``/vd/<family>/state`` (full vehicle:
``VehicleState``, plus ``/vd/vehicle/odom`` and ``/tf`` when the pose is known; K&C: ``/tf``
of the wheels when the wheel centres are known), and
``/vd/provenance``. Log time = header stamp.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

from builtin_interfaces.msg import Time

from vd_data_server.ros.names import DEFAULT_NAMESPACE
from vd_data_server.ros.qos import profile_of
from vd_events.bags.bag import BagWriter, log_time
from vd_solvers.conversions import outcome_messages as messages
from vd_solvers.conversions import provenance_to_msg
from vd_solvers.results import EventOutcome


def _time(ns: int):

    return Time(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def outcome_messages(outcome: EventOutcome, stamp_ns: int) -> list[tuple[str, object]]:
    """
    (topic, message) of one outcome, as its solver publishes them in ``/vd``.

    The messages of :func:`vd_solvers.conversions.outcome_messages` (a log's unmeasured
    channels are NaN in the typed states and 0 in the pose, docs/testdata.md).
    """
    return [(topic if topic.startswith('/') else f'{DEFAULT_NAMESPACE}/{topic}', msg)
            for topic, msg in messages(outcome, _time(stamp_ns))]


def write_outcomes(bag: Path, items: Sequence[tuple[EventOutcome, int]],
                   custom_data: Mapping[str, str], master_file: str = '') -> Path:
    """Write every (outcome, start stamp ns) to the new bag ``bag``; return its path."""
    messages = []
    for outcome, stamp_ns in items:
        messages.append(('/vd/provenance',
                         provenance_to_msg(outcome, _time(stamp_ns), master_file)))
        messages += outcome_messages(outcome, stamp_ns)
    writer = BagWriter(bag, custom_data)
    try:
        for topic, msg in messages:
            # the QoS the solvers offer, so a replay latches like the live graph
            writer.write(topic, msg, log_time(msg, 0), [profile_of(topic)])
        return writer.close()
    except BaseException:
        writer.abort()
        raise


__all__ = ['write_outcomes', 'outcome_messages']
