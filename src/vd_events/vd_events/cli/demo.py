# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``make demo``: the bundled sample study end to end.

1. The data server serves the sample sedan study; its feedback (the thesis'
   overview tab) is printed as received over ROS.
2. The demo plan runs the K&C, bicycle and two-track models on every configuration
   (``vd study``: in-process, the solver nodes' code without a graph), one MCAP bag per run.
3. The capability study runs every K&C event rigid and flexible on ``baseline`` and
   says, per axle, which events need the flexible model; the report holds it all.
Everything goes to ``out/demo/`` (replaced on each run).
"""
from __future__ import annotations

from pathlib import Path
import shutil
import sys
import time

from ament_index_python.packages import get_package_share_directory

from vd_data_server.overview import console, print_status
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_events.reports.display import summary as run_summary
from vd_events.reports.report import build_pages
from vd_events.studies.capability import run_study
from vd_events.studies.plan import expand, load_plan, run_plan

OUT = Path('out/demo')
def _plan_path() -> Path:

    return Path(get_package_share_directory('vd_events')) / 'plans' / 'demo.yaml'


def main() -> int:

    term = console()
    t0 = time.perf_counter()
    master = default_master()
    term.rule('vd demo: the data (data server feedback)')
    print_status(load_study(master), term)
    if OUT.exists():
        shutil.rmtree(OUT)
    term.rule('vd demo: K&C, bicycle and two-track models')
    plan = load_plan(_plan_path())
    total = len(expand(plan, load_study(master), OUT / 'bags'))
    count = [0]

    def done(run) -> None:
        """One line per run as it completes: a log or CI sees the progress too."""
        count[0] += 1
        r = run.request
        status = run.error or run_summary(run.outcome.metrics)
        term.print(f"  [{count[0]:>2}/{total}] "
                   f"{r.configuration:<11} {r.event:<22} "
                   f"{r.model + (' ' + r.axle if r.axle else ''):<10} {status}", soft_wrap=True)

    summary = run_plan(plan, OUT / 'bags', OUT, on_done=done)
    term.rule('vd demo: rigid vs flexible K&C, the analytical capability of the models')
    study = load_study(master)
    count[0] = 0

    def ran(run) -> None:
        count[0] += 1
        r = run.request
        term.print(f"  [{count[0]:>2}] {r.configuration:<11} {r.event:<22} kc {r.axle:<5} "
                   f"{r.fidelity:<8} {run.error or 'done'}", soft_wrap=True)

    tables = run_study(master, study, 'baseline', ['front', 'rear'], OUT / 'capability',
                       on_done=ran)
    for table in tables:
        needs = sorted({c.event for c in table.cells if c.verdict == 'Flexible'})
        term.print(f"  baseline    {table.axle:<5} flexible ({', '.join(table.components)}) "
                   f"needed for: {', '.join(needs) or 'none'}", soft_wrap=True)
    bags = [Path(b) for b in summary['finished']]
    bags += sorted((OUT / 'capability').glob('capability_*'))
    summary.update(build_pages(bags, OUT))
    term.print(f"\nbags:   {summary['bags']} ({len(summary['runs'])} runs)")
    term.print(f"report: {summary['report']}")
    term.print(f"study report (one self-contained file): {summary['study_report']}")
    term.print(f'done in {time.perf_counter() - t0:.1f} s')
    return 1 if summary['errors'] else 0


if __name__ == '__main__':
    sys.exit(main())
