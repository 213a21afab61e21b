"""
``ros2 run vd_events recorder``: records vd topics to an MCAP bag.

The role ``ros2 bag record`` plays (which pip-installed ROS lacks). Parameter
``bag``: the bag directory to create (refused if it exists). The bag is
written under ``<bag>.partial`` and becomes ``<bag>`` only when its owner says
the recording is complete: the service ``~/finish`` (std_srvs/Trigger, called by
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
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger

from tf2_msgs.msg import TFMessage
from vd_data_server.node_main import die_with_parent
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
from vd_solvers.conversions import TIME_AXIS
from vd_solvers.solver_node import LATCHED, SAMPLES

# the publishers' own profiles: latched data, results and samples kept for late joiners
_LATCHED = LATCHED
_STREAM = SAMPLES
#: where the recorder says how many event results it has written completely (latched)
RECORDED_TOPIC = '/vd/recorder/recorded'

#: the full vehicle's pose, one message per recorded step (odometry and TF)
ODOMETRY_TOPIC = '/vd/vehicle/odom'
TF_TOPIC = '/tf'
#: seconds the recorder process stays up after ~/finish, for its response to be delivered
FINISH_LINGER = 0.3

#: topic -> (type, QoS) recorded by default
TOPICS = {
    '/vd/configuration': (Configuration, _LATCHED),
    '/vd/data_status': (DataStatus, _LATCHED),
    '/vd/provenance': (Provenance, _STREAM),
    '/vd/steady_state/result': (EventResult, _STREAM),
    '/vd/steady_state/state': (AnalyticalState, _STREAM),
    '/vd/kc/result': (EventResult, _STREAM),
    '/vd/kc/state': (KcState, _STREAM),
    '/vd/vehicle/result': (EventResult, _STREAM),
    '/vd/vehicle/state': (VehicleState, _STREAM),
    ODOMETRY_TOPIC: (Odometry, _STREAM),
    TF_TOPIC: (TFMessage, _STREAM),
}


_LATCHED_ONE = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1,
                          reliability=ReliabilityPolicy.RELIABLE,
                          durability=DurabilityPolicy.TRANSIENT_LOCAL)


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
    def __init__(self, bag: str | None = None, **kwargs) -> None:
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
        self.writer = BagWriter(path, {'vd.recorder': 'vd_events recorder'})
        self.counts: dict[str, int] = dict.fromkeys(TOPICS, 0)
        # runs stamped before this recorder started are not its own: on the time axis of
        # this process they end at or before TIME_AXIS.end(), which may lie ahead of the
        # wall clock after time-domain runs (their history stays latched in the solvers)
        self.start = max(self.get_clock().now().nanoseconds, TIME_AXIS.end() + 1)
        self._samples: dict[tuple[str, str, str], int] = {}
        self._qos: dict[str, list] = {}  # topic -> the offered QoS recorded in the bag
        self._pending: list[tuple[tuple[str, str, str], int, int]] = []
        self._odometry_needed = 0  # odometry messages the full-vehicle results so far bring
        self.complete = 0  # results written together with all their step samples
        self.error: str | None = None  # a write failed (full disk...): the bag is dropped
        self.finished = False
        # in-process runs spin this node on a multi-threaded executor while the runner
        # stops it from its own thread: writes and close never overlap
        self._lock = threading.Lock()
        try:
            self.create_service(Trigger, '~/finish', self._finish)
            self.recorded_pub = self.create_publisher(UInt32, RECORDED_TOPIC, _LATCHED_ONE)
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
        if topic == '/vd/configuration':
            name = msg.name
        if self.only and name is not None and name not in self.only:
            return
        stamp = _stamp_ns(msg)
        if stamp is not None and stamp < self.start:
            return  # kept by a solver from an earlier run: not this recording's
        if topic == '/vd/provenance':
            for key in ('configuration', 'data_hash', 'model', 'fidelity', 'event',
                        'master_file', 'software_version'):
                self.writer.set_custom_data(f'vd.{key}', str(getattr(msg, key)))
            self.writer.set_custom_data('vd.modified', '; '.join(
                f'{g.group}.{k.key}={k.master_value} {k.unit}'.strip()
                for g in msg.groups for k in g.modified_keys) or 'none')
        if topic not in self._qos:
            self._qos[topic] = self._offered(topic)
        self.writer.write(topic, msg, log_time(msg, time.time_ns()), self._qos[topic])
        self.counts[topic] += 1
        if topic.endswith('/state'):
            key = (msg.configuration, msg.event, msg.model)
            self._samples[key] = self._samples.get(key, 0) + 1
        elif topic.endswith('/result'):
            steps = max((len(c.values) for c in msg.channels), default=0)
            if msg.model == 'vehicle':
                self._odometry_needed += steps
            self._pending.append(((msg.configuration, msg.event, msg.model), steps,
                                  self._odometry_needed))
        self._publish_complete()

    def _offered(self, topic: str) -> list:
        """
        Return the QoS profiles the publishers of ``topic`` offer (as discovered).

        History and depth, which discovery does not carry, are those of this recorder's
        subscription (the publishers' own profile).
        """
        own = TOPICS[topic][1]
        out = []
        for info in self.get_publishers_info_by_topic(topic):
            q = info.qos_profile
            if q.history == HistoryPolicy.UNKNOWN or q.depth == 0:
                q.history, q.depth = own.history, own.depth
            out.append(q)
        return out or [own]

    def _publish_complete(self) -> None:
        """
        Count the results whose every step state is written too, and say so.

        For the full vehicle, every odometry message too.
        """
        odometry = min(self.counts[ODOMETRY_TOPIC], self.counts[TF_TOPIC])
        done = [p for p in self._pending
                if self._samples.get(p[0], 0) >= p[1] and odometry >= p[2]]
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


def main(args=None) -> None:
    die_with_parent()
    rclpy.init(args=args)
    node = None
    interrupted = False
    try:
        node = Recorder()
        while rclpy.ok() and not node.finished:
            rclpy.spin_once(node, timeout_sec=0.1)
        linger = time.monotonic() + FINISH_LINGER  # the finish response reaches the runner
        while rclpy.ok() and time.monotonic() < linger:
            rclpy.spin_once(node, timeout_sec=0.05)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as err:  # noqa: BLE001 - report a bad parameter without a traceback
        print(f'recorder: {err}', flush=True)
        raise SystemExit(2) from None
    finally:
        # first of all, whatever ended the recording: no unfinished bag may stay
        if node is not None and not node.finished:
            node.abort()
            interrupted = True
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    if interrupted:
        print(f"recorder: interrupted before the recording was complete: no bag written "
              f"({node.writer.path}{'' if node.error else '.partial removed'})", flush=True)
        sys.exit(1)


if __name__ == '__main__':
    main()
