# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The road group: sample variants load, bad road files stop with exact messages.

The messages name the file, the key and (for keys of the file) its line; an OpenCRG file
that is no valid one stops the run naming the file and the reader's reason.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.road.from_config import road_of
from vd_solvers.vehicle.events import run_vehicle_event


def _master(root: Path) -> Path:
    return root / 'studies' / 'sedan_roads.yaml'


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding='utf-8')
    assert old in text
    path.write_text(text.replace(old, new), encoding='utf-8')


def test_every_sample_road_loads_and_names_itself(sample_root):
    study = load_study(_master(sample_root))
    names = {name: road_of(config).description for name, config in study.configurations.items()}
    assert names['baseline'].startswith('ISO 8608 class B road, seed 1, parallel tracks')
    assert names['class_c'].startswith('ISO 8608 class C road, seed 1, independent tracks')
    assert names['cleat'].startswith('bump of height 0.02 m and length 0.1 m at 20 m')
    assert names['crg'].startswith('OpenCRG sample.crg (sha256 ')
    assert names['dry'] == 'flat road, friction 1'
    assert names['wet'] == 'flat road, friction 0.6'
    assert names['split_mu'] == 'flat road, friction 0.3 right / 1 left of y = 0 m'


def test_a_surface_without_its_keys_is_refused_with_file_key_and_line(sample_root):
    _edit(sample_root / 'sedan' / 'road' / 'iso_b.yaml', '  seed: 1\n', '')
    with pytest.raises(DataError) as err:
        load_study(_master(sample_root))
    assert "sedan/road/iso_b.yaml: data.seed: required for surface 'iso8608' (line 6)" \
        in str(err.value)


def test_a_key_of_another_surface_is_refused(sample_root):
    path = sample_root / 'sedan' / 'road' / 'dry.yaml'
    path.write_text(path.read_text(encoding='utf-8') + '  obstacle: bump\n', encoding='utf-8')
    with pytest.raises(DataError) as err:
        load_study(_master(sample_root))
    assert ("sedan/road/dry.yaml: data.obstacle: not used by surface 'flat' (it uses: "
            "friction, friction_left) (line 8)") in str(err.value)


def test_an_obstacle_beyond_the_road_is_refused(sample_root):
    _edit(sample_root / 'sedan' / 'road' / 'cleat.yaml', 'length: 60000', 'length: 20050')
    with pytest.raises(DataError) as err:
        load_study(_master(sample_root))
    assert ('sedan/road/cleat.yaml: data.length: the road (20.05 m) must reach beyond the '
            'obstacle (which ends at 20.1 m)') in str(err.value)


def test_a_missing_crg_file_is_refused(sample_root):
    _edit(sample_root / 'sedan' / 'road' / 'crg_sample.yaml', 'roads/sample.crg',
          'roads/missing.crg')
    with pytest.raises(DataError) as err:
        load_study(_master(sample_root))
    assert ("sedan/road/crg_sample.yaml: data.file: road file 'roads/missing.crg' does not "
            'exist') in str(err.value)


def test_a_crg_file_that_is_no_opencrg_stops_the_run_naming_it(sample_root):
    (sample_root / 'roads' / 'sample.crg').write_text('$ROAD_CRG\nnonsense\n', encoding='ascii')
    config = load_study(_master(sample_root)).configurations['crg']
    with pytest.raises(SolverError) as err:
        run_vehicle_event(config, 'ride')
    message = str(err.value)
    assert message.startswith("configuration 'crg', event 'ride': ")
    assert f"{sample_root / 'roads' / 'sample.crg'}: not a valid OpenCRG road file: " in message


def test_a_changed_crg_file_changes_the_data_hash(sample_root):
    before = load_study(_master(sample_root)).configurations['crg'].data_hash
    path = sample_root / 'roads' / 'sample.crg'
    path.write_text(path.read_text(encoding='ascii').replace('vd sample road', 'vd sample  road'),
                    encoding='ascii')
    assert load_study(_master(sample_root)).configurations['crg'].data_hash != before
