# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd launch``: start the graph and keep it running, or the lock-step pair closed loop."""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from vd_data_server.errors import DataError
from vd_events.cli import options
from vd_events.orchestration.launch import launch
from vd_events.orchestration.lockstep import run_lockstep


def cmd_launch(args: argparse.Namespace) -> int:
    if args.lockstep:
        return _launch_lockstep(args)
    return launch(Path(args.master) if args.master else None, distributed=args.distributed,
                  namespace=options.namespace(args), allow_edits=args.allow_edits,
                  solvers=args.solvers)


def _launch_lockstep(args: argparse.Namespace) -> int:
    for name, low, high in (('duration', 0.01, 3600.0), ('radius', 5.0, 1000.0),
                            ('speed', 0.5, 60.0)):
        value = getattr(args, name)
        if not low <= value <= high:
            raise DataError(f'--{name} {value:g} is outside [{low:g}, {high:g}]')
    if args.distributed:
        raise DataError('--lockstep runs embedded; for separate processes start '
                        'vehicle_solver (mode:=lockstep) and path_follower (docs/ros-api.md)')
    master, study = options.study(args.master)
    if args.config and args.config not in study.configurations:
        raise DataError(f"configuration '{args.config}' is not in the study "
                        f"(configurations: {', '.join(study.configuration_names)})")
    out = run_lockstep(configuration=args.config, master=master, duration=args.duration,
                       radius=args.radius, speed=args.speed,
                       bag=Path(args.bag) if args.bag else None)
    if args.json:
        print(json.dumps(out.to_json()))
    else:
        print(f'lock-step {out.status}; {out.steps} steps in {out.wall:.1f} s '
              f'({out.steps_per_second:.0f} steps/s)' + (f'; bag: {out.bag}' if out.bag else ''))
    return 0 if out.status.startswith('finished') else 1


__all__ = ['cmd_launch']
