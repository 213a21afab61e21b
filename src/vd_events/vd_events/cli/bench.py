# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd bench``: the benchmark suite (``make bench``), printed or as JSON."""
from __future__ import annotations

import argparse
import json

from vd_events.bench.suite import print_bench, run_bench


def cmd_bench(args: argparse.Namespace) -> int:
    results = run_bench()
    if args.json:
        print(json.dumps(results, indent=2))
    else:
        print_bench(results)
    return 0


__all__ = ['cmd_bench']
