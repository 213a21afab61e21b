# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The type check of all of src (mypy.ini, Python 3.12): part of the test suite, zero errors."""
from __future__ import annotations

from pathlib import Path
import subprocess
import sys

from vdtest import HANG_GUARD

REPO = Path(__file__).resolve().parents[1]


def test_the_cores_type_check_clean() -> None:
    run = subprocess.run([sys.executable, '-m', 'mypy', '--config-file', 'mypy.ini'],
                         cwd=REPO, capture_output=True, text=True, timeout=HANG_GUARD)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.startswith('Success: no issues found'), run.stdout
