"""The standard ``main()`` of a vd node (ros2/examples style), shared by the packages."""
from __future__ import annotations

from collections.abc import Callable
import os
import signal

import rclpy
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.node import Node

#: set by a parent that starts nodes as its children (``vd run --distributed``): its pid
PARENT_ENV = 'VD_PARENT_PID'


def die_with_parent() -> None:
    """
    A child node of a ``vd`` run ends with its parent, even after ``kill -9``.

    Linux delivers SIGTERM to this process when the parent dies (prctl
    PR_SET_PDEATHSIG); SIGTERM is a node's clean shutdown. A parent that died
    before this call is caught by comparing the parent pid.
    """
    parent = os.environ.get(PARENT_ENV)
    if not parent:
        return
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        pr_set_pdeathsig = 1
        libc.prctl(pr_set_pdeathsig, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):  # not Linux: the parent's own cleanup must do
        return
    if str(os.getppid()) != parent:
        os.kill(os.getpid(), signal.SIGTERM)


def spin_guarded(executor, node: Node) -> None:
    """
    Spin until shutdown; a callback that fails (a bug the input triggered) is logged
    and the node keeps serving instead of dying with it.
    """
    while rclpy.ok(context=executor.context):
        try:
            executor.spin_once(timeout_sec=0.5)
        except (KeyboardInterrupt, ExternalShutdownException):
            raise
        except Exception as err:  # noqa: BLE001 - the node boundary
            node.get_logger().error(f'a callback failed: {type(err).__name__}: {err}')


def spin_node(factory: Callable[[], Node], args=None, threads: int = 2) -> None:
    """init, build the node, spin; a clean shutdown on Ctrl-C and SIGTERM."""
    die_with_parent()
    rclpy.init(args=args)
    node = None
    try:
        node = factory()
        executor = MultiThreadedExecutor(num_threads=threads)
        executor.add_node(node)
        spin_guarded(executor, node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
