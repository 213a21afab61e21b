# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The README's main command, end to end: ``make demo`` runs its plan and says so line by line.

``python -m vd_events.cli.demo`` (what ``make demo`` runs after setup) in a fresh folder, with
stdout a pipe as in a log or CI: it must finish with exit 0, print each run's line as the
run completes, leave a bag per run and the report, and print every line the README
quotes from it (the sample car's numbers in the README come from this run).
"""
from __future__ import annotations

import os
from pathlib import Path
import re
import subprocess
import sys

import pytest

pytestmark = [pytest.mark.ros, pytest.mark.slow]

README = Path(__file__).resolve().parents[2] / 'README.md'
RUN_LINE = re.compile(r'^\s+\[\s*(\d+)/(\d+)\] (.*)$')


def _readme_demo_lines() -> list[str]:
    """Return the run lines of the README's demo output block (whitespace folded)."""
    text = README.read_text(encoding='utf-8')
    block = text.split('Output of `make demo`', 1)[1].split('```', 2)[1]
    return [' '.join(line.split()) for line in block.splitlines()
            if RUN_LINE.match(line) or line.startswith('  baseline    front')
            or line.startswith('  baseline    rear')]


@pytest.fixture(scope='module')
def demo(tmp_path_factory) -> tuple[subprocess.CompletedProcess, Path]:
    cwd = tmp_path_factory.mktemp('demo')
    # no timeout: a loaded machine makes the demo slower, never failed
    done = subprocess.run([sys.executable, '-m', 'vd_events.cli.demo'], cwd=cwd, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          env=dict(os.environ, COLUMNS='80'))
    return done, cwd


def test_the_demo_finishes_every_run(demo):
    done, cwd = demo
    assert done.returncode == 0, done.stdout[-3000:]
    lines = [RUN_LINE.match(line) for line in done.stdout.splitlines()]
    runs = [m for m in lines if m is not None]
    # one line per run, numbered as they complete, none an error
    assert [int(m.group(1)) for m in runs] == list(range(1, len(runs) + 1))
    assert {int(m.group(2)) for m in runs} == {len(runs)}
    bags = sorted(p for p in (cwd / 'out' / 'demo' / 'bags').iterdir())
    assert len(bags) == len(runs)
    assert all((bag / 'metadata.yaml').is_file() for bag in bags)
    assert not list((cwd / 'out' / 'demo' / 'bags').glob('*.partial'))
    assert (cwd / 'out' / 'demo' / 'report.html').is_file()
    assert f'bags:   out/demo/bags ({len(runs)} runs)' in done.stdout


def test_the_readme_quotes_the_demo_as_it_runs(demo):
    done, _ = demo
    printed = {' '.join(line.split()) for line in done.stdout.splitlines()}
    quoted = _readme_demo_lines()
    assert len(quoted) >= 10
    assert [q for q in quoted if q not in printed] == []
