# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A tire's data sheet: the key numbers of a .tir file and its characteristic curves.

What ``vd tire FILE`` shows before a file is used: the version and its switches, size,
loads and pressures, the stiffnesses, peak friction, trail, radii and relaxation lengths
at the nominal load, the ranges the file is valid for, and pure-slip curves Fx(kappa),
Fy(alpha), Mz(alpha) swept over load, inflation pressure and camber. Everything comes
from :class:`~vd_solvers.tire.magic_formula.MagicFormula` (file convention, SI).
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Final

import numpy as np

from vd_data_server.tir import TireProperties
from vd_solvers.tire.magic_formula import MagicFormula

__all__ = ['Curve', 'Row', 'Sweep', 'characteristics', 'sweeps']

#: loads of the load sweep, x FNOMIN (clipped to the file's FZMAX)
LOAD_FACTORS: Final[tuple[float, ...]] = (0.5, 1.0, 1.5)
#: cambers of the camber sweep, rad (clipped to CAMMIN..CAMMAX)
CAMBERS: Final[tuple[float, ...]] = (-math.radians(4.0), 0.0, math.radians(4.0))
#: slip ranges plotted (clipped to the file's KPUMIN..KPUMAX, ALPMIN..ALPMAX)
KAPPA_RANGE: Final[tuple[float, float]] = (-0.3, 0.3)
ALPHA_RANGE: Final[tuple[float, float]] = (-math.radians(15.0), math.radians(15.0))
POINTS: Final[int] = 121
# finite step of the camber stiffness, rad
_CAMBER_STEP: Final[float] = 1e-4
_VERSIONS: Final[dict[str, str]] = {'PAC2002': 'PAC2002 (MF 5.2)', 'MF52': 'MF-Tyre 5.2',
                                    'MF61': 'MF-Tyre 6.1', 'MF62': 'MF-Tyre 6.2'}
_USE_MODES: Final[dict[int, str]] = {
    1: 'Fx and My only', 2: 'Fy, Mx and Mz only', 3: 'uncombined', 4: 'combined slip',
    5: 'combined slip with turn slip'}


@dataclass(frozen=True)
class Row:
    """One line of the sheet: a value in SI with its unit, or a text (unit '')."""

    name: str
    value: float | str
    unit: str = ''


@dataclass(frozen=True)
class Curve:
    """One pure-slip curve: Fx(kappa), Fy(alpha), Mz(alpha) at one condition."""

    label: str
    kappa: np.ndarray
    fx: np.ndarray
    alpha: np.ndarray  # rad
    fy: np.ndarray
    mz: np.ndarray


@dataclass(frozen=True)
class Sweep:
    """Curves over one varied quantity (load, pressure or camber)."""

    title: str
    curves: tuple[Curve, ...]


def characteristics(mf: MagicFormula) -> tuple[list[Row], list[str]]:
    """Return the key data of the tire and warnings about it (module doc)."""
    props = mf.props
    rows = [
        Row('version', f'{_VERSIONS[props.file_format]} ({_declared(props)})'),
        Row('use mode', _use_mode(props)),
        Row('measured on', str(props.get('MODEL', 'TYRESIDE', 'not given'))),
        Row('aligning moment normalised by', 'FNOMIN (MF-Tyre)'
            if props.aligning_normalisation == 'mf-tyre' else "Fz0' = FNOMIN LFZO (book)"),
        Row('unloaded radius', props.unloaded_radius, 'm'),
    ]
    for key, name in (('WIDTH', 'width'), ('ASPECT_RATIO', 'aspect ratio'),
                      ('RIM_RADIUS', 'rim radius')):
        value = props.get('DIMENSION', key, math.nan)
        if isinstance(value, float) and not math.isnan(value):
            rows.append(Row(name, value, '' if key == 'ASPECT_RATIO' else 'm'))
    fz = props.fnomin
    rows += [Row('nominal load FNOMIN', fz, 'N'),
             Row("scaled nominal load Fz0' (LFZO)", mf.nominal_load, 'N')]
    if mf.inflation_pressure > 0.0:
        rows.append(Row('inflation pressure', mf.inflation_pressure, 'Pa'))
        rows += _pair(props, 'OPERATING_CONDITIONS', 'NOMPRES', 'nominal pressure', 'Pa')
        rows += _pair(props, 'TIRE_CONDITIONS', 'IP_NOM', 'nominal pressure', 'Pa')
    loaded, effective = (float(r) for r in mf.radii(fz)) if mf.vertical_stiffness > 0.0 \
        else (math.nan, math.nan)
    sigma_k, sigma_a = (float(s) for s in mf.relaxation_lengths(fz))
    fy_peak, fx_peak = _peaks(mf, fz)
    camber_stiffness = float((mf.fy(fz, 0.0, _CAMBER_STEP) - mf.fy(fz, 0.0, -_CAMBER_STEP))
                             / (2.0 * _CAMBER_STEP))
    rows += [
        Row('vertical stiffness (at the pressure)', mf.vertical_stiffness, 'N/m'),
        Row('loaded radius at FNOMIN', loaded, 'm'),
        Row('effective rolling radius at FNOMIN', effective, 'm'),
        Row('cornering stiffness dFy/dalpha at FNOMIN', float(mf.cornering_stiffness(fz)),
            'N/rad'),
        Row('camber stiffness dFy/dgamma at FNOMIN', camber_stiffness, 'N/rad'),
        Row('slip stiffness dFx/dkappa at FNOMIN', float(mf.slip_stiffness(fz)), 'N'),
        Row('peak |Fx| / Fz at FNOMIN', fx_peak / fz, ''),
        Row('peak |Fy| / Fz at FNOMIN', fy_peak / fz, ''),
        Row('pneumatic trail at FNOMIN', float(mf.pneumatic_trail(fz)), 'm'),
        Row('relaxation length sigma_kappa at FNOMIN', sigma_k, 'm'),
        Row('relaxation length sigma_alpha at FNOMIN', sigma_a, 'm'),
    ]
    for block, low, high, name, unit in (
            ('VERTICAL_FORCE_RANGE', 'FZMIN', 'FZMAX', 'valid load', 'N'),
            ('LONG_SLIP_RANGE', 'KPUMIN', 'KPUMAX', 'valid slip ratio', ''),
            ('SLIP_ANGLE_RANGE', 'ALPMIN', 'ALPMAX', 'valid slip angle', 'rad'),
            ('INCLINATION_ANGLE_RANGE', 'CAMMIN', 'CAMMAX', 'valid inclination', 'rad'),
            ('INFLATION_PRESSURE_RANGE', 'PRESMIN', 'PRESMAX', 'valid pressure', 'Pa')):
        given = props.sections.get(block, {})
        if low in given and high in given:
            rows.append(Row(f'{name} from', given[low], unit))
            rows.append(Row(f'{name} to', given[high], unit))
    rows.append(Row('has', ', '.join(_contents(props)) or 'pure slip only'))
    return rows, _warnings(mf, fz)


def sweeps(mf: MagicFormula) -> list[Sweep]:
    """Pure-slip curves swept over load, inflation pressure and camber (module doc)."""
    props = mf.props
    fz0 = props.fnomin
    kappa = np.linspace(*_clip_range(props, 'LONG_SLIP_RANGE', 'KPUMIN', 'KPUMAX',
                                     KAPPA_RANGE), POINTS)
    alpha = np.linspace(*_clip_range(props, 'SLIP_ANGLE_RANGE', 'ALPMIN', 'ALPMAX',
                                     ALPHA_RANGE), POINTS)
    fz_max = _number(props, 'VERTICAL_FORCE_RANGE', 'FZMAX', math.inf)
    loads = [f * fz0 for f in LOAD_FACTORS if f * fz0 <= fz_max] or [fz0]
    result = [Sweep('load', tuple(_curve(mf, f'Fz {fz:.0f} N', fz, 0.0, kappa, alpha)
                                  for fz in loads))]
    if mf.inflation_pressure > 0.0:
        low = _number(props, 'INFLATION_PRESSURE_RANGE', 'PRESMIN', 0.8 * mf.inflation_pressure)
        high = _number(props, 'INFLATION_PRESSURE_RANGE', 'PRESMAX', 1.2 * mf.inflation_pressure)
        pressures = sorted({low, mf.inflation_pressure, high})
        result.append(Sweep('inflation pressure', tuple(
            _curve(MagicFormula(props, side=mf.side, pressure=p), f'{p / 1e5:.2f} bar', fz0,
                   0.0, kappa, alpha) for p in pressures)))
    cam_low = _number(props, 'INCLINATION_ANGLE_RANGE', 'CAMMIN', -math.inf)
    cam_high = _number(props, 'INCLINATION_ANGLE_RANGE', 'CAMMAX', math.inf)
    cambers = [min(max(g, cam_low), cam_high) for g in CAMBERS]
    result.append(Sweep('inclination', tuple(
        _curve(mf, f'gamma {math.degrees(g):+.1f} deg', fz0, g, kappa, alpha)
        for g in dict.fromkeys(cambers))))
    return result


def _curve(mf: MagicFormula, label: str, fz: float, gamma: float, kappa: np.ndarray,
           alpha: np.ndarray) -> Curve:
    longitudinal = mf.steady_state(fz, kappa, 0.0, gamma, 0.0)
    lateral = mf.steady_state(fz, 0.0, alpha, gamma, 0.0)
    return Curve(label, kappa, longitudinal.fx, alpha, lateral.fy, lateral.mz)


def _peaks(mf: MagicFormula, fz: float) -> tuple[float, float]:
    """Largest |Fy| and |Fx| over slip at ``fz``, zero camber, N."""
    alpha = np.linspace(-math.radians(30.0), math.radians(30.0), 601)
    kappa = np.linspace(-1.0, 1.0, 801)
    return float(np.max(np.abs(mf.fy(fz, alpha)))), float(np.max(np.abs(mf.fx(fz, kappa))))


def _declared(props: TireProperties) -> str:
    model = props.sections.get('MODEL', {})
    parts = []
    for key in ('FITTYP', 'PROPERTY_FILE_FORMAT'):
        value = model.get(key)
        if value is not None:
            parts.append(f'{key} {value:g}' if isinstance(value, float) else f'{key} {value}')
    return ', '.join(parts)


def _use_mode(props: TireProperties) -> str:
    mode = props.get('MODEL', 'USE_MODE', 4.0)
    if not isinstance(mode, float):
        return str(mode)
    digit = int(mode) % 10
    return f'{int(mode)}: {_USE_MODES.get(digit, "not evaluated")}'


def _pair(props: TireProperties, block: str, key: str, name: str, unit: str) -> list[Row]:
    value = props.sections.get(block, {}).get(key)
    return [Row(name, value, unit)] if isinstance(value, float) else []


def _number(props: TireProperties, block: str, key: str, default: float) -> float:
    value = props.sections.get(block, {}).get(key)
    return value if isinstance(value, float) else default


def _clip_range(props: TireProperties, block: str, low: str, high: str,
                wanted: tuple[float, float]) -> tuple[float, float]:
    return (max(wanted[0], _number(props, block, low, -math.inf)),
            min(wanted[1], _number(props, block, high, math.inf)))


def _contents(props: TireProperties) -> list[str]:
    """Return the effects the file's coefficients describe."""
    sections = props.sections

    def any_of(block: str, prefix: tuple[str, ...]) -> bool:
        return any(k.startswith(prefix) and isinstance(v, float) and v != 0.0
                   for k, v in sections.get(block, {}).items())

    found = []
    if any_of('LONGITUDINAL_COEFFICIENTS', ('PPX',)) or any_of('LATERAL_COEFFICIENTS', ('PPY',)):
        found.append('inflation pressure')
    if any_of('LONGITUDINAL_COEFFICIENTS', ('RBX',)) or any_of('LATERAL_COEFFICIENTS',
                                                               ('RBY',)):
        found.append('combined slip')
    if any_of('OVERTURNING_COEFFICIENTS', ('QSX',)):
        found.append('overturning moment')
    if any_of('ROLLING_COEFFICIENTS', ('QSY',)):
        found.append('rolling resistance')
    if any_of('TURNSLIP_COEFFICIENTS', ('P', 'Q')):
        found.append('turn slip coefficients')
    if any_of('STRUCTURAL', ('LONGITUDINAL_STIFFNESS', 'LATERAL_STIFFNESS')) or any_of(
            'LONGITUDINAL_COEFFICIENTS', ('PTX',)):
        found.append('relaxation lengths')
    return found


def _warnings(mf: MagicFormula, fz: float) -> list[str]:
    path = mf.props.path
    warnings = []
    if float(mf.cornering_stiffness(fz)) > 0.0:
        warnings.append(f'{path}: the cornering stiffness is positive at FNOMIN: a positive '
                        'slip angle gives a positive Fy, opposite to the TYDEX W-axis system '
                        'vd expects (the bicycle fit refuses such a file)')
    if float(mf.pneumatic_trail(fz)) < 0.0:
        warnings.append(f'{path}: the pneumatic trail is negative at FNOMIN')
    low = _number(mf.props, 'INFLATION_PRESSURE_RANGE', 'PRESMIN', -math.inf)
    high = _number(mf.props, 'INFLATION_PRESSURE_RANGE', 'PRESMAX', math.inf)
    if mf.inflation_pressure > 0.0 and not low <= mf.inflation_pressure <= high:
        warnings.append(f'{path}: the inflation pressure {mf.inflation_pressure:g} Pa is '
                        f'outside the range the file is valid for, {low:g}..{high:g} Pa')
    return warnings
