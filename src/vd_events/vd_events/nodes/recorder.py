# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``ros2 run vd_events recorder``: the recorder node's process (vd_events.bags.recorder).

Exit codes: 0 once the owner finished the bag, 1 when a signal ended the recording
before (the partial bag removed), 2 for a bad parameter (an existing bag path...).
"""
from __future__ import annotations

import sys
import time

from vd_data_server.ros.node_main import run_node
from vd_events.bags.recorder import FINISH_LINGER, Recorder


def _record(executor, node: Recorder) -> None:
    """Spin until the bag is finished, then a little longer for the finish response."""
    while executor.context.ok() and not node.finished:
        executor.spin_once(timeout_sec=0.1)
    linger = time.monotonic() + FINISH_LINGER  # the finish response reaches the runner
    while executor.context.ok() and time.monotonic() < linger:
        executor.spin_once(timeout_sec=0.05)


def main(args=None) -> None:
    """Entry point of ``ros2 run vd_events recorder``."""
    made: list[Recorder] = []

    def factory() -> Recorder:
        made.append(Recorder())
        return made[-1]

    try:
        run_node(factory, _record, args)
    except Exception as err:  # noqa: BLE001 - report a bad parameter without a traceback
        print(f'recorder: {err}', flush=True)
        raise SystemExit(2) from None
    node = made[0] if made else None
    if node is not None and node.interrupted:
        print(f"recorder: interrupted before the recording was complete: no bag written "
              f"({node.writer.path}{'' if node.error else '.partial removed'})", flush=True)
        sys.exit(1)


if __name__ == '__main__':
    main()
