# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A configuration's tire: the .tir values after master-file overrides reach the Magic Formula.

The sample study ``sedan_mf62.yaml`` runs the sedan on the MF 6.2 sample tire at the file's
inflation pressure and at 2.1 bar set by an override; the pressure is checked against the
file's valid range like any value, and ``aligning_normalisation`` picks the trail's load.
"""
from __future__ import annotations

from pathlib import Path

import numpy.testing as npt
import pytest

from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vd_data_server.tire_group import tire_properties
from vd_solvers.tire.magic_formula import MagicFormula
from vdtest import replace_once, tree_snapshot

OVERRIDE = 'front_tire.tir.OPERATING_CONDITIONS.INFLPRES: 2.1 bar'


@pytest.fixture
def mf62_master(sample_root: Path) -> Path:
    return sample_root / 'studies' / 'sedan_mf62.yaml'


def test_a_configuration_sets_the_inflation_pressure(mf62_master: Path) -> None:
    study = load_study(mf62_master)
    nominal = study.configurations['mf62'].group('front_tire')
    low = study.configurations['mf62_low_pressure'].group('front_tire')
    key = 'tir.OPERATING_CONDITIONS.INFLPRES'
    assert nominal.values[key].number() == 260000.0
    assert low.values[key].number() == pytest.approx(210000.0, rel=1e-12)  # 2.1 bar
    assert 'master override' in low.values[key].source
    tire_nominal = MagicFormula(tire_properties(nominal))
    tire_low = MagicFormula(tire_properties(low))
    assert tire_nominal.inflation_pressure == 260000.0
    npt.assert_allclose(tire_low.inflation_pressure, 210000.0, rtol=1e-12)
    # the same as setting the pressure on the model directly
    direct = MagicFormula(tire_properties(nominal), pressure=210000.0)
    npt.assert_allclose(tire_low.cornering_stiffness(6000.0), direct.cornering_stiffness(6000.0),
                        rtol=1e-12)


def test_a_pressure_outside_the_files_range_is_refused(sample_root: Path,
                                                       mf62_master: Path) -> None:
    replace_once(mf62_master, OVERRIDE, 'front_tire.tir.OPERATING_CONDITIONS.INFLPRES: 5 bar')
    before = tree_snapshot(sample_root)
    with pytest.raises(DataError) as info:
        load_study(mf62_master)
    assert tree_snapshot(sample_root) == before
    assert str(info.value) == (
        "sedan/front_tire/MF62.yaml -> tires/MF62_255_55R20.tir: INFLPRES: key 'INFLPRES' in "
        'block [OPERATING_CONDITIONS] must lie in the range the file is valid for, '
        'PRESMIN..PRESMAX = 200000..400000 Pa, found 500000')


def test_aligning_normalisation_is_a_value_of_the_tire_group(sample_root: Path,
                                                             mf62_master: Path) -> None:
    study = load_study(sample_root / 'studies' / 'sedan.yaml')
    group = study.configurations['baseline'].group('front_tire')
    assert group.text('aligning_normalisation') == 'mf-tyre'
    props = tire_properties(group)
    assert props.aligning_normalisation == 'mf-tyre'
    replace_once(mf62_master, OVERRIDE,
                 f'{OVERRIDE}\n      front_tire.aligning_normalisation: book')
    book = tire_properties(load_study(mf62_master).configurations['mf62_low_pressure']
                           .group('front_tire'))
    assert book.aligning_normalisation == 'book'


def test_an_unknown_normalisation_is_refused(sample_root: Path, mf62_master: Path) -> None:
    replace_once(mf62_master, OVERRIDE,
                 f'{OVERRIDE}\n      front_tire.aligning_normalisation: chrono')
    with pytest.raises(DataError) as info:
        load_study(mf62_master)
    assert str(info.value) == (
        f'{mf62_master}: configurations.mf62_low_pressure.overrides.front_tire.'
        "aligning_normalisation: 'chrono' is not one of: mf-tyre, book")
