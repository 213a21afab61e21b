# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What a K&C run in a new process imports: no pint once its study is cached.

pint is imported at the first unit conversion (a study from the cache converts nothing);
numba at the first call of a compiled function (the K&C joints' primitives are compiled, so
every K&C solve imports it and loads its machine code from the cache built at setup). The
run's result is the same with the study loaded from the files and from the cache.
"""
from __future__ import annotations

import json
import os
from pathlib import Path
import subprocess
import sys

#: runs ``vd run`` and prints its JSON and then which of the heavy modules were imported
SCRIPT = """
import json, sys
from vd_events.cli.main import main
code = main(sys.argv[1:])
print(json.dumps({'code': code, 'loaded': [m for m in ('numba', 'pint') if m in sys.modules]}))
"""


def _run(master: Path, cache: Path) -> tuple[dict, list[str]]:
    env = dict(os.environ, XDG_CACHE_HOME=str(cache))
    done = subprocess.run([sys.executable, '-c', SCRIPT, 'run', 'parallel_wheel_travel',
                           '--master', str(master), '--axle', 'front', '--model', 'kc',
                           '--json'], env=env, capture_output=True, text=True, check=True)
    *result, last = done.stdout.strip().splitlines()
    tail = json.loads(last)
    assert tail['code'] == 0, done.stderr
    outcome = json.loads('\n'.join(result))
    outcome.pop('timings')
    return outcome, tail['loaded']


def test_a_kc_run_from_the_cached_study_imports_no_pint(
        sedan_master: Path, tmp_path: Path) -> None:
    cache = tmp_path / 'cache'
    first, loaded_first = _run(sedan_master, cache)
    assert loaded_first == ['numba', 'pint']  # the files were read and converted
    assert list((cache / 'vd' / 'studies').glob('*.pickle'))
    second, loaded_second = _run(sedan_master, cache)
    assert loaded_second == ['numba']
    assert second == first  # every metric and channel, to the last bit
