# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The recorder node: records vd topics to an MCAP bag (``ros2 run vd_events recorder``).

The role ``ros2 bag record`` plays (which pip-installed ROS lacks). Parameter
``bag``: the bag directory to create (refused if it exists). The bag is
written under ``<bag>.partial`` and becomes ``<bag>`` only when its owner says
the recording is complete: the service ``recorder/finish`` (std_srvs/Trigger, called by
the runner once it has confirmed every result it asked for) or ``stop()``.
Any other end (Ctrl-C, SIGTERM, the parent run dying) removes the partial bag
and says so: an interrupted recording never looks finished. The run's
provenance goes into the bag's metadata.

Each message is logged at its own stamp (``bag.log_time``: the simulation-time axis of
the states), and each topic records the QoS its publishers offered, so ``ros2 bag play``
of the bag reproduces the latched topics.

A run's per-step messages (typed states, odometry, TF) are written from its EventResult
(``vd_solvers.conversions.outcome_messages``, the one definition the solver publishes
them by): one message over DDS per run, written in one go, so the recorder keeps up
however long the run and however slowly its executor takes messages (rclpy takes one
per subscription and wait). A result is complete once its configuration and
provenance are written too; ``recorder/recorded`` (latched) says how many are.
"""
from __future__ import annotations

import threading
import time

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger

from vd_data_server.ros import names
from vd_data_server.ros.qos import CONFIGURATIONS, LATEST, RESULTS, STATES, TF
from vd_events.bags.bag import (
    RECORDER_DATA,
    BagWriter,
    cannot_write,
    log_time,
    offered_profiles,
    provenance_data,
)
from vd_events.errors import BagError
from vd_interfaces.msg import Configuration, DataStatus, EventResult, Provenance
from vd_solvers.conversions import TIME_AXIS, outcome_from_msg, outcome_messages, start_stamp
from vd_solvers.families import FAMILIES, ODOMETRY_TOPIC, TF_TOPIC

#: where the recorder says how many event results it has written completely (latched),
#: relative to the namespace (``/vd/recorder/recorded``)
RECORDED_TOPIC = 'recorder/recorded'
#: the service that closes the bag under its final name (``/vd/recorder/finish``)
FINISH_SERVICE = 'recorder/finish'
#: seconds the recorder process stays up after finish, for its response to be delivered
FINISH_LINGER = 0.3

#: topic (relative to the namespace) -> (type, QoS) the recorder subscribes to; the
#: subscriptions use the publishers' own profiles
TOPICS = {
    names.CONFIGURATION: (Configuration, CONFIGURATIONS),
    names.DATA_STATUS: (DataStatus, LATEST),
    names.PROVENANCE: (Provenance, RESULTS),
    **{family.result_topic: (EventResult, RESULTS) for family in FAMILIES.values()},
}
#: the result topics: each result brings its run's per-step messages
FAMILY_RESULTS = frozenset(family.result_topic for family in FAMILIES.values())
#: the topics written from each result, with the profile their publishers use
DERIVED = {**{family.state_topic: STATES for family in FAMILIES.values()},
           ODOMETRY_TOPIC: STATES, TF_TOPIC: TF}


def _stamp_ns(msg) -> int | None:
    """Return the stamp of a result or provenance message (None for data topics)."""
    if isinstance(msg, (Configuration, DataStatus)):
        return None
    stamp = msg.stamp
    return stamp.sec * 1_000_000_000 + stamp.nanosec


class Recorder(Node):
    """Record the graph's topics of one namespace to a bag; final only when finished."""

    def __init__(self, bag: str | None = None, **kwargs) -> None:
        kwargs.setdefault('namespace', names.DEFAULT_NAMESPACE)
        super().__init__('recorder', **kwargs)
        self.declare_parameter('bag', bag or '', ParameterDescriptor(
            description='bag directory to create', read_only=True))
        self.declare_parameter('configurations', [''], ParameterDescriptor(
            description="record only these configurations ('' = all)", read_only=True))
        path = self.get_parameter('bag').value
        if not path:
            raise ValueError("parameter 'bag' is required (the bag directory to create)")
        wanted = [c for c in self.get_parameter('configurations').value if c]
        self.only = set(wanted)
        self.counts: dict[str, int] = dict.fromkeys([*TOPICS, *DERIVED], 0)
        self.frame_prefix = self.declare_parameter(
            'frame_prefix', names.frame_prefix(self.get_namespace()), ParameterDescriptor(
                description="the solvers' frame prefix (the frames of the TF written from "
                'each result)', read_only=True)).value
        # runs stamped before this recorder started are not its own: on the time axis of
        # this process they end at or before TIME_AXIS.end(), which may lie ahead of the
        # wall clock after time-domain runs; a result kept latched by a solver of another
        # process was sent before this recorder existed (its source timestamp says so)
        self.start = max(self.get_clock().now().nanoseconds, TIME_AXIS.end() + 1)
        self.created = time.time_ns()
        self._qos: dict[str, list] = {}  # topic -> the offered QoS recorded in the bag
        self._provenance: set[tuple[str, str, str]] = set()
        self._pending: list[tuple[str, str, str]] = []  # results waiting for provenance
        self.complete = 0  # results written with their states, provenance and configuration
        self.error: str | None = None  # a write failed (full disk...): the bag is dropped
        self.finished = False
        self.interrupted = False  # destroyed before the recording was complete
        # the bag holds the resolved names (/vd/kc/result, /car2/kc/result, /tf)
        self._bag_topics = {t: self.resolve_topic_name(t) for t in [*TOPICS, *DERIVED]}
        # in-process runs spin this node on a multi-threaded executor while the runner
        # stops it from its own thread: writes and close never overlap
        self._lock = threading.Lock()
        # the bag's partial folder exists from here on: whatever stops the constructor
        # (a signal meanwhile) removes it
        self.writer = BagWriter(path, RECORDER_DATA)
        try:
            self.create_service(Trigger, FINISH_SERVICE, self._finish)
            self.recorded_pub = self.create_publisher(UInt32, RECORDED_TOPIC, LATEST)
            for topic, (msg_type, qos) in TOPICS.items():
                self.create_subscription(msg_type, topic, self._callback(topic), qos)
        except BaseException:  # e.g. a SIGTERM that shut the context down meanwhile
            self.writer.abort()
            raise
        self.get_logger().info(f'recording to {path}')

    def _callback(self, topic: str):
        run_topic = topic not in (names.CONFIGURATION, names.DATA_STATUS)

        def record(msg, info) -> None:
            if run_topic and info['source_timestamp'] < self.created:
                return  # a run a solver kept latched from before this recording
            with self._lock:
                if self.writer.closed:
                    return
                try:
                    self._record(topic, msg)
                except OSError as err:
                    self.error = str(cannot_write(self.writer.path, err))
                    self.get_logger().error(self.error)
                    self.writer.abort()
        return record

    def _record(self, topic: str, msg) -> None:
        name = getattr(msg, 'configuration', None)
        if topic == names.CONFIGURATION:
            name = msg.name
        if self.only and name is not None and name not in self.only:
            return
        stamp = _stamp_ns(msg)
        if stamp is not None and stamp < self.start:
            return  # kept by a solver from an earlier run: not this recording's
        if topic == names.PROVENANCE:
            for key, value in provenance_data(msg).items():
                self.writer.set_custom_data(key, value)
            self._provenance.add((msg.configuration, msg.event, msg.model))
        if topic in FAMILY_RESULTS:
            outcome = outcome_from_msg(msg)
            for derived, m in outcome_messages(outcome, start_stamp(outcome, msg.stamp),
                                               self.frame_prefix):
                self._write(derived, m)
            self._pending.append((msg.configuration, msg.event, msg.model))
        else:
            self._write(topic, msg)
        self._publish_complete()

    def _write(self, topic: str, msg) -> None:
        if topic not in self._qos:
            self._qos[topic] = self._offered(topic)
        self.writer.write(self._bag_topics[topic], msg, log_time(msg, time.time_ns()),
                          self._qos[topic])
        self.counts[topic] += 1

    def _offered(self, topic: str) -> list:
        """
        Return the QoS profiles the publishers of ``topic`` offer (as discovered).

        History and depth, which discovery does not carry, are those of the publishers'
        own profile (vd_data_server.ros.qos).
        """
        own = TOPICS[topic][1] if topic in TOPICS else DERIVED[topic]
        return offered_profiles(self, self._bag_topics[topic], own)

    def _publish_complete(self) -> None:
        """Count the results whose provenance and configuration are written too; say so."""
        if self.only and self.counts[names.CONFIGURATION] == 0:
            return
        done = [p for p in self._pending if p in self._provenance]
        if done:
            self._pending = [p for p in self._pending if p not in done]
            self.complete += len(done)
            self.recorded_pub.publish(UInt32(data=self.complete))

    def stop(self):
        """Close the bag (renaming it to its final name) and return its path."""
        with self._lock:
            if self.error is not None:
                raise BagError(self.error)
            self.finished = True
            return self.writer.close()

    def abort(self) -> None:
        with self._lock:
            self.writer.abort()

    def _finish(self, request, response):
        try:
            response.message = str(self.stop())
            response.success = True
        except (BagError, OSError) as err:
            response.success, response.message = False, str(err)
        return response


    def destroy_node(self) -> None:
        """Whatever ended the recording: no unfinished bag stays."""
        if not self.finished:
            self.abort()
            self.interrupted = True
        super().destroy_node()


__all__ = ['Recorder', 'RECORDED_TOPIC', 'FINISH_SERVICE', 'FINISH_LINGER']
