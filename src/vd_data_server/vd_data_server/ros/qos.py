# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The QoS profiles of the vd graph: one definition that every node imports.

All are ``KEEP_LAST``, ``RELIABLE``, ``TRANSIENT_LOCAL`` (latched): a node that joins
late, or whose discovery of the publisher is still settling when a message goes out,
gets it all the same. They differ in depth.

- configurations: the data server's publisher keeps exactly one message per
  configuration of the current study (its depth is the number of configurations and it
  republishes them all on every change), so a late joiner gets exactly the current
  version of every configuration; subscribers take up to ``CONFIGURATION_DEPTH``;
- data status: the last one;
- results and provenance: the last ``RESULTS_DEPTH`` per publisher;
- per-step states (and odometry, TF): the last ``STATES_DEPTH`` per publisher.
"""
from __future__ import annotations

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

#: subscriber depth for /configuration: deep enough for every configuration of a large study
CONFIGURATION_DEPTH = 1000
RESULTS_DEPTH = 100
STATES_DEPTH = 10000


def latched(depth: int) -> QoSProfile:
    """Reliable, transient-local, the last ``depth`` messages."""
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=max(1, depth),
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL)


#: subscribers of /configuration (the publisher's depth follows the study, see above)
CONFIGURATIONS = latched(CONFIGURATION_DEPTH)
#: /data_status and other topics where only the latest message counts
LATEST = latched(1)
#: results and provenance, kept for late joiners
RESULTS = latched(RESULTS_DEPTH)
#: per-step states, odometry and TF of the runs, kept for late joiners
STATES = latched(STATES_DEPTH)

#: lock-step commands: reliable, volatile, a few in flight (one per step is expected)
COMMANDS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=10,
                      reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)
#: the lock-step session's status: the latest one, latched
STATUS = latched(1)
#: /clock as ROS publishes it (rclpy's time source subscribes reliable, depth 1..10)
CLOCK = COMMANDS
