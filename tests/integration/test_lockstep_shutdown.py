# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A running vehicle_solver stops cleanly on SIGINT (as ``ros2 launch`` and a terminal send it).

In every mode, with the session running (free mode: its step timer firing as the signal
ends the context), the process exits 0 without a FATAL log or a traceback.
"""
from __future__ import annotations

import os
import signal
import subprocess
import time

import pytest

from vdtest import HANG_GUARD, wait_for

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _exe() -> str:
    from ament_index_python.packages import get_package_prefix

    return os.path.join(get_package_prefix('vd_solvers'), 'lib', 'vd_solvers', 'vehicle_solver')


@pytest.mark.parametrize('mode', ['lockstep', 'free', 'events'])
def test_sigint_stops_the_vehicle_solver_cleanly(ros_domain, sedan_master, mode):
    proc = subprocess.Popen([_exe(), '--ros-args', '-p', f'mode:={mode}', '-p',
                             f'master:={sedan_master}'] if mode != 'events' else
                            [_exe(), '--ros-args', '-r', '__ns:=/sig'],
                            env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    lines = []
    deadline = time.monotonic() + HANG_GUARD
    assert proc.stdout is not None
    if mode != 'events':  # the session is up: its timers run
        while time.monotonic() < deadline:
            line = proc.stdout.readline()
            if not line:
                break
            lines.append(line)
            if 'co-simulation' in line:
                break
    else:  # the node is up: its signal handlers are installed
        import rclpy

        probe = rclpy.create_node('sigint_probe')
        try:
            # the odometry publisher: made after the node's own and lifecycle services
            assert wait_for([probe], lambda: probe.count_publishers('/sig/vehicle/odom') > 0)
        finally:
            probe.destroy_node()
    t0 = time.monotonic()
    os.killpg(proc.pid, signal.SIGINT)
    time.sleep(0.05)
    try:
        os.killpg(proc.pid, signal.SIGINT)  # a terminal's Ctrl-C and ros2 launch: twice
    except ProcessLookupError:
        pass
    out, _ = proc.communicate(timeout=HANG_GUARD)
    took = time.monotonic() - t0
    text = ''.join(lines) + out
    assert proc.returncode == 0, text
    assert 'FATAL' not in text and 'Traceback' not in text, text
    print(f'{mode}: stopped {took:.2f} s after SIGINT')
