# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd study PLAN`` and ``vd report BAG...``: many runs, and the report pages of bags."""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from vd_events.cli import options
from vd_events.reports.report import build_pages
from vd_events.studies.plan import load_plan, run_plan


def cmd_study(args: argparse.Namespace) -> int:
    plan = load_plan(Path(args.plan))
    out = Path(args.report) if args.report else Path('out') / plan.name
    bags = Path(args.bag) if args.bag else out / 'bags'
    progress = options.progress_bar(args)
    summary = options.with_progress(progress, lambda: run_plan(
        plan, bags, out, distributed=args.distributed, progress=progress,
        namespace=options.namespace(args)))
    pages = build_pages([Path(b) for b in summary['finished']], out) if summary['finished'] \
        else {'report': None, 'study_report': None}
    summary.update(pages)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(f"report: {summary['report']}")
        print(f"study report (one self-contained file): {summary['study_report']}")
        print(f"bags:   {summary['bags']}")
    return 0 if not summary['errors'] else 1


def cmd_report(args: argparse.Namespace) -> int:
    pages = build_pages([Path(b) for b in args.bags], Path(args.out))
    print(f"report: {pages['report']}")
    print(f"study report (one self-contained file): {pages['study_report']}")
    return 0


__all__ = ['cmd_study', 'cmd_report']
