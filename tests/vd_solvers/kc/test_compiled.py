# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The K&C solver's compiled parts against the same functions run as Python.

The primitives (``joints.primitives``) and the weighted second derivatives
(``system.second_order_sum``) run compiled here and, in a child process, with
``VD_NO_JIT=1`` as plain Python: a rigid and a flexible event of the sample sedan give the
same channels (1e-9 of each channel's largest magnitude: the two differ in rounding only).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.testing as npt
import pytest

from vd_solvers import compiled
from vdtest import run_uncompiled

STUDIES = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
RTOL = 1e-9

RUN = """
import numpy as np
from vd_data_server.study import load_study
from vd_solvers.kc.from_config import run_kc_event

def run(master):
    config = load_study(master).configurations['baseline']
    out = {}
    for fidelity, event in (('rigid', 'lateral_force'), ('flexible', 'opposite_wheel_travel')):
        outcome = run_kc_event(config, event, 'front', ['steps=5'], fidelity=fidelity)
        for name, channel in outcome.channels.items():
            out[f'{fidelity}/{name}'] = np.asarray(channel.values, dtype=float)
    return out
"""


def _run_here() -> dict[str, np.ndarray]:
    scope: dict[str, object] = {}
    exec(RUN, scope)  # noqa: S102  (the same code the child runs)
    return scope['run'](STUDIES / 'sedan.yaml')  # type: ignore[operator]


def _run_uncompiled(tmp_path: Path) -> dict[str, np.ndarray]:
    return run_uncompiled(RUN, 'run', STUDIES / 'sedan.yaml', tmp_path)


@pytest.mark.skipif(not compiled.ENABLED, reason='VD_NO_JIT is set: nothing compiled to compare')
def test_compiled_kc_runs_equal_the_uncompiled_functions(tmp_path):
    fast = _run_here()
    slow = _run_uncompiled(tmp_path)
    assert set(fast) == set(slow)
    assert any(k.startswith('flexible/') for k in fast)
    for key, value in fast.items():
        finite = np.isfinite(slow[key])
        npt.assert_array_equal(np.isfinite(value), finite, err_msg=key)
        scale = float(np.max(np.abs(slow[key][finite]), initial=0.0))
        npt.assert_allclose(value[finite], slow[key][finite], rtol=RTOL, atol=RTOL * scale,
                            err_msg=key)
