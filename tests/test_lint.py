# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Lint the way ROS 2 packages are linted: ament_flake8/ament_pep257 rules and headers."""
from pathlib import Path
import shutil
import subprocess
import sys

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _ruff() -> str:
    exe = shutil.which('ruff', path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.fail('ruff is not installed in the workspace venv (requirements.lock pins it)')
    return exe


@pytest.mark.linter
def test_ruff_finds_nothing():
    """Zero findings of the ruff.toml rule set (line length, quotes, imports, docstrings)."""
    run = subprocess.run([_ruff(), 'check', '--no-cache', '--output-format', 'concise', '.'],
                         cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


@pytest.mark.linter
def test_every_source_file_has_the_licence_header():
    """Every Python and shell file carries the copyright and SPDX header (tools/spdx.py)."""
    run = subprocess.run([sys.executable, 'tools/spdx.py'], cwd=ROOT, capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stderr
