# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_events recorder``: records vd topics to an MCAP bag.

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
"""
from __future__ import annotations

import sys
import threading
import time

from nav_msgs.msg import Odometry
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.qos import HistoryPolicy
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger

from tf2_msgs.msg import TFMessage
from vd_data_server import names
from vd_data_server.node_main import run_node
from vd_data_server.qos import CONFIGURATIONS, LATEST, STATES
from vd_events.bag import BagError, BagWriter, log_time
from vd_interfaces.msg import (
    AnalyticalState,
    Configuration,
    DataStatus,
    EventResult,
    KcState,
    Provenance,
    VehicleState,
)
from vd_solvers.conversions import TIME_AXIS, has_wheel_frames
from vd_solvers.families import FAMILIES, ODOMETRY_TOPIC, TF_TOPIC

#: where the recorder says how many event results it has written completely (latched),
#: relative to the namespace (``/vd/recorder/recorded``)
RECORDED_TOPIC = 'recorder/recorded'
#: the service that closes the bag under its final name (``/vd/recorder/finish``)
FINISH_SERVICE = 'recorder/finish'
#: seconds the recorder process stays up after finish, for its response to be delivered
FINISH_LINGER = 0.3

#: each family's per-step message type
STATE_TYPES = {'steady_state': AnalyticalState, 'kc': KcState, 'vehicle': VehicleState}

#: topic (relative to the namespace, or absolute) -> (type, QoS) recorded by default;
#: the subscriptions use the publishers' own profiles
TOPICS = {
    names.CONFIGURATION: (Configuration, CONFIGURATIONS),
    names.DATA_STATUS: (DataStatus, LATEST),
    names.PROVENANCE: (Provenance, STATES),
    **{topic: spec for family in FAMILIES.values() for topic, spec in (
        (family.result_topic, (EventResult, STATES)),
        (family.state_topic, (STATE_TYPES[family.name], STATES)))},
    ODOMETRY_TOPIC: (Odometry, STATES),
    TF_TOPIC: (TFMessage, STATES),
}


def _stamp_ns(msg) -> int | None:
    """Return the stamp of a result, state or provenance message (None for data topics)."""
    stamp = getattr(msg, 'stamp', None)
    if stamp is None and hasattr(msg, 'header'):
        stamp = msg.header.stamp
    if stamp is None and getattr(msg, 'transforms', None):  # TF
        stamp = msg.transforms[0].header.stamp
    if stamp is None or isinstance(msg, (Configuration, DataStatus)):
        return None
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
        self.counts: dict[str, int] = dict.fromkeys(TOPICS, 0)
        # runs stamped before this recorder started are not its own: on the time axis of
        # this process they end at or before TIME_AXIS.end(), which may lie ahead of the
        # wall clock after time-domain runs (their history stays latched in the solvers)
        self.start = max(self.get_clock().now().nanoseconds, TIME_AXIS.end() + 1)
        self._samples: dict[tuple[str, str, str], int] = {}
        self._qos: dict[str, list] = {}  # topic -> the offered QoS recorded in the bag
        self._pending: list[tuple[tuple[str, str, str], int, int, int]] = []
        self._odometry_needed = 0  # odometry messages the full-vehicle results so far bring
        self._tf_needed = 0  # TF messages the results so far bring (vehicle and K&C)
        self.complete = 0  # results written together with all their step samples
        self.error: str | None = None  # a write failed (full disk...): the bag is dropped
        self.finished = False
        self.interrupted = False  # destroyed before the recording was complete
        # the bag holds the resolved names (/vd/kc/result, /car2/kc/result, /tf)
        self._bag_topics = {t: self.resolve_topic_name(t) for t in TOPICS}
        # in-process runs spin this node on a multi-threaded executor while the runner
        # stops it from its own thread: writes and close never overlap
        self._lock = threading.Lock()
        # the bag's partial folder exists from here on: whatever stops the constructor
        # (a signal meanwhile) removes it
        self.writer = BagWriter(path, {'vd.recorder': 'vd_events recorder'})
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
        def record(msg) -> None:
            with self._lock:
                if self.writer.closed:
                    return
                try:
                    self._record(topic, msg)
                except OSError as err:
                    self.error = f'{self.writer.path}: cannot write the bag: {err.strerror or err}'
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
            for key in ('configuration', 'data_hash', 'model', 'fidelity', 'event',
                        'master_file', 'software_version'):
                self.writer.set_custom_data(f'vd.{key}', str(getattr(msg, key)))
            self.writer.set_custom_data('vd.modified', '; '.join(
                f'{g.group}.{k.key}={k.master_value} {k.unit}'.strip()
                for g in msg.groups for k in g.modified_keys) or 'none')
        if topic not in self._qos:
            self._qos[topic] = self._offered(topic)
        self.writer.write(self._bag_topics[topic], msg, log_time(msg, time.time_ns()),
                          self._qos[topic])
        self.counts[topic] += 1
        if topic.endswith('/state'):
            key = (msg.configuration, msg.event, msg.model)
            self._samples[key] = self._samples.get(key, 0) + 1
        elif topic.endswith('/result'):
            steps = max((len(c.values) for c in msg.channels), default=0)
            if msg.model == 'vehicle':
                self._odometry_needed += steps
                self._tf_needed += steps
            elif msg.model == 'kc' and has_wheel_frames({c.name: c.values
                                                         for c in msg.channels}):
                self._tf_needed += steps  # the wheels' frames, one TF message per step
            self._pending.append(((msg.configuration, msg.event, msg.model), steps,
                                  self._odometry_needed, self._tf_needed))
        self._publish_complete()

    def _offered(self, topic: str) -> list:
        """
        Return the QoS profiles the publishers of ``topic`` offer (as discovered).

        History and depth, which discovery does not carry, are those of this recorder's
        subscription (the publishers' own profile).
        """
        own = TOPICS[topic][1]
        out = []
        for info in self.get_publishers_info_by_topic(self._bag_topics[topic]):
            q = info.qos_profile
            if q.history == HistoryPolicy.UNKNOWN or q.depth == 0:
                q.history, q.depth = own.history, own.depth
            out.append(q)
        return out or [own]

    def _publish_complete(self) -> None:
        """
        Count the results whose every step state is written too, and say so.

        For the full vehicle, every odometry and TF message too; for K&C, every TF message.
        """
        done = [p for p in self._pending
                if self._samples.get(p[0], 0) >= p[1] and self.counts[ODOMETRY_TOPIC] >= p[2]
                and self.counts[TF_TOPIC] >= p[3]]
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


def _record(executor, node: Recorder) -> None:
    """Spin until the bag is finished, then a little longer for the finish response."""
    while executor.context.ok() and not node.finished:
        executor.spin_once(timeout_sec=0.1)
    linger = time.monotonic() + FINISH_LINGER  # the finish response reaches the runner
    while executor.context.ok() and time.monotonic() < linger:
        executor.spin_once(timeout_sec=0.05)


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_events recorder``."""
    made: list[Recorder] = []

    def factory() -> Recorder:
        made.append(Recorder())
        return made[-1]

    try:
        run_node(factory, _record, args)
    except Exception as err:  # noqa: BLE001 - report a bad parameter without a traceback
        print(f'recorder: {err}', flush=True)
        raise SystemExit(2) from None
    node = made[0] if made else None
    if node is not None and node.interrupted:
        print(f"recorder: interrupted before the recording was complete: no bag written "
              f"({node.writer.path}{'' if node.error else '.partial removed'})", flush=True)
        sys.exit(1)


if __name__ == '__main__':
    main()
