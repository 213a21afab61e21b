# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Dump every K&C event of the sample studies to one .npz, or compare two such dumps.

    python tools/kc_dump.py dump OUT.npz            # every study, configuration, axle,
                                                     # event; rigid, flexible, rigid limit
    python tools/kc_dump.py compare A.npz B.npz     # max difference, 0 if <= 1e-9

A check that a change of the K&C numerics leaves its answers as they were: dump with the
code before and after, compare (:func:`compare`).
"""
from __future__ import annotations

import sys

import numpy as np

STUDIES = ('sedan.yaml', 'hmmwv.yaml')


def dump(out: str) -> int:
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study
    from vd_solvers.errors import SolverError
    from vd_solvers.kc.from_config import EVENTS, run_kc_event

    folder = default_master().parent
    arrays: dict[str, np.ndarray] = {}
    for name in STUDIES:
        study = load_study(folder / name)
        for config_name in study.configuration_names:
            config = study.configurations[config_name]
            for axle in ('front', 'rear'):
                for event in EVENTS:
                    for fidelity, limit in (('rigid', False), ('flexible', False),
                                            ('flexible', True)):
                        key = f'{name}/{config_name}/{axle}/{event}/{fidelity}' + (
                            '_limit' if limit else '')
                        try:
                            o = run_kc_event(config, event, axle, fidelity=fidelity,
                                             at_rigid_limit=limit)
                        except SolverError as err:
                            print(f'{key}: skipped ({err})', file=sys.stderr)
                            continue
                        for ch, c in o.channels.items():
                            arrays[f'{key}/channel/{ch}'] = np.asarray(c.values, dtype=float)
                        for m, v in o.metrics.items():
                            arrays[f'{key}/metric/{m}'] = np.array([v.value], dtype=float)
                        print(key, file=sys.stderr)
    np.savez_compressed(out, **arrays)
    return 0


def compare(a_path: str, b_path: str) -> int:
    """
    Print the largest difference between two dumps relative to the channel's scale.

    The scale of a channel (or metric) is its largest magnitude over the whole first dump:
    every study, configuration, axle, event and fidelity. Channels that are zero by
    symmetry in one event (the anti-roll bar's twist under equal longitudinal forces,
    the rack force in parallel travel) hold round-off there, which two correct codes need
    not share; they are judged on the scale the quantity has where it is not zero.
    """
    a, b = np.load(a_path), np.load(b_path)
    missing = sorted(set(a.files) ^ set(b.files))
    common = sorted(set(a.files) & set(b.files))
    scale: dict[str, float] = {}
    for k in common:
        name = k.rsplit('/', 2)[-1]
        finite = a[k][np.isfinite(a[k])]
        scale[name] = max(scale.get(name, 0.0), float(np.max(np.abs(finite), initial=0.0)))
    worst, where, identical = 0.0, '', 0
    for k in common:
        x, y = a[k], b[k]
        if x.shape != y.shape or not np.array_equal(np.isfinite(x), np.isfinite(y)):
            print(f'{k}: shapes or non-finite entries differ')
            return 1
        finite = np.isfinite(x)
        gap = float(np.max(np.abs(x[finite] - y[finite]), initial=0.0))
        identical += gap == 0.0
        rel = gap / scale[k.rsplit('/', 2)[-1]] if gap else 0.0
        if rel > worst:
            worst, where = rel, k
    print(f'{len(a.files)} and {len(b.files)} entries, {len(missing)} in one only'
          + (f' (e.g. {missing[:3]})' if missing else '') + f', {identical} bit-identical')
    print(f"max difference {worst:.3e} of the channel's scale" + (f' at {where}' if where else ''))
    return 0 if not missing and worst <= 1e-9 else 1


if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == 'dump':
        raise SystemExit(dump(sys.argv[2]))
    if len(sys.argv) == 4 and sys.argv[1] == 'compare':
        raise SystemExit(compare(sys.argv[2], sys.argv[3]))
    raise SystemExit(__doc__)
