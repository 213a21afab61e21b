# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Signals at chosen points of embedded and distributed runs (issue 10, causes 1 and 6).

Afterwards there is no finished-looking bag, no orphan process, and a rerun works.

The signal goes out once the run's recorder has started (``<bag>.partial`` exists), i.e.
while the goal is being sent or solved. ``make fuzz`` adds SIGTERM and a random extra
delay (up to the end of the run).
"""
from __future__ import annotations

import json
import os
from pathlib import Path
import random
import signal
import subprocess
import sys
import time

import pytest

from vdtest import HANG_GUARD

pytestmark = [pytest.mark.ros, pytest.mark.slow]

FUZZ = os.environ.get('HYPOTHESIS_PROFILE') == 'fuzz'
STARTUP = 30.0  # s: for the run to reach its recorder


def _vd(*argv: str, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, '-m', 'vd_events.cli.main', *argv],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, **kwargs)


def _children_of(pid: int) -> list[int]:
    """Return the processes started by the run ``pid`` (they carry VD_PARENT_PID=pid)."""
    mark = f'VD_PARENT_PID={pid}'.encode()
    found = []
    for entry in Path('/proc').iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if mark in (entry / 'environ').read_bytes().split(b'\0'):
                found.append(int(entry.name))
        except OSError:
            continue
    return found


def _wait_for(predicate, timeout: float) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.05)
    return predicate()


CASES = [('embedded', signal.SIGINT), ('embedded', signal.SIGKILL),
         ('distributed', signal.SIGINT), ('distributed', signal.SIGKILL)]
if FUZZ:
    CASES += [('embedded', signal.SIGTERM), ('distributed', signal.SIGTERM)]


@pytest.mark.parametrize(('mode', 'sig'), CASES, ids=lambda v: getattr(v, 'name', v))
def test_signal_during_a_run(tmp_path, sedan_master, mode, sig):
    bag = tmp_path / 'bag'
    partial = tmp_path / 'bag.partial'
    argv = ['run', 'parallel_wheel_travel', '--axle', 'front', '--master', str(sedan_master),
            '--bag', str(bag), '--json']
    extra = ['--distributed'] if mode == 'distributed' else []
    proc = _vd(*argv, *extra)
    try:
        assert _wait_for(lambda: partial.exists() or proc.poll() is not None, STARTUP)
        assert proc.poll() is None, proc.communicate()
        if FUZZ:
            time.sleep(random.uniform(0.0, 2.0))
        children = _children_of(proc.pid)
        os.kill(proc.pid, sig)
        out, err = proc.communicate(timeout=HANG_GUARD)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    finished = proc.returncode == 0  # the random delay may reach the end of the run
    if not finished:
        assert not (bag / 'metadata.yaml').exists(), 'an interrupted run left a finished bag'
    if sig == signal.SIGKILL:
        assert proc.returncode == -signal.SIGKILL
    elif not finished:
        assert proc.returncode == 130, err
        assert json.loads(out) == {'error': f"configuration 'baseline', event "
                                            f"'parallel_wheel_travel', model 'kc': interrupted; "
                                            f"no bag written ({partial} removed)"}
        assert not bag.exists() and not partial.exists()
    # no orphan: every node of a distributed run ends with it, even after kill -9
    assert _wait_for(lambda: not any(_alive(pid) for pid in children), 15.0), children
    assert not _children_of(proc.pid)
    if mode == 'distributed' and not finished:
        # the recorder ended with the killed run and removed its partial bag itself
        assert _wait_for(lambda: not partial.exists(), 15.0)
        assert not bag.exists()
    if (mode, sig) == ('embedded', signal.SIGKILL) or FUZZ:
        # nothing could clean up after kill -9 of the one process: the partial bag stays,
        # and the rerun replaces it (its writer's lock died with the process)
        rerun = tmp_path / 'rerun'
        done = subprocess.run([sys.executable, '-m', 'vd_events.cli.main', *argv[:-3], '--bag',
                               str(bag if not finished else rerun), '--json'],
                              capture_output=True, text=True, timeout=HANG_GUARD)
        assert done.returncode == 0, done.stderr
        result = json.loads(done.stdout)
        assert (Path(result['bag']) / 'metadata.yaml').is_file()
        assert not partial.exists()


def _alive(pid: int) -> bool:
    try:
        state = Path(f'/proc/{pid}/stat').read_text().split(')')[-1].split()[0]
    except OSError:
        return False
    return state != 'Z'
