# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``ros2 run vd_events path_follower``: the example controller's process."""
from __future__ import annotations

from rclpy.experimental import EventsExecutor

from vd_data_server.ros.node_main import run_node
from vd_events.orchestration.path_follower import PathFollower


def main(args=None) -> None:
    """
    Spin the controller on the events executor until Ctrl-C or SIGTERM.

    Through ``run_node``'s ``spin_once`` loop: the EventsExecutor's own ``spin()``
    polls without blocking in this rclpy and keeps a core busy while waiting.
    """
    run_node(PathFollower, args=args, executor=lambda node: EventsExecutor())


if __name__ == '__main__':
    main()
