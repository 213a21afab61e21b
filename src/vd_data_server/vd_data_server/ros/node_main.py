# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The standard ``main()`` of a vd node (ros2/examples style), shared by the packages."""
from __future__ import annotations

from collections.abc import Callable, Sequence
import os
import signal
import threading

import rclpy
from rclpy.executors import (
    Executor,
    ExternalShutdownException,
    MultiThreadedExecutor,
    SingleThreadedExecutor,
)
from rclpy.node import Node

#: set by a parent that starts nodes as its children (``vd run --distributed``): its pid
PARENT_ENV = 'VD_PARENT_PID'


def die_with_parent() -> None:
    """
    End this node process with its ``vd`` parent, even after ``kill -9``.

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
    Spin until shutdown; a failing callback is logged and the node keeps serving.

    A callback that fails (a bug the input triggered) does not kill the node.
    """
    while rclpy.ok(context=executor.context):
        try:
            executor.spin_once(timeout_sec=0.5)
        except (KeyboardInterrupt, ExternalShutdownException):
            raise
        except Exception as err:  # noqa: BLE001 - the node boundary
            node.get_logger().error(f'a callback failed: {type(err).__name__}: {err}')


def make_executor(threads: int = 1, context=None):
    """
    Return a single-threaded executor for one thread, else a multi-threaded one.

    A solver needs two threads (its execute callback runs while goal, cancel and
    configuration callbacks are served); the data server needs one.
    """
    if threads <= 1:
        return SingleThreadedExecutor(context=context)
    return MultiThreadedExecutor(num_threads=threads, context=context)


def quiet_teardown(nodes: Sequence[Node], context=None) -> None:
    """
    Destroy ``nodes`` and shut rclpy down; further SIGINT/SIGTERM are ignored meanwhile.

    A Ctrl-C on a terminal (and ``ros2 launch``) signals the whole process group, so a
    node often gets SIGINT twice: the first ends the spin, the second must not
    interrupt the teardown with a traceback.
    """
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, signal.SIG_IGN)
    for node in nodes:
        node.destroy_node()
    rclpy.try_shutdown(context=context)


def run_node(factory: Callable[[], Node], body: Callable | None = None, args=None,
             threads: int = 1, executor: Callable[[Node], Executor] | None = None):
    """
    Run one node the ros2/examples way; return what ``body(executor, node)`` returns.

    ``rclpy.init``, build the node, ``body`` (default: spin until shutdown), and on every
    end (Ctrl-C, SIGTERM, an exception of ``body``) a clean teardown. A Ctrl-C or SIGTERM
    returns None, also when it shut the context down in the middle of a spin. Exceptions
    of ``factory`` and ``body`` other than these propagate after the teardown.
    ``executor(node)``, if given, makes the executor (default: :func:`make_executor` with
    ``threads``).
    """
    die_with_parent()
    rclpy.init(args=args)
    node = None
    try:
        node = factory()
        spinner = executor(node) if executor is not None else make_executor(threads)
        spinner.add_node(node)
        return (body or spin_guarded)(spinner, node)
    except (KeyboardInterrupt, ExternalShutdownException):
        return None
    except Exception:
        # a SIGTERM shuts the context down under a spin that is building its wait set
        # ("the given context is not valid"): that is the signal's clean end, not an error
        if not rclpy.ok():
            return None
        raise
    finally:
        quiet_teardown([node] if node is not None else [])


def spin_node(factory: Callable[[], Node], args=None, threads: int = 2) -> None:
    """Build the node and spin it; a clean shutdown on Ctrl-C (once or twice) and SIGTERM."""
    run_node(factory, args=args, threads=threads)
