# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Facts two groups both describe: the anti-roll bar of the rigid and the flexible model.

The rigid model reads the bar from the stabilizer group, the flexible model builds it
from the flex group and the hard points. Every test edits a private copy of the sample
data so that the two disagree, and checks the exact message (naming both files, keys and
values) and that nothing was written.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vdtest import replace_once, tree_snapshot

FRONT_FLEX = 'sedan/front_flex/X.yaml'
BAR_LINE = '    anti_roll_bar: {material: bar_steel, elements_per_member: 4}'


def refused(root: Path, master: Path) -> str:
    before = tree_snapshot(root)
    with pytest.raises(DataError) as info:
        load_study(master)
    assert tree_snapshot(root) == before
    return str(info.value)


def test_a_flexible_bar_of_another_diameter_is_refused(sample_root, sedan_master):
    """The issue's case: a 22 mm flexible twin of the 24 mm bar (bar_radius 12 mm)."""
    flex = sample_root / FRONT_FLEX
    replace_once(flex, '  sections:\n',
                 '  sections:\n    bar: {shape: solid_round, diameter: 22}\n')
    replace_once(flex, BAR_LINE, BAR_LINE.replace('material: bar_steel',
                                                  'material: bar_steel, section: bar'))
    assert refused(sample_root, sedan_master) == (
        f"{FRONT_FLEX}: components.anti_roll_bar.section: section 'bar' (diameter 22 mm) "
        'contradicts sedan/front_stabilizer/X.yaml bar_radius 12 mm (a solid bar of diameter '
        "24 mm): one bar, one description; leave the section out (the flexible bar takes the "
        "stabilizer's) or make them agree")


def test_a_flexible_bar_of_the_same_diameter_is_accepted(sample_root, sedan_master):
    flex = sample_root / FRONT_FLEX
    replace_once(flex, '  sections:\n',
                 '  sections:\n    bar: {shape: solid_round, diameter: 24}\n')
    replace_once(flex, BAR_LINE, BAR_LINE.replace('material: bar_steel',
                                                  'material: bar_steel, section: bar'))
    load_study(sedan_master)


def test_a_stiffer_rear_bar_variant_flows_into_the_flexible_bar(sedan_master):
    """stiff_rear picks the 22 mm rear_stabilizer Y; the flexible bar follows, no edit."""
    from vd_solvers.kc.from_config import suspension_input

    study = load_study(sedan_master)
    for name, radius in (('baseline', 9e-3), ('stiff_rear', 11e-3)):
        config = study.configurations[name]
        bar = suspension_input(config, 'rear', 'flexible').flexible['anti_roll_bar']
        stab = config.group('rear_stabilizer')
        assert stab.scalar('bar_radius') == pytest.approx(radius, rel=1e-12)
        # solid round bar: J = pi d^4 / 32 with d = 2 r (Roark, Table 10.7 case 1)
        assert bar.section.j == pytest.approx(3.141592653589793 * (2 * radius) ** 4 / 32,
                                              rel=1e-12)
        assert bar.material.shear_modulus == stab.scalar('shear_modulus')


def test_a_bar_material_of_another_shear_modulus_is_refused(sample_root, sedan_master):
    replace_once(sample_root / FRONT_FLEX,
                 'bar_steel: {youngs_modulus: 206000, shear_modulus: 79300',
                 'bar_steel: {youngs_modulus: 206000, shear_modulus: 81000')
    assert refused(sample_root, sedan_master) == (
        f"{FRONT_FLEX}: materials.bar_steel: material 'bar_steel' has shear modulus 81 GPa, "
        'sedan/front_stabilizer/X.yaml shear_modulus is 79.3 GPa: one bar, one material; '
        'make them agree')


def test_a_torsion_length_other_than_the_pivot_distance_is_refused(sample_root, sedan_master):
    """The beam bar twists between the arb_pivot hard points, the rigid bar over torsion_length."""
    replace_once(sample_root / 'sedan/front_stabilizer/X.yaml', 'torsion_length: 800',
                 'torsion_length: 850')
    assert refused(sample_root, sedan_master) == (
        'sedan/front_stabilizer/X.yaml: torsion_length: torsion_length 850 mm but the '
        'arb_pivot hard points of sedan/front_hardpoints/X.yaml are 800 mm apart (where the '
        'flexible bar twists); keep them within 1 mm')


def test_parts_heavier_than_the_corner_are_refused_at_check_time(sample_root, sedan_master):
    replace_once(sample_root / FRONT_FLEX, 'section: knuckle, rigid_mass: 6.0',
                 'section: knuckle, rigid_mass: 60.0')
    unsprung = load_study(sedan_master.parent / 'hmmwv.yaml')  # untouched: still loads
    assert unsprung.configurations
    message = refused(sample_root, sedan_master)
    assert message.startswith(
        f"{FRONT_FLEX}: components: the parts' rigid_mass add up to 67.1 kg, not below "
        'unsprung_mass_front ')
    assert message.endswith('kg of sedan/mass/X.yaml (the corner holds them): lower them or '
                            'raise the unsprung mass')


def test_a_bar_given_by_its_stiffness_needs_a_flex_section_of_that_stiffness(sample_root,
                                                                           sedan_master):
    """
    A stabilizer given only by its torsional stiffness: the flex section must give it.

    The 24 mm bar over the 800 mm between the pivots: G J / L = 79.3e9 * pi * 0.024^4 / 32
    / 0.8 = 3228.7 N*m/rad (Roark, Table 10.7 case 1); a file that states 4000 N*m/rad and a
    24 mm flex section contradicts itself, one that states 3229 agrees.
    """
    stab = sample_root / 'sedan/front_stabilizer/X.yaml'
    replace_once(stab, '  bar_radius: 12.0\n  torsion_length: 800\n  shear_modulus: 79300 N/mm^2',
                 '  torsional_stiffness: 4000 N*m/rad')
    assert refused(sample_root, sedan_master) == (
        f"{FRONT_FLEX}: components.anti_roll_bar.section: the bar's section is needed: "
        'sedan/front_stabilizer/X.yaml gives only its torsional_stiffness, not bar_radius')
    flex = sample_root / FRONT_FLEX
    replace_once(flex, '  sections:\n',
                 '  sections:\n    bar: {shape: solid_round, diameter: 24}\n')
    replace_once(flex, BAR_LINE, BAR_LINE.replace('material: bar_steel',
                                                  'material: bar_steel, section: bar'))
    assert refused(sample_root, sedan_master) == (
        f"{FRONT_FLEX}: components.anti_roll_bar.section: section 'bar' and material "
        "'bar_steel' give the bar G J / L = 3228.7 N*m/rad over the 800 mm between the "
        'arb_pivot hard points, sedan/front_stabilizer/X.yaml torsional_stiffness is 4000 '
        'N*m/rad: one bar, one stiffness; make them agree')
    replace_once(stab, '4000 N*m/rad', '3229 N*m/rad')
    load_study(sedan_master)
