# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
One ``/clock`` owner per ROS domain.

Two lock-step vehicles in one domain: the second one on the same clock refuses, naming
the node and namespace that own it; on a clock of its own (a remapping) it runs beside
the first, and ``/clock`` keeps a single publisher whose time never goes back.
"""
from __future__ import annotations

import pytest

from vdtest import wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _vehicle(master, namespace: str, clock: str | None = None):
    from rclpy.parameter import Parameter

    from vd_solvers.nodes.vehicle import VehicleSolver

    values = {'mode': 'lockstep', 'master': str(master), 'initial_speed': 5.0,
              'start_timeout': 600.0}
    cli = ['--ros-args', '-r', f'/clock:={clock}'] if clock else None
    return VehicleSolver(namespace=namespace, cli_args=cli, parameter_overrides=[
        Parameter(k, value=v) for k, v in values.items()])


def test_a_second_session_on_the_same_clock_refuses_naming_its_owner(ros_domain,
                                                                      sedan_master):
    first = _vehicle(sedan_master, '/car1')
    try:
        with pytest.raises(ValueError) as err:
            _vehicle(sedan_master, '/car2')
    finally:
        first.destroy_node()
    assert str(err.value) == (
        '/clock is already published by /car1/vehicle_solver (namespace /car1): one /clock '
        'owner per ROS domain. Give this session a clock of its own (--ros-args -r '
        '/clock:=/car2/clock, or lockstep.launch.py clock_topic:=/car2/clock, and the same '
        'remapping for its controller) or another ROS_DOMAIN_ID')


def test_a_second_session_on_its_own_clock_runs_beside_the_first(ros_domain, sedan_master):
    import rclpy
    from rosgraph_msgs.msg import Clock

    from vd_data_server.ros.qos import CLOCK, COMMANDS
    from vd_interfaces.msg import VehicleCommand

    first = _vehicle(sedan_master, '/car1')
    second = _vehicle(sedan_master, '/car2', clock='/car2/clock')
    probe = rclpy.create_node('clock_probe')
    clocks: dict[str, list[int]] = {'/clock': [], '/car2/clock': []}
    nodes = [first, second, probe]
    try:
        for topic, stamps in clocks.items():
            probe.create_subscription(Clock, topic, lambda m, s=stamps: s.append(
                m.clock.sec * 10**9 + m.clock.nanosec), CLOCK)
        assert first.lockstep.clock_pub.topic_name == '/clock'
        assert second.lockstep.clock_pub.topic_name == '/car2/clock'
        pubs = {ns: probe.create_publisher(VehicleCommand, f'{ns}/vehicle/command', COMMANDS)
                for ns in ('/car1', '/car2')}
        assert wait_for(nodes, lambda: all(p.get_subscription_count() for p in pubs.values()))
        # the second car runs three steps ahead of the first: on one clock that would be
        # a jump back and forth; on two clocks each one only goes forward
        sessions = {'/car1': first.lockstep, '/car2': second.lockstep}
        for ns, steps in (('/car2', 3), ('/car1', 1), ('/car2', 4), ('/car1', 2)):
            session = sessions[ns]
            while session.stepper.step < steps:
                msg = VehicleCommand()
                msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(session.now_ns, 10**9)
                pubs[ns].publish(msg)
                target = session.stepper.step + 1
                assert wait_for(nodes, lambda s=session, t=target: s.stepper.step >= t)
        assert wait_for(nodes, lambda: clocks['/clock'] and clocks['/clock'][-1] == 2 * 5_000_000
                        and clocks['/car2/clock'][-1] == 4 * 5_000_000)
        # one publisher on /clock: the first car's (its node's name is checked where the
        # second session is refused; the graph's names of a participant's publishers can
        # stay '_NODE_NAME_UNKNOWN_' after many nodes came and went in one process)
        assert wait_for(nodes, lambda: probe.count_publishers('/clock') == 1)
        assert probe.count_publishers('/car2/clock') == 1
    finally:
        for node in nodes:
            node.destroy_node()
    for stamps in clocks.values():
        assert stamps == sorted(stamps)  # repeats while waiting, never a step back
