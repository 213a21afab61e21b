# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The distributed launch: nodes kept up, a plan driven against them, SIGTERM.

`vd launch --distributed` keeps the nodes up; `ros2 run vd_events event_runner` drives
a plan against them; SIGTERM stops everything.
"""
from __future__ import annotations

import os
from pathlib import Path
import random
import signal
import subprocess
import sys
import time

import pytest

from vdtest import HANG_GUARD

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def test_launch_and_event_runner(tmp_path, sedan_master):
    from ament_index_python.packages import get_package_prefix

    env = dict(os.environ, ROS_DOMAIN_ID=str(random.randint(216, 232)),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    plan = tmp_path / 'plan.yaml'
    plan.write_text(f"""name: er
master: {sedan_master}
runs:
  - event: handling_diagram
    models: [two_track]
    configurations: [baseline]
    parameters: [steps=5]
  - event: lateral_force
    models: [kc]
    axle: front
    configurations: [sport]
    parameters: [steps=11]
""")
    launcher = subprocess.Popen([sys.executable, '-m', 'vd_events.cli.main', 'launch',
                                 '--distributed', '--master', str(sedan_master)], env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        runner = Path(get_package_prefix('vd_events')) / 'lib' / 'vd_events' / 'event_runner'
        done = subprocess.run([str(runner), '--ros-args', '-p', f'plan:={plan}'], env=env,
                              capture_output=True, text=True, timeout=HANG_GUARD)
        assert done.returncode == 0, done.stdout + done.stderr
        log = done.stdout + done.stderr
        assert "configuration 'baseline', event 'handling_diagram': 5 steps" in log
        assert "configuration 'sport', event 'lateral_force': 11 steps" in log
    finally:
        launcher.send_signal(signal.SIGTERM)
        out, _ = launcher.communicate(timeout=HANG_GUARD)
    assert launcher.returncode == 0, out
    time.sleep(0.5)
    leftover = subprocess.run(['pgrep', '-f', f'master_file:={sedan_master}'],
                              capture_output=True, text=True)
    assert leftover.stdout == ''
