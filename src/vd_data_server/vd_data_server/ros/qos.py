# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The QoS profiles of the vd graph: one definition that every node imports.

What the ROS tools expect (tf2, RViz, Foxglove, ``ros2 topic echo``, ``ros2 bag``):

- **latched** (``RELIABLE``, ``TRANSIENT_LOCAL``): what a node that joins late must still
  get -- configurations, the data status, results and provenance, the lock-step status,
  ``robot_description``. The data server's configuration publisher keeps exactly one
  message per configuration of the current study (its depth is the number of
  configurations and it republishes them all on every change), so a late joiner gets
  exactly the current version of every configuration; subscribers take up to
  ``CONFIGURATION_DEPTH``;
- **per-step streams** (``RELIABLE``, ``VOLATILE``, bounded depth): states, odometry,
  ``joint_states``: a late ``ros2 topic echo`` starts with the next step instead of
  replaying a finished run. The recorder rebuilds the states of a run from its latched
  result, so it never depends on catching the stream;
- ``/tf`` and ``/tf_static`` as tf2's broadcasters offer them (``tf2_ros/qos.hpp``):
  ``/tf`` reliable, volatile, depth 100; ``/tf_static`` reliable, transient_local, depth 1;
- inputs (commands, ``/clock``) reliable, volatile; a rig's ``JointState`` is taken best
  effort, volatile, which matches every publisher: default QoS (``ros2 topic pub``,
  ``joint_state_broadcaster``), sensor-data QoS and the latched profiles.
"""
from __future__ import annotations

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

#: subscriber depth for /configuration: deep enough for every configuration of a large study
CONFIGURATION_DEPTH = 1000
RESULTS_DEPTH = 100
#: per-step streams: a run's burst of states is published at once, so the writer keeps
#: enough of them in flight for a slow reader (a volatile history, not a replay)
STATES_DEPTH = 1000
#: tf2's own depths (tf2_ros DynamicBroadcasterQoS / StaticBroadcasterQoS)
TF_DEPTH = 100


def latched(depth: int) -> QoSProfile:
    """Reliable, transient-local, the last ``depth`` messages."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=max(1, depth),
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL)


def stream(depth: int) -> QoSProfile:
    """Reliable, volatile, the last ``depth`` messages in flight."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=max(1, depth),
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)


#: subscribers of /configuration (the publisher's depth follows the study, see above)
CONFIGURATIONS = latched(CONFIGURATION_DEPTH)
#: /data_status and other topics where only the latest message counts
LATEST = latched(1)
#: results and provenance, kept for late joiners
RESULTS = latched(RESULTS_DEPTH)
#: per-step states, odometry and joint states: a stream, not kept for late joiners
STATES = stream(STATES_DEPTH)
#: /tf: volatile, as tf2's TransformBroadcaster and TransformListener
TF = stream(TF_DEPTH)
#: /tf_static and robot_description: latched, the last one
TF_STATIC = latched(1)

#: commands (VehicleCommand, AckermannDriveStamped, Twist): reliable, volatile, a few in
#: flight (one per step is expected)
COMMANDS = stream(10)
#: the lock-step session's status: the latest one, latched
STATUS = latched(1)
#: /clock as ROS publishes it (rclpy's time source subscribes reliable, depth 1..10)
CLOCK = COMMANDS
#: a rig's samples: best effort + volatile matches reliable and best-effort publishers,
#: volatile and transient_local ones alike; deep enough for a burst
RIG_INPUT = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=STATES_DEPTH,
                       reliability=ReliabilityPolicy.BEST_EFFORT,
                       durability=DurabilityPolicy.VOLATILE)


def profile_of(topic: str) -> QoSProfile:
    """
    Return the profile vd's publishers offer on ``topic`` (a name, relative or absolute).

    What a bag records for a topic written without a live publisher (``vd capability``,
    imported measurements, the lock-step bag before discovery), so ``ros2 bag play``
    latches what the live graph latches.
    """
    leaf = topic.rstrip('/').rsplit('/', 1)[-1]
    if topic.rstrip('/') in ('/tf', 'tf'):
        return TF
    if leaf in ('tf_static', 'robot_description'):
        return TF_STATIC
    if leaf in ('clock', 'command', 'ackermann_cmd', 'cmd_vel'):
        return COMMANDS
    if leaf in ('result', 'provenance', 'table'):
        return RESULTS
    if leaf == 'configuration':
        return CONFIGURATIONS
    if leaf in ('data_status', 'lockstep_status', 'recorded'):
        return LATEST
    return STATES
