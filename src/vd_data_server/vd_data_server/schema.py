# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
What each kind of vehicle data file holds: keys, quantities, ranges.

The schema is data (specs below), read by :mod:`vd_data_server.datafile` to
validate and convert files and by ``docs/data-format.md`` (generated check in
the tests) to document every key. Units are pint quantities checked for
dimension, which is why this is not a JSON Schema.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Union


@dataclass(frozen=True)
class Scalar:
    quantity: str
    doc: str
    required: bool = True
    default: float | None = None  # SI
    minimum: float | None = None  # SI, inclusive
    positive: bool = False  # strictly > 0
    maximum: float | None = None  # SI, inclusive


@dataclass(frozen=True)
class Curve:
    """A table y(x) given as ``{x: [...], y: [...]}``; x strictly increasing."""

    x_quantity: str
    y_quantity: str
    doc: str
    required: bool = True
    increasing: bool = True  # y must be non-decreasing (physical force curves)
    x_minimum: float | None = None
    y_minimum: float | None = None


@dataclass(frozen=True)
class Point:
    """A point ``[x, y, z]`` in the vehicle frame, in the file's length unit."""

    doc: str
    required: bool = True


@dataclass(frozen=True)
class Vector:
    """A dimensionless direction ``[x, y, z]``, normalised at load."""

    doc: str
    required: bool = True


@dataclass(frozen=True)
class Text:
    doc: str
    choices: tuple[str, ...] | None = None
    required: bool = True
    #: the message for a text that is no choice, formatted with ``value`` and ``choices``
    refusal: str = "'{value}' is not one of: {choices}"


@dataclass(frozen=True)
class Name:
    """
    A plain name: letters, digits, '_', '-' and '.', not starting with a punctuation mark.

    Names pick files and folders (variants, the vehicle) and name configurations, so they
    hold no path separators and never climb out of the data root.
    """

    doc: str
    #: the message for a name that is not plain, formatted with ``value``
    refusal: str = "must be a plain name (letters, digits, '_', '-', '.'), found {value!r}"
    required: bool = True
    numbers: bool = False  # a number is a name too (variant ``1``)


@dataclass(frozen=True)
class Flag:
    """``true`` or ``false``; with ``or_list``, also a list of names (a switch for those)."""

    doc: str
    required: bool = False
    or_list: str | None = None  # what the names of the list are, in messages


@dataclass(frozen=True)
class ListOf:
    """A list ``[a, b, ...]`` of one spec; ``alternative`` is a text allowed instead."""

    value: 'Spec'
    doc: str
    what: str = 'texts'  # in messages: "expected a list of <what>"
    required: bool = False
    non_empty: bool = False
    alternative: str | None = None


@dataclass(frozen=True)
class Raw:
    """Any value, checked later by whoever reads it (an override value)."""

    doc: str
    required: bool = True


@dataclass(frozen=True)
class Section:
    fields: Mapping[str, 'Spec']
    doc: str = ''
    required: bool = True
    #: groups of keys of which exactly one must be given
    one_of: tuple[tuple[str, ...], ...] = ()


@dataclass(frozen=True)
class MapOf:
    """Free names (hard points, bushing connections, configurations) -> the same spec."""

    value: 'Spec'
    doc: str
    required: bool = True
    #: what the names must be (a plain name, one of a set of texts), if anything
    keys: 'Name | Text | None' = None
    #: an empty mapping (or none at all) is fine
    empty: bool = False
    #: what a value that is no mapping is refused as: "expected <expected>, found ..."
    expected: str = 'a non-empty mapping of names'


Spec = Union[Scalar, Curve, Point, Vector, Text, Name, Flag, ListOf, Raw, Section, MapOf]

AXLES = ('front', 'rear')

# --- suspension templates: the hard points each one needs (left side) ---
TEMPLATE_POINTS: Mapping[str, tuple[str, ...]] = {
    'macpherson': ('lca_front', 'lca_rear', 'lca_outer', 'tierod_inner', 'tierod_outer',
                   'strut_top', 'strut_lower', 'wheel_centre'),
    'double_wishbone': ('uca_front', 'uca_rear', 'uca_outer', 'lca_front', 'lca_rear',
                        'lca_outer', 'tierod_inner', 'tierod_outer', 'spring_upper',
                        'spring_lower', 'damper_upper', 'damper_lower', 'wheel_centre'),
    'multilink': ('upper_front', 'upper_rear', 'upper_outer', 'lateral_inner', 'lateral_outer',
                  'trailing_inner', 'trailing_outer', 'tierod_inner', 'tierod_outer',
                  'spring_upper', 'spring_lower', 'damper_upper', 'damper_lower',
                  'wheel_centre'),
}
#: parts and links of each template that may be made flexible (the K&C templates'
#: ``Topology.flexible_components``; a test keeps the two equal), plus the bar
TEMPLATE_COMPONENTS: Mapping[str, tuple[str, ...]] = {
    'macpherson': ('upright', 'lca', 'strut', 'tierod'),
    'double_wishbone': ('upright', 'lca', 'uca', 'tierod'),
    'multilink': ('upright', 'upper_arm', 'trailing_link', 'lateral_link', 'tierod'),
}
BAR_COMPONENT = 'anti_roll_bar'
SECTION_SHAPES: Mapping[str, tuple[str, ...]] = {
    'solid_round': ('diameter',),
    'tube': ('outer_diameter', 'wall'),
    'rectangle': ('width', 'height'),
    'i_beam': ('height', 'flange_width', 'flange_thickness', 'web_thickness'),
    'general': ('area', 'iy', 'iz', 'torsion_constant'),
}

#: the anti-roll bar's drop link (lower and upper end) and its pivot on the body
ARB_POINTS = ('arb_link_lower', 'arb_link_upper', 'arb_pivot')
#: body mounts of a flexible subframe (left side; mirrored)
SUBFRAME_POINTS = ('subframe_front', 'subframe_rear')
#: optional points every template understands
OPTIONAL_POINTS = ARB_POINTS + SUBFRAME_POINTS
SUBFRAME_COMPONENT = 'subframe'

#: drive layouts and differential types of the driveline group
DRIVE_LAYOUTS = ('FWD', 'RWD', 'AWD')
DIFFERENTIALS = ('open', 'limited_slip', 'locked')
ANTI_LOCK = ('all_wheels', 'none')

_STOP = Section({
    'clearance': Scalar('length', 'travel of the spring/damper from design length before the '
                        'stop touches', minimum=0.0),
    'curve': Curve('length', 'force', 'stop force versus compression beyond the clearance',
                   x_minimum=0.0),
})

#: the six directions of a bushing, in its frame: translations, then rotations
BUSHING_DIRECTIONS = ('x', 'y', 'z', 'rx', 'ry', 'rz')


def _six(trans: str, rot: str, what: str, required: bool) -> Section:
    return Section({
        d: Scalar(trans if len(d) == 1 else rot,
                  f"{what} along/about the bushing's {d[-1]} axis", minimum=0.0,
                  required=required, default=None if required else 0.0)
        for d in BUSHING_DIRECTIONS
    }, required=required)


def _caliper(axle: str) -> Section:
    return Section({
        'piston_diameter': Scalar('length', f'{axle} caliper piston diameter', positive=True),
        'pistons': Scalar('dimensionless', 'pistons per side of the disc (1 on a floating '
                          'caliper)', required=False, default=1.0, minimum=1.0, maximum=6.0),
        'pad_friction': Scalar('dimensionless', 'pad-to-disc friction coefficient',
                               positive=True, maximum=1.0),
        'effective_radius': Scalar('length', "from the wheel axis to the pads' centre of "
                                   'pressure (inside the rim)', positive=True),
    }, doc=f'{axle} wheel brake')


def _differential(axle: str) -> Section:
    return Section({
        'type': Text(f'{axle} differential', choices=DIFFERENTIALS),
        'locking_torque': Scalar('torque', 'limited_slip: torque the clutch carries from the '
                                 'faster to the slower wheel when it slips', required=False,
                                 default=0.0, minimum=0.0),
        'lock_damping': Scalar('torsional_damping', 'locked: stiffness of the lock against '
                               'a left/right speed difference', required=False,
                               default=1000.0, positive=True),
    }, required=False, doc=f'{axle} axle differential (default: open)')


KINDS: Mapping[str, Section] = {
    'hardpoints': Section({
        'template': Text('suspension template', choices=tuple(TEMPLATE_POINTS)),
        'points': MapOf(Point('hard point, left side, vehicle frame (origin on the ground under '
                              'the front axle centre, x forward, y left, z up)'),
                        'hard points by name; the template fixes which are required'),
    }),
    'spring': Section({
        'rate': Scalar('stiffness', 'linear coil-spring rate along its axis', required=False,
                       positive=True),
        'curve': Curve('length', 'force', 'spring force versus compression from the free length '
                       '(extension negative)', required=False),
        'free_length': Scalar('length', 'unloaded length', required=False, positive=True),
        'preload': Scalar('force', 'force at the design (hard-point) length; the free length '
                          'follows from it and the rate or curve', required=False, minimum=0.0),
    }, one_of=(('rate', 'curve'), ('free_length', 'preload'))),
    'damper': Section({
        'curve': Curve('velocity', 'force', 'damper force versus compression velocity '
                       '(rebound negative)'),
        'scale': Scalar('dimensionless', "damping scale factor (the thesis' 'damping %')",
                        required=False, default=1.0, positive=True),
    }),
    'bump_stop': _STOP,
    'rebound_stop': _STOP,
    'bushings': Section({
        'connections': MapOf(Section({
            'stiffness': _six('stiffness', 'torsional_stiffness', 'linear stiffness', True),
            'damping': _six('damping', 'torsional_damping', 'linear damping', False),
            'axis': Vector('bushing axial (z) direction in the vehicle frame; default vehicle z',
                           required=False),
        }), 'bushings by the hard point of the connection they make compliant'),
    }),
    'stabilizer': Section({
        'torsional_stiffness': Scalar('torsional_stiffness', 'bar twist stiffness (left arm '
                                      'relative to right)', required=False, positive=True),
        'bar_radius': Scalar('length', 'bar radius (solid round bar)', required=False,
                             positive=True),
        'torsion_length': Scalar('length', "length of the bar's straight torsion part",
                                 required=False, positive=True),
        'shear_modulus': Scalar('pressure', 'bar material shear modulus', required=False,
                                default=79.3e9, positive=True),
    }, one_of=(('torsional_stiffness', 'bar_radius'),)),
    'steering': Section({
        'rack_ratio': Scalar('rack_ratio', 'rack travel per steering-wheel angle (c-factor)',
                             positive=True),
        'rack_travel_limit': Scalar('length', 'rack travel from centre to either stop',
                                    positive=True),
        'rack_stiffness': Scalar('stiffness', 'rack housing mounting stiffness along y',
                                 required=False, positive=True),
        'column_stiffness': Scalar('torsional_stiffness', 'steering column torsional stiffness',
                                   required=False, positive=True),
    }),
    'alignment': Section({
        'camber': Scalar('angle', 'static camber at design (negative: top of wheel inward)'),
        'toe': Scalar('angle', 'static toe per wheel at design (positive: toe-in)'),
    }),
    'tire': Section({
        'file': Text('TeimOrbit .tir property file, path relative to the data root'),
        'aligning_normalisation': Text(
            "load the pneumatic trail and the Fx arm of Mz are normalised by: 'mf-tyre' "
            "(FNOMIN, as MF-Tyre) or 'book' (FNOMIN LFZO, Pacejka 2012 4.E42); default mf-tyre",
            choices=('mf-tyre', 'book'), required=False),
    }),
    'mass': Section({
        'sprung_mass': Scalar('mass', 'sprung (body) mass', positive=True),
        'sprung_cog': Point('sprung-mass centre of gravity, vehicle frame'),
        'sprung_inertia': Section({
            'ixx': Scalar('inertia', 'roll moment of inertia about the sprung COG', positive=True),
            'iyy': Scalar('inertia', 'pitch moment of inertia about the sprung COG',
                          positive=True),
            'izz': Scalar('inertia', 'yaw moment of inertia about the sprung COG', positive=True),
            'ixy': Scalar('inertia', 'product of inertia', required=False, default=0.0),
            'ixz': Scalar('inertia', 'product of inertia', required=False, default=0.0),
            'iyz': Scalar('inertia', 'product of inertia', required=False, default=0.0),
        }),
        'unsprung_mass_front': Scalar('mass', 'unsprung mass per front corner', positive=True),
        'unsprung_mass_rear': Scalar('mass', 'unsprung mass per rear corner', positive=True),
    }),
    'flex': Section({
        'materials': MapOf(Section({
            'youngs_modulus': Scalar('pressure', "Young's modulus E", positive=True),
            'poissons_ratio': Scalar('dimensionless', "Poisson's ratio (G = E / (2 (1 + nu)))",
                                     required=False),
            'shear_modulus': Scalar('pressure', 'shear modulus G', required=False,
                                    positive=True),
            'density': Scalar('density', 'density (0: a massless model)', minimum=0.0),
        }, one_of=(('poissons_ratio', 'shear_modulus'),)), 'materials by name'),
        'sections': MapOf(Section({
            'shape': Text('cross-section shape', choices=('solid_round', 'tube', 'rectangle',
                                                          'i_beam', 'general')),
            'diameter': Scalar('length', 'solid_round: diameter', required=False,
                               positive=True),
            'outer_diameter': Scalar('length', 'tube: outer diameter', required=False,
                                     positive=True),
            'wall': Scalar('length', 'tube: wall thickness', required=False, positive=True),
            'width': Scalar('length', "rectangle: width along the beam's local y (horizontal)",
                            required=False, positive=True),
            'height': Scalar('length', "rectangle, i_beam: height along the beam's local z "
                             "(vertical)", required=False, positive=True),
            'flange_width': Scalar('length', 'i_beam: flange width', required=False,
                                   positive=True),
            'flange_thickness': Scalar('length', 'i_beam: flange thickness', required=False,
                                       positive=True),
            'web_thickness': Scalar('length', 'i_beam: web thickness', required=False,
                                    positive=True),
            'area': Scalar('area', 'general: cross-section area', required=False,
                           positive=True),
            'iy': Scalar('area_moment', 'general: second moment of area about local y '
                         '(vertical bending)', required=False, positive=True),
            'iz': Scalar('area_moment', 'general: second moment of area about local z',
                         required=False, positive=True),
            'torsion_constant': Scalar('area_moment', 'general: torsion constant J',
                                       required=False, positive=True),
            'shear_area_y': Scalar('area', 'general: shear area along local y (omit both '
                                   'for Euler-Bernoulli)', required=False, positive=True),
            'shear_area_z': Scalar('area', 'general: shear area along local z',
                                   required=False, positive=True),
        }), 'cross-sections by name'),
        'components': MapOf(Section({
            'material': Text('material name (beam frame)', required=False),
            'section': Text('section name (beam frame; left out for the anti_roll_bar, it is the '
                            "stabilizer's bar)", required=False),
            'arm_section': Text('anti_roll_bar only: section of the two arms (default: '
                                'section)', required=False),
            'elements_per_member': Scalar('dimensionless', 'beam elements per straight '
                                          'piece of a member (1..50)', required=False,
                                          default=1.0, positive=True),
            'rigid_mass': Scalar('mass', "the part's mass in the rigid K&C model (at the "
                                 "centroid of its hard points, thesis 5.1)", required=False,
                                 minimum=0.0),
            'shape_points': MapOf(Section({
                'from': Text('member start point (hard point name)'),
                'to': Text('member end point (hard point name)'),
                'fraction': Scalar('dimensionless', 'position along the member, 0..1'),
                'offset': Point('offset from that position (left side)', required=False),
            }), 'bends of a member, defined relative to its hard points', required=False),
            'imported': Section({
                'file': Text('reduced stiffness file, path relative to the data root'),
                'format': Text('file format', choices=('plain', 'dmig')),
                'matrix': Text('dmig: the DMIG matrix name (e.g. KAAX)', required=False),
                'grids': MapOf(Text('hard point the GRID is attached to'),
                               'dmig: GRID id -> hard point', required=False),
                'length_unit': Text('dmig: length unit of the FE model (default m)',
                                    required=False),
                'force_unit': Text('dmig: force unit of the FE model (default N)',
                                   required=False),
            }, required=False),
        }), 'flexible components by name (template parts and links, anti_roll_bar)'),
    }),
    'road': Section({
        'surface': Text('the road surface: flat, an ISO 8608 random road, a single obstacle '
                        'or an OpenCRG file', choices=('flat', 'iso8608', 'obstacle', 'crg')),
        'friction': Scalar('dimensionless', "the road's friction factor (scales the tires' "
                           'LMUX and LMUY; 1: as measured)', required=False, default=1.0,
                           positive=True),
        'friction_left': Scalar('dimensionless', 'split friction: the factor left of the road '
                                "centre line (y > 0); 'friction' holds right of it",
                                required=False, positive=True),
        'road_class': Text('iso8608: the road class', choices=tuple('ABCDEFGH'),
                           required=False),
        'seed': Scalar('dimensionless', 'iso8608: seed of the random phases (an integer)',
                       required=False, minimum=0.0),
        'length': Scalar('road_length', 'iso8608 and obstacle: length of the road', required=False,
                         positive=True),
        'tracks': Text('iso8608: the two wheel tracks alike or independent',
                       choices=('parallel', 'independent'), required=False),
        'obstacle': Text('obstacle: its kind', choices=('bump', 'pothole', 'kerb'),
                         required=False),
        'height': Scalar('length', 'obstacle: height (depth of a pothole)', required=False,
                         positive=True),
        'obstacle_length': Scalar('length', 'obstacle: length along the road (kerb: its ramp)',
                                  required=False, minimum=0.0),
        'start': Scalar('road_length', 'obstacle: distance from the start of the run to it',
                        required=False, minimum=0.0),
        'side': Text('obstacle: under both wheel tracks or one', choices=('both', 'left',
                                                                          'right'),
                     required=False),
        'file': Text('crg: the OpenCRG file, path relative to the data root', required=False),
    }),
    'geometry': Section({
        'wheelbase': Scalar('length', 'front to rear axle distance at design', positive=True),
        'track_front': Scalar('length', 'front wheel-centre track at design', positive=True),
        'track_rear': Scalar('length', 'rear wheel-centre track at design', positive=True),
    }),
    'targets': Section({
        'roll_stiffness_front': Scalar('torsional_stiffness', 'front suspension roll stiffness '
                                       '(incl. anti-roll bar), design target', positive=True),
        'roll_stiffness_rear': Scalar('torsional_stiffness', 'rear suspension roll stiffness '
                                      '(incl. anti-roll bar), design target', positive=True),
        'roll_centre_height_front': Scalar('length', 'front roll-centre height above ground, '
                                           'design target'),
        'roll_centre_height_rear': Scalar('length', 'rear roll-centre height above ground, '
                                          'design target'),
    }),
    'brakes': Section({
        'front': _caliper('front'),
        'rear': _caliper('rear'),
        'master_cylinder_diameter': Scalar('length', 'master-cylinder bore', positive=True),
        'pedal_ratio': Scalar('dimensionless', 'pedal lever ratio', positive=True,
                              maximum=20.0),
        'booster_gain': Scalar('dimensionless', 'brake booster force gain (1: no booster)',
                               required=False, default=1.0, minimum=1.0, maximum=20.0),
        'knee_pressure': Scalar('pressure', "rear proportioning valve's knee pressure (left "
                                'out: no valve)', required=False, positive=True),
        'knee_slope': Scalar('dimensionless', 'rear pressure rise per master pressure above '
                             'the knee', required=False, default=1.0, minimum=0.0,
                             maximum=1.0),
        'anti_lock': Text("anti-lock brakes: 'all_wheels' (a slip controller per wheel) or "
                          "'none'; default none", choices=ANTI_LOCK, required=False),
        'abs_dump_slip': Scalar('dimensionless', 'braking slip above which the anti-lock '
                                'controller lowers the pressure', required=False,
                                default=0.15, positive=True, maximum=0.9),
        'abs_build_slip': Scalar('dimensionless', 'braking slip below which it raises it '
                                 'again (below abs_dump_slip)', required=False, default=0.08,
                                 positive=True, maximum=0.9),
    }),
    'driveline': Section({
        'layout': Text('driven axles: FWD, RWD or AWD', choices=DRIVE_LAYOUTS),
        'front_share': Scalar('dimensionless', "AWD: the front axle's share of the drive "
                              'torque (FWD: 1, RWD: 0)', required=False, minimum=0.0,
                              maximum=1.0),
        'engine_torque': Curve('angular_velocity', 'torque', 'full-load engine torque versus '
                               'engine speed (none outside the curve)', increasing=False,
                               x_minimum=0.0, y_minimum=0.0),
        'gears': Curve('dimensionless', 'dimensionless', 'gear ratio (engine over gearbox '
                       'output speed) by gear number 1, 2, ...', increasing=False,
                       x_minimum=1.0, y_minimum=0.0),
        'final_drive': Scalar('dimensionless', 'final-drive (axle) ratio', positive=True,
                              maximum=50.0),
        'efficiency': Scalar('dimensionless', 'gearbox and final-drive efficiency',
                             required=False, default=0.92, positive=True, maximum=1.0),
        'inertia': Scalar('inertia', 'rotational inertia turning at engine speed (crankshaft, '
                          'flywheel, converter, gearbox input); 0: none', required=False,
                          default=0.0, minimum=0.0),
        'shift_speed': Scalar('angular_velocity', 'engine speed of a full-throttle upshift '
                              "(default: the curve's last speed)", required=False,
                              positive=True),
        'front_differential': _differential('front'),
        'rear_differential': _differential('rear'),
    }),
    'aero': Section({
        'drag_coefficient': Scalar('dimensionless', 'drag coefficient C_d', minimum=0.0,
                                   maximum=3.0),
        'frontal_area': Scalar('area', "frontal area A (also the lift coefficients' "
                               'reference)', positive=True),
        'lift_coefficient_front': Scalar('dimensionless', 'front-axle lift coefficient '
                                         'C_l,f (positive up; negative: downforce)',
                                         required=False, default=0.0),
        'lift_coefficient_rear': Scalar('dimensionless', 'rear-axle lift coefficient C_l,r',
                                        required=False, default=0.0),
        'air_density': Scalar('density', 'air density (20 degC, 101.325 kPa: 1.204 kg/m^3)',
                              required=False, default=1.204, positive=True),
    }),
}

#: vehicle-level groups (no axle prefix)
VEHICLE_KINDS = ('mass', 'geometry', 'targets', 'steering', 'brakes', 'driveline', 'aero',
                 'road')
#: per-axle groups are named ``front_<kind>`` / ``rear_<kind>``
AXLE_KINDS = ('hardpoints', 'spring', 'damper', 'bump_stop', 'rebound_stop', 'bushings',
              'stabilizer', 'alignment', 'tire', 'flex')
#: groups a configuration must pick a variant for
REQUIRED_GROUPS = ('mass', 'geometry', 'targets',
                   *(f'{a}_{k}' for a in AXLES for k in
                     ('hardpoints', 'spring', 'damper', 'bump_stop', 'rebound_stop',
                      'alignment', 'tire')))


def group_kind(group: str) -> str:
    """Kind of an input group name (``front_spring`` -> ``spring``)."""
    for axle in AXLES:
        prefix = f'{axle}_'
        if group.startswith(prefix) and group[len(prefix):] in AXLE_KINDS:
            return group[len(prefix):]
    if group in VEHICLE_KINDS:
        return group
    raise KeyError(group)


def all_group_names() -> tuple[str, ...]:
    names = list(VEHICLE_KINDS)
    names += [f'{a}_{k}' for a in AXLES for k in AXLE_KINDS]
    return tuple(names)


# --- master files (studies): the same specs, validated by the same walker (shape.py) ---
_VARIANT = Name('variant: the file <vehicle>/<group>/<variant>.yaml',
                refusal='variant must be a plain name, found {value!r}', numbers=True)


def _variants(doc: str) -> MapOf:
    return MapOf(_VARIANT, doc, required=False, empty=True, expected='a mapping of group: variant',
                 keys=Text('input group', choices=all_group_names(),
                           refusal='unknown input group (expected one of: {choices})'))


MASTER = Section({
    'study': Section({
        'name': Text('name of the study'),
        'description': Text('what the study is for', required=False),
        'vehicle': Name('folder of the vehicle under the data root',
                        refusal="'{value}' is not a plain folder name"),
        'data_root': Text('folder of the shared data files, relative to the master file '
                          '(default: ..)', required=False),
    }),
    'defaults': _variants('variant per input group, for every configuration'),
    'configurations': MapOf(Section({
        'description': Text('what the configuration is', required=False),
        'variants': _variants('variants that differ from the defaults'),
        'overrides': MapOf(Raw('a value with its unit'), 'single values: GROUP.KEY: VALUE',
                           required=False, empty=True,
                           expected='a mapping of group.key: value'),
        'flexible': Flag('flexible components on (all of them, or the listed ones)',
                         or_list='component names'),
        'flexible_components': ListOf(Text('flexible component'), 'flexible components on',
                                      what='component names', non_empty=True),
    }, required=False), 'the configurations of the study',
        keys=Name('configuration name', refusal="configuration names may hold letters, "
                  "digits, '_', '-' and '.'"),
        expected='a non-empty mapping of configuration names'),
})


@dataclass(frozen=True)
class FieldDoc:
    key: str
    kind: str
    quantity: str
    required: bool
    doc: str


def describe(spec: Spec, prefix: str = '') -> list[FieldDoc]:
    """Flat documentation rows of a spec (used to check docs/data-format.md)."""
    rows: list[FieldDoc] = []
    if isinstance(spec, Section):
        for name, sub in spec.fields.items():
            rows += describe(sub, f'{prefix}{name}' if not prefix else f'{prefix}.{name}')
        return rows
    if isinstance(spec, MapOf):
        return describe(spec.value, f'{prefix}.<name>')
    quantity = {Scalar: lambda s: s.quantity, Curve: lambda s: f'{s.x_quantity} -> {s.y_quantity}',
                Point: lambda s: 'length', Vector: lambda s: 'dimensionless',
                Text: lambda s: 'text', Name: lambda s: 'name', Flag: lambda s: 'flag',
                ListOf: lambda s: 'list', Raw: lambda s: 'any'}[type(spec)](spec)
    rows.append(FieldDoc(prefix, type(spec).__name__.lower(), quantity, spec.required, spec.doc))
    return rows


__all__ = ['AXLES', 'KINDS', 'TEMPLATE_POINTS', 'OPTIONAL_POINTS', 'ARB_POINTS',
           'SUBFRAME_POINTS', 'BUSHING_DIRECTIONS', 'REQUIRED_GROUPS', 'DRIVE_LAYOUTS',
           'DIFFERENTIALS', 'ANTI_LOCK',
           'TEMPLATE_COMPONENTS', 'BAR_COMPONENT', 'SUBFRAME_COMPONENT', 'SECTION_SHAPES',
           'Scalar', 'Curve', 'Point', 'Vector', 'Text', 'Name', 'Flag', 'ListOf', 'Raw',
           'Section', 'MapOf', 'MASTER', 'group_kind',
           'all_group_names', 'describe']


def leaf_spec(kind: str, key: str) -> Spec | None:
    """Return the leaf spec a flat key of a group of ``kind`` refers to (None if unknown)."""
    spec: Spec = KINDS[kind]
    for part in key.split('.'):
        if isinstance(spec, MapOf):
            spec = spec.value
            continue
        if not isinstance(spec, Section) or part not in spec.fields:
            return None
        spec = spec.fields[part]
    if isinstance(spec, MapOf):
        return None
    return spec
