# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd data check`` refuses the imported stiffness files a K&C run refuses (issue 28).

The front lower arm of the sample sedan is switched to an imported reduced stiffness:
first the arm's own condensed beam stiffness (plain YAML in mm and N, and a Nastran DMIG
punch), which check and run accept; then each file broken in one way, which the check
refuses with the message of the run, exit 2, nothing written.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from vd_events.cli.main import main
from vd_solvers.errors import SolverError
from vd_solvers.flex.imported import dof_scales
from vdtest import replace_once, tree_snapshot

FLEX = 'sedan/front_flex/X.yaml'
PLAIN = 'sedan/front_flex/lca_k.yaml'
PUNCH = 'sedan/front_flex/lca_k.pch'
LCA = 'lca: {material: steel, section: pressed_arm, rigid_mass: 3.5, elements_per_member: 2}'
WHAT = f'{PLAIN} ({FLEX} components.lca.imported)'
LABEL = "configuration 'baseline', axle 'front', flexible"


@pytest.fixture(scope='module')
def arm():
    """Return the lower arm's condensed beam stiffness of the bundled baseline (SI)."""
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study
    from vd_solvers.kc.from_config import build_kc_model

    config = load_study(default_master()).configurations['baseline']
    model = build_kc_model(config, 'front', 'flexible', 'arm')
    (comp,) = [c for c in model.system.outputs.components if c.name == 'lca']
    return comp


def _plain(comp) -> dict:
    """Write the arm in the plain format (mm, N), its nodes on the data file's hard points."""
    from vd_data_server.paths import default_master

    points = yaml.safe_load((default_master().parents[1] / 'sedan/front_hardpoints/X.yaml')
                            .read_text())['data']['points']
    k = comp.stiffness / dof_scales(len(comp.nodes), 1e-3, 1.0, 1.0)
    return {'units': {'length': 'mm', 'force': 'N', 'angle': 'rad'},
            'nodes': {n: points[n] for n in comp.nodes}, 'stiffness': k.tolist()}


def _dmig(comp) -> str:
    lines = [f"DMIG*   {'KAAX':<16}{0:>16}{6:>16}{2:>16}", '*       ' + f'{0:>16}']
    for j in range(comp.stiffness.shape[0]):
        lines.append(f"DMIG*   {'KAAX':<16}{101 + j // 6:>16}{j % 6 + 1:>16}")
        for i in range(j + 1):
            lines.append(f'*       {101 + i // 6:>16}{i % 6 + 1:>16}'
                         f'{comp.stiffness[i, j]:>16.9E}')
    return '\n'.join(lines) + '\n'


def _use_plain(root: Path, text: str) -> None:
    replace_once(root / FLEX, LCA, f'lca: {{rigid_mass: 3.5, imported: {{file: {PLAIN}, '
                 'format: plain}}')
    (root / PLAIN).write_text(text)


def _use_punch(root: Path, comp, text: str) -> None:
    grids = ', '.join(f'{101 + i}: {n}' for i, n in enumerate(comp.nodes))
    replace_once(root / FLEX, LCA, f'lca: {{rigid_mass: 3.5, imported: {{file: {PUNCH}, '
                 f'format: dmig, matrix: KAAX, grids: {{{grids}}}}}}}')
    (root / PUNCH).write_text(text)


def _check(capsys, root: Path, master: Path) -> tuple[int, str, str]:
    rc = main(['data', 'check', '--master', str(master)])
    out, err = capsys.readouterr()
    return rc, out, err.strip()


def _refused(capsys, root: Path, master: Path, message: str) -> None:
    before = tree_snapshot(root)
    rc, out, err = _check(capsys, root, master)
    assert (rc, out, err) == (2, '', message)
    assert tree_snapshot(root) == before


def test_the_arms_own_stiffness_passes_the_check(capsys, sample_root, sedan_master, arm):
    """A DMIG punch without GRID cards: the nodes sit on each configuration's hard points."""
    _use_punch(sample_root, arm, _dmig(arm))
    rc, out, err = _check(capsys, sample_root, sedan_master)
    assert (rc, err) == (0, '') and out.endswith('OK (3 configurations, 28 data files)\n')


def test_stiffness_of_other_geometry_fails_the_check(capsys, sample_root, sedan_master, arm):
    """
    The plain file's nodes are the baseline's hard points.

    The sport configuration moves the ball joint 10 mm (a master-file override): the
    stiffness belongs to other geometry there, which check and run refuse.
    """
    _use_plain(sample_root, yaml.safe_dump(_plain(arm)))
    _refused(capsys, sample_root, sedan_master,
             "configuration 'sport', axle 'front', flexible: flexible component 'lca': imported "
             'node lca_outer lies 10.0 mm from the hard point (more than 2 mm): the stiffness '
             'belongs to other geometry')


def _nonsymmetric(d: dict) -> None:
    d['stiffness'][0][1] += 1e3 * max(abs(v) for v in d['stiffness'][0])


def _indefinite(d: dict) -> None:
    d['stiffness'] = (-np.array(d['stiffness'])).tolist()


def _nan(d: dict) -> None:
    d['stiffness'][2][2] = float('nan')


def _inf(d: dict) -> None:
    d['stiffness'][2][2] = float('inf')


def _wrong_size(d: dict) -> None:
    d['stiffness'] = [row[:-6] for row in d['stiffness'][:-6]]


def _ragged(d: dict) -> None:
    d['stiffness'][4] = d['stiffness'][4][:-1]


def _unknown_node(d: dict) -> None:
    first = next(iter(d['nodes']))
    d['nodes'] = {('nowhere' if n == first else n): p for n, p in d['nodes'].items()}


def _bad_units(d: dict) -> None:
    d['units']['length'] = 'kg'


def _strings(d: dict) -> None:
    d['stiffness'][0][0] = 'stiff'


@pytest.mark.parametrize(('breakage', 'message'), [
    (_nonsymmetric, f"{LABEL}: {WHAT}: stiffness of 'lca' is not symmetric"),
    (_nan, f"{LABEL}: {WHAT}: stiffness of 'lca' holds non-finite numbers"),
    (_inf, f"{LABEL}: {WHAT}: stiffness of 'lca' holds non-finite numbers"),
    (_wrong_size, f'{LABEL}: {WHAT}: stiffness must be 18 x 18 for 3 nodes, found 12x12'),
    (_ragged, f'{LABEL}: {WHAT}: nodes and stiffness must hold numbers'),
    (_strings, f'{LABEL}: {WHAT}: nodes and stiffness must hold numbers'),
    (_bad_units, f"{LABEL}: {WHAT}: units: unit 'kg' is not a length unit (expected e.g. 'm')"),
])
def test_broken_plain_stiffness_fails_the_check(capsys, sample_root, sedan_master, arm,
                                                breakage, message):
    d = _plain(arm)
    breakage(d)
    _use_plain(sample_root, yaml.safe_dump(d))
    _refused(capsys, sample_root, sedan_master, message)


@pytest.mark.parametrize('breakage', [_indefinite, _unknown_node])
def test_stiffness_the_model_refuses_fails_the_check_as_the_run(capsys, sample_root,
                                                                 sedan_master, arm, breakage):
    """The check's message is the run's message, whatever it is."""
    from vd_data_server.study import load_study
    from vd_solvers.kc.from_config import run_kc_event

    d = _plain(arm)
    breakage(d)
    _use_plain(sample_root, yaml.safe_dump(d))
    config = load_study(sedan_master).configurations['baseline']
    with pytest.raises(SolverError) as run:
        run_kc_event(config, 'parallel_wheel_travel', 'front', ['steps=3'], fidelity='flexible')
    label = "configuration 'baseline', event 'parallel_wheel_travel', axle 'front'"
    assert str(run.value).startswith(f'{label}: ')
    _refused(capsys, sample_root, sedan_master,
             f'{LABEL}: ' + str(run.value)[len(label) + 2:])


@pytest.mark.parametrize(('text', 'message'), [
    ('', f'{LABEL}: {WHAT}: the file is empty (expected units, nodes and stiffness)'),
    ('stiffness: ' + '[' * 200 + ']' * 200 + '\n',
     f'{WHAT}: exceeds the limit of 64 nesting levels (line 1)'),
    ('stiffness: [1, 2\n', f"{WHAT}: malformed YAML: expected ',' or ']', but got "
                           "'<stream end>' (line 2, column 1)"),
])
def test_unreadable_plain_files_fail_the_check(capsys, sample_root, sedan_master, text,
                                               message):
    _use_plain(sample_root, text)
    _refused(capsys, sample_root, sedan_master, message)


def test_truncated_dmig_fails_the_check(capsys, sample_root, sedan_master, arm):
    text = _dmig(arm)
    _use_punch(sample_root, arm, text[:len(text) // 2])
    what = f'{PUNCH} ({FLEX} components.lca.imported)'
    _refused(capsys, sample_root, sedan_master,
             f"{LABEL}: {what}: DMIG 'KAAX' column 103-1: entries must come as GRID, "
             'component, value')
