# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Beam cross-sections and materials: the properties a 3D beam element needs.

Local axes of a section: x along the beam, y and z in the cross-section (the
element fixes their direction, :mod:`.beam`). ``iy`` is the second moment of
area about local y (bending in the x-z plane), ``iz`` about local z, ``j`` the
torsion constant (Saint-Venant), ``shear_area_y``/``_z`` the effective shear
areas kappa*A for Timoshenko shear deformation (None: no shear deformation,
i.e. Euler-Bernoulli). All SI: m, m^2, m^4, Pa, kg/m^3.

Shear coefficients: Cowper, "The shear coefficient in Timoshenko's beam
theory", J. Appl. Mech. 33 (1966) 335-340, Table 1 (solid and hollow circle,
rectangle). Torsion constant of a rectangle: Roark's Formulas for Stress and
Strain, 7th ed., Table 10.7 case 4 (series approximation, < 0.5 % error); of
an I section: thin-walled open section sum of b t^3 / 3 (Roark Table 10.7
case 26 without fillets).
"""
from __future__ import annotations

from dataclasses import dataclass
import math

from vd_solvers.errors import SolverError


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material."""

    youngs_modulus: float  # E, Pa
    shear_modulus: float  # G, Pa
    density: float  # kg/m^3 (0 allowed: a massless model)

    def __post_init__(self) -> None:
        for name in ('youngs_modulus', 'shear_modulus'):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise SolverError(
                    f'material {name} must be a positive finite number, got {value!r}'
                )
        if not (math.isfinite(self.density) and self.density >= 0.0):
            raise SolverError(f'material density must be >= 0, got {self.density!r}')

    @property
    def poissons_ratio(self) -> float:
        return self.youngs_modulus / (2.0 * self.shear_modulus) - 1.0

    @staticmethod
    def from_poisson(youngs_modulus: float, poissons_ratio: float, density: float) -> Material:
        """E, nu, rho -> Material (G = E / (2 (1 + nu)))."""
        if not (math.isfinite(poissons_ratio) and -1.0 < poissons_ratio < 0.5):
            raise SolverError(f'poissons_ratio must lie in (-1, 0.5), got {poissons_ratio!r}')
        return Material(youngs_modulus, youngs_modulus / (2.0 * (1.0 + poissons_ratio)), density)


@dataclass(frozen=True)
class Section:
    """Section properties of a prismatic beam (see the module doc)."""

    area: float
    iy: float
    iz: float
    j: float
    shear_area_y: float | None = None
    shear_area_z: float | None = None
    shape: str = 'general'

    def __post_init__(self) -> None:
        given = {n: getattr(self, n) for n in ('area', 'iy', 'iz', 'j', 'shear_area_y',
                                               'shear_area_z') if getattr(self, n) is not None}
        _positive(self.shape, **given)


def _positive(shape: str, **values: float) -> None:
    for name, value in values.items():
        if not (math.isfinite(value) and value > 0.0):
            raise SolverError(f'{shape} section: {name} must be positive, got {value!r}')


def solid_round(diameter: float, nu: float) -> Section:
    """Solid circle of ``diameter``; Cowper kappa = 6(1+nu)/(7+6nu)."""
    _positive('solid_round', diameter=diameter)
    area = math.pi * diameter**2 / 4.0
    i = math.pi * diameter**4 / 64.0
    kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)
    return Section(area, i, i, 2.0 * i, kappa * area, kappa * area, 'solid_round')


def tube(outer_diameter: float, wall: float, nu: float) -> Section:
    """Round tube; Cowper's hollow-circle kappa with m = inner/outer diameter."""
    _positive('tube', outer_diameter=outer_diameter, wall=wall)
    if not 2.0 * wall < outer_diameter:
        raise SolverError(f'tube section: wall {wall!r} m leaves no bore in outer diameter '
                          f'{outer_diameter!r} m (use solid_round)')
    inner = outer_diameter - 2.0 * wall
    area = math.pi * (outer_diameter**2 - inner**2) / 4.0
    i = math.pi * (outer_diameter**4 - inner**4) / 64.0
    m2 = (inner / outer_diameter) ** 2
    kappa = 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / (
        (7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)
    return Section(area, i, i, 2.0 * i, kappa * area, kappa * area, 'tube')


def rectangle(width: float, height: float, nu: float) -> Section:
    """
    Solid rectangle, ``width`` along local y, ``height`` along local z.

    Cowper kappa = 10(1+nu)/(12+11nu).
    """
    _positive('rectangle', width=width, height=height)
    area = width * height
    a, b = max(width, height), min(width, height)
    j = a * b**3 * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b**4 / (12.0 * a**4)))
    kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
    return Section(area, width * height**3 / 12.0, height * width**3 / 12.0, j,
                   kappa * area, kappa * area, 'rectangle')


def i_beam(height: float, flange_width: float, flange_thickness: float,
           web_thickness: float) -> Section:
    """
    I section: web along local z (``height``), flanges along local y.

    Shear areas: the web (z) and 5/6 of the flanges (y).
    """
    _positive('i_beam', height=height, flange_width=flange_width,
              flange_thickness=flange_thickness, web_thickness=web_thickness)
    web = height - 2.0 * flange_thickness
    if not (web > 0.0 and web_thickness <= flange_width):
        raise SolverError('i_beam section: flanges thicker than half the height, or a web '
                          'wider than the flanges')
    area = 2.0 * flange_width * flange_thickness + web * web_thickness
    iy = (flange_width * height**3 - (flange_width - web_thickness) * web**3) / 12.0
    iz = (2.0 * flange_thickness * flange_width**3 + web * web_thickness**3) / 12.0
    j = (2.0 * flange_width * flange_thickness**3 + (height - flange_thickness)
         * web_thickness**3) / 3.0
    return Section(area, iy, iz, j, 5.0 / 6.0 * 2.0 * flange_width * flange_thickness,
                   height * web_thickness, 'i_beam')


SHAPES = ('solid_round', 'tube', 'rectangle', 'i_beam', 'general')
