"""``ros2 run vd_events recorder``: records vd topics to an MCAP bag.

The role ``ros2 bag record`` plays (which pip-installed ROS lacks). Parameter
``bag``: the bag directory to create (refused if it exists). The bag is
written under ``<bag>.partial`` and renamed when the node stops (Ctrl-C,
SIGTERM or ``stop()``); the run's provenance goes into the bag's metadata.
"""
from __future__ import annotations

import time

import rclpy
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from nav_msgs.msg import Odometry
from std_msgs.msg import UInt32
from vd_interfaces.msg import (Configuration, DataStatus, EventResult, Provenance, Sample,
                               VehicleState)

from vd_events.bag import BagWriter
from vd_solvers.solver_node import LATCHED, SAMPLES

# the publishers' own profiles: latched data, results and samples kept for late joiners
_LATCHED = LATCHED
_STREAM = SAMPLES
#: where the recorder says how many event results it has written completely (latched)
RECORDED_TOPIC = "/vd/recorder/recorded"

#: the full vehicle's pose, one message per recorded step
ODOMETRY_TOPIC = "/vd/vehicle/odom"
#: topic -> (type, QoS) recorded by default
TOPICS = {
    "/vd/configuration": (Configuration, _LATCHED),
    "/vd/data_status": (DataStatus, _LATCHED),
    "/vd/provenance": (Provenance, _STREAM),
    "/vd/steady_state/result": (EventResult, _STREAM),
    "/vd/steady_state/state": (Sample, _STREAM),
    "/vd/kc/result": (EventResult, _STREAM),
    "/vd/kc/state": (Sample, _STREAM),
    "/vd/vehicle/result": (EventResult, _STREAM),
    "/vd/vehicle/state": (VehicleState, _STREAM),
    ODOMETRY_TOPIC: (Odometry, _STREAM),
}


_LATCHED_ONE = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1,
                          reliability=ReliabilityPolicy.RELIABLE,
                          durability=DurabilityPolicy.TRANSIENT_LOCAL)


def _stamp_ns(msg) -> int | None:
    """The stamp of a result, sample or provenance message (None for data topics)."""
    stamp = getattr(msg, "stamp", None)
    if stamp is None and hasattr(msg, "header"):
        stamp = msg.header.stamp
    if stamp is None or isinstance(msg, (Configuration, DataStatus)):
        return None
    return stamp.sec * 1_000_000_000 + stamp.nanosec


class Recorder(Node):
    def __init__(self, bag: str | None = None, **kwargs) -> None:
        super().__init__("recorder", **kwargs)
        self.declare_parameter("bag", bag or "", ParameterDescriptor(
            description="bag directory to create", read_only=True))
        self.declare_parameter("configurations", [""], ParameterDescriptor(
            description="record only these configurations ('' = all)", read_only=True))
        path = self.get_parameter("bag").value
        if not path:
            raise ValueError("parameter 'bag' is required (the bag directory to create)")
        wanted = [c for c in self.get_parameter("configurations").value if c]
        self.only = set(wanted)
        self.writer = BagWriter(path, {"vd.recorder": "vd_events recorder"})
        self.counts: dict[str, int] = {topic: 0 for topic in TOPICS}
        self.start = self.get_clock().now().nanoseconds
        self._samples: dict[tuple[str, str, str], int] = {}
        self._pending: list[tuple[tuple[str, str, str], int, int]] = []
        self._odometry_needed = 0  # odometry messages the full-vehicle results so far bring
        self.complete = 0  # results written together with all their step samples
        self.recorded_pub = self.create_publisher(UInt32, RECORDED_TOPIC, _LATCHED_ONE)
        for topic, (msg_type, qos) in TOPICS.items():
            self.create_subscription(msg_type, topic, self._callback(topic), qos)
        self.get_logger().info(f"recording to {path}")

    def _callback(self, topic: str):
        def record(msg) -> None:
            if self.writer.closed:
                return
            name = getattr(msg, "configuration", None)
            if topic == "/vd/configuration":
                name = msg.name
            if self.only and name is not None and name not in self.only:
                return
            stamp = _stamp_ns(msg)
            if stamp is not None and stamp < self.start:
                return  # kept by a solver from an earlier run: not this recording's
            if topic == "/vd/provenance":
                for key in ("configuration", "data_hash", "model", "fidelity", "event",
                            "master_file", "software_version"):
                    self.writer.set_custom_data(f"vd.{key}", str(getattr(msg, key)))
                self.writer.set_custom_data("vd.modified", "; ".join(
                    f"{g.group}.{k.key}={k.master_value} {k.unit}".strip()
                    for g in msg.groups for k in g.modified_keys) or "none")
            self.writer.write(topic, msg, time.time_ns())
            self.counts[topic] += 1
            if topic.endswith("/state"):
                key = (msg.configuration, msg.event, msg.model)
                self._samples[key] = self._samples.get(key, 0) + 1
            elif topic.endswith("/result"):
                steps = max((len(c.values) for c in msg.channels), default=0)
                if msg.model == "vehicle":
                    self._odometry_needed += steps
                self._pending.append(((msg.configuration, msg.event, msg.model), steps,
                                      self._odometry_needed))
            self._publish_complete()
        return record

    def _publish_complete(self) -> None:
        """Count the results whose every step sample (and, for the full vehicle, every
        odometry message) is written too, and say so."""
        odometry = self.counts[ODOMETRY_TOPIC]
        done = [p for p in self._pending
                if self._samples.get(p[0], 0) >= p[1] and odometry >= p[2]]
        if done:
            self._pending = [p for p in self._pending if p not in done]
            self.complete += len(done)
            self.recorded_pub.publish(UInt32(data=self.complete))

    def stop(self):
        """Close the bag (renaming it to its final name) and return its path."""
        return self.writer.close()

    def abort(self) -> None:
        self.writer.abort()


def main(args=None) -> None:
    rclpy.init(args=args)
    node = None
    try:
        node = Recorder()
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as err:  # noqa: BLE001 - report a bad parameter without a traceback
        print(f"recorder: {err}")
        raise SystemExit(2) from None
    finally:
        if node is not None:
            node.stop()
            node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
