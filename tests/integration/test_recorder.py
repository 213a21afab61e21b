"""The recorder process closes its bag cleanly on SIGTERM and SIGINT: a finished bag with
what it received, never a bag that only looks finished."""
from __future__ import annotations

import os
import signal
import subprocess

import pytest

from vdtest import spin_until

pytestmark = [pytest.mark.ros, pytest.mark.slow]


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_recorder_closes_the_bag_on_signal(ros_domain, tmp_path, sig):
    from ament_index_python.packages import get_package_prefix
    from rclpy.node import Node
    from vd_interfaces.msg import Sample

    from vd_events.bag import read_bag
    from vd_solvers.solver_node import SAMPLES

    exe = os.path.join(get_package_prefix("vd_events"), "lib", "vd_events", "recorder")
    bag = tmp_path / "bag"
    env = dict(os.environ, ROS_DOMAIN_ID=str(ros_domain))
    proc = subprocess.Popen([exe, "--ros-args", "-p", f"bag:={bag}"], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    node = Node("sample_publisher")
    try:
        pub = node.create_publisher(Sample, "/vd/kc/state", SAMPLES)
        assert spin_until([node], lambda: pub.get_subscription_count() >= 1, timeout=20.0)
        stamp = node.get_clock().now().to_msg()
        for step in range(3):
            msg = Sample(event="e", configuration="c", model="kc", step=step, names=["x"],
                         values=[float(step)])
            msg.header.stamp = stamp
            pub.publish(msg)
        spin_until([node], lambda: False, timeout=1.0)
        proc.send_signal(sig)
        out, _ = proc.communicate(timeout=20)
    finally:
        node.destroy_node()
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, out
    assert (bag / "metadata.yaml").is_file()
    assert not (tmp_path / "bag.partial").exists()
    steps = [m.msg.step for m in read_bag(bag) if m.topic == "/vd/kc/state"]
    assert steps == [0, 1, 2]


def test_recorder_refuses_an_existing_bag(ros_domain, tmp_path):
    from ament_index_python.packages import get_package_prefix

    exe = os.path.join(get_package_prefix("vd_events"), "lib", "vd_events", "recorder")
    bag = tmp_path / "bag"
    bag.mkdir()
    done = subprocess.run([exe, "--ros-args", "-p", f"bag:={bag}"], capture_output=True,
                          text=True, timeout=30,
                          env=dict(os.environ, ROS_DOMAIN_ID=str(ros_domain)))
    assert done.returncode == 2
    assert f"recorder: {bag}: bag path already exists (choose another --bag)" in done.stdout
    assert list(bag.iterdir()) == []
