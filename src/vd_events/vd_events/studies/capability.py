# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The analytical-capability study (thesis ch. 5, Tables 5.2.1/5.2.2).

For every K&C event of an axle, run the rigid and the flexible model on the same
configuration and say, per quantity, whether the rigid model is good enough ("Rigid")
or the flexible one is needed ("Flexible").

Criterion (documented in docs/capability.md; every tolerance configurable):

* per-step quantities -- toe, camber, wheelbase change (contact-point x), track change
  and wheel normal load (pad force), both wheels -- are compared as *changes from the
  design step*, so a static offset (the thesis' mass offset of 5.1) does not hide or
  fake a difference in shape; the offset at design is reported beside it. A cell is
  Rigid when the worst |change_flexible - change_rigid| over the steps where no bump
  or rebound stop is engaged is <= its tolerance: an absolute tolerance per quantity
  (0.05 deg toe and camber, 0.5 mm, 1 % of the design wheel load), or, if larger, a
  fraction (``RELATIVE``, 5 %) of the quantity's range in that event (rigid model).
  Steps with a stop engaged (either model) are judged separately: when they exceed
  the tolerance the cell gets the thesis' asterisk ("use flexible where the stop is
  compressed").
* derived metrics (compliance steer and camber, lateral and longitudinal stiffness,
  roll stiffness, bump steer ...) are Rigid when the flexible value is within
  ``METRIC_RELATIVE`` (5 %) of the rigid one, or within an absolute floor for
  metrics that are near zero.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
import math
from pathlib import Path
import time

import numpy as np

from vd_data_server.errors import DataError
from vd_data_server.master import flex_components
from vd_data_server.ros.qos import RESULTS, profile_of
from vd_events.bags.bag import BagWriter, check_bag_path, log_time
from vd_events.bags.outcomes import outcome_messages
from vd_events.errors import RunError
from vd_events.orchestration.inprocess import run_inprocess
from vd_events.orchestration.requests import RunRequest, validate
from vd_interfaces.msg import CapabilityCell, CapabilityTable
from vd_solvers.constants import DEG
from vd_solvers.conversions import TIME_AXIS, run_stamp, stamp_ns, time_msg
from vd_solvers.kc.cache import kc_outcome
from vd_solvers.kc.from_config import RIGID_LIMIT_BAR_SCALE, RIGID_LIMIT_SCALE
from vd_solvers.results import EventOutcome

#: per-step quantities: channel stem(s), SI unit, absolute tolerance (SI; None: wheel load)
QUANTITIES: Mapping[str, tuple[tuple[str, ...], str, float | None]] = {
    'toe': (('toe_left', 'toe_right'), 'rad', 0.05 * DEG),
    'camber': (('camber_left', 'camber_right'), 'rad', 0.05 * DEG),
    'wheelbase': (('contact_point_x_left', 'contact_point_x_right'), 'm', 0.5e-3),
    'track': (('track',), 'm', 0.5e-3),
    'wheel_load': (('pad_force_left', 'pad_force_right'), 'N', None),
}
#: wheel-load tolerance as a fraction of the design wheel load
LOAD_FRACTION = 0.01
#: a difference this fraction of the quantity's range in the event is also acceptable
RELATIVE = 0.05
#: derived metrics compared per event, with the absolute floor in the metric's SI unit
METRICS: Mapping[str, Mapping[str, float]] = {
    'parallel_wheel_travel': {'bump_steer': 0.5 * DEG, 'camber_gain': 0.5 * DEG,  # rad/m
                              'wheel_rate': 500.0, 'roll_centre_height_kinematic': 0.002},
    'opposite_wheel_travel': {'roll_stiffness': 10.0 / DEG,  # N*m/rad (10 N*m/deg)
                              'roll_steer': 0.005, 'roll_camber': 0.005},  # rad/rad
    'lateral_force': {'lateral_compliance_steer': 0.01 * DEG / 1e3,  # rad/N (0.01 deg/kN)
                      'lateral_compliance_camber': 0.01 * DEG / 1e3,
                      'lateral_stiffness': 1e4},  # N/m
    'longitudinal_force': {'longitudinal_stiffness_braking': 1e4,
                           'longitudinal_stiffness_traction': 1e4,
                           'longitudinal_compliance_steer_braking': 0.01 * DEG / 1e3},
    'aligning_torque': {'aligning_torque_compliance_steer': 0.01 * DEG / 1e3},  # rad/(N*m)
    'steering': {'steering_ratio': 0.1, 'ackermann': 1.0},
}
METRIC_RELATIVE = 0.05
#: the rigid-limit check (see :func:`rigid_limit_cells`): the flexible model at its rigid
#: limit must reproduce every rigid metric within this fraction of the metric's verdict
#: tolerance, so that whatever still differs between the two models' data cannot decide
#: a verdict
LIMIT_FRACTION = 0.1
EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel', 'lateral_force',
          'longitudinal_force', 'aligning_torque', 'steering')
STOPS = ('bump_stop_force_left', 'bump_stop_force_right', 'rebound_stop_force_left',
         'rebound_stop_force_right')


@dataclass(frozen=True)
class Cell:
    event: str
    quantity: str
    unit: str
    max_difference: float
    tolerance: float
    verdict: str
    stop_engaged: bool = False
    stop_difference: float = 0.0
    stop_needs_flexible: bool = False
    design_offset: float = 0.0
    rigid_value: float = 0.0
    flexible_value: float = 0.0

    @property
    def label(self) -> str:
        return self.verdict + ('*' if self.stop_needs_flexible else '')


@dataclass(frozen=True)
class Table:
    configuration: str
    data_hash: str
    axle: str
    components: tuple[str, ...]
    cells: tuple[Cell, ...]
    metrics: tuple[Cell, ...]
    notes: tuple[str, ...] = field(default_factory=tuple)
    rigid_limit: tuple[Cell, ...] = ()

    def to_json(self) -> dict:
        def cell(c: Cell) -> dict:
            return {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                    for k, v in c.__dict__.items()} | {'label': c.label}

        return {'configuration': self.configuration, 'data_hash': self.data_hash,
                'axle': self.axle, 'flexible_components': list(self.components),
                'cells': [cell(c) for c in self.cells],
                'metrics': [cell(c) for c in self.metrics], 'notes': list(self.notes),
                'rigid_limit': [cell(c) for c in self.rigid_limit]}


#: the swept channel of each event, whose zero is the design step
SWEEP = {'parallel_wheel_travel': 'pad_travel_left', 'opposite_wheel_travel': 'pad_travel_left',
         'lateral_force': 'applied_force', 'longitudinal_force': 'applied_force',
         'aligning_torque': 'applied_moment', 'steering': 'steering_wheel_angle'}


def _design_step(outcome: EventOutcome) -> int:
    ch = outcome.channels.get(SWEEP.get(outcome.event, ''))
    return int(np.argmin(np.abs(ch.values))) if ch is not None else outcome.n_steps // 2


def _stop_mask(*outcomes: EventOutcome) -> np.ndarray:
    n = outcomes[0].n_steps
    mask = np.zeros(n, dtype=bool)
    for o in outcomes:
        for name in STOPS:
            ch = o.channels.get(name)
            if ch is not None:
                mask |= np.asarray(ch.values) > 0.0
    return mask


def compare(rigid: EventOutcome, flexible: EventOutcome,
            tolerances: Mapping[str, float] | None = None) -> tuple[list[Cell], list[Cell]]:
    """
    Return the cells (per-step quantities) and metric cells of one event.

    See the module doc. ``tolerances`` overrides the absolute tolerance per quantity (SI).
    """
    if rigid.n_steps != flexible.n_steps:
        raise ValueError(f'{rigid.event}: the rigid and flexible runs have different steps')
    event = rigid.event
    at = _design_step(rigid)
    stops = _stop_mask(rigid, flexible)
    cells = []
    for quantity, (names, unit, tol) in QUANTITIES.items():
        worst = stop_worst = 0.0
        offset = 0.0
        span = 0.0
        tolerance = (tolerances or {}).get(quantity, tol)
        for name in names:
            r = np.asarray(rigid.channels[name].values, dtype=float)
            f = np.asarray(flexible.channels[name].values, dtype=float)
            if tolerance is None:
                tolerance = LOAD_FRACTION * abs(float(r[at]))
            gap = np.abs((f - f[at]) - (r - r[at]))
            free = gap[~stops]
            worst = max(worst, float(free.max(initial=0.0)))
            stop_worst = max(stop_worst, float(gap[stops].max(initial=0.0)))
            span = max(span, float(np.ptp(r[~stops])) if np.any(~stops) else 0.0)
            if abs(f[at] - r[at]) > abs(offset):
                offset = float(f[at] - r[at])
        assert tolerance is not None  # the wheel load's is set from the design load above
        limit = max(float(tolerance), RELATIVE * span)
        cells.append(Cell(event, quantity, unit, worst, limit,
                          'Rigid' if worst <= limit else 'Flexible', bool(np.any(stops)),
                          stop_worst, bool(stop_worst > limit), offset))
    metric_cells = []
    for name, floor in METRICS.get(event, {}).items():
        if name not in rigid.metrics or name not in flexible.metrics:
            continue
        a, b = rigid.metrics[name].value, flexible.metrics[name].value
        if not (math.isfinite(a) and math.isfinite(b)):
            diff, limit, verdict = math.inf, 0.0, 'Flexible'
        else:
            diff, limit = abs(b - a), max(floor, METRIC_RELATIVE * abs(a))
            verdict = 'Rigid' if diff <= limit else 'Flexible'
        metric_cells.append(Cell(event, name, rigid.metrics[name].unit, diff, limit, verdict,
                                 rigid_value=a, flexible_value=b))
    return cells, metric_cells


def rigid_limit_cells(pairs: Sequence[tuple[EventOutcome, EventOutcome]]) -> list[Cell]:
    """
    Compare the rigid model with the flexible one at its rigid limit, metric by metric.

    ``pairs``: (rigid, flexible at the rigid limit) per event. A cell is Rigid when the
    two agree within ``LIMIT_FRACTION`` of the metric's verdict tolerance: both models
    then see the same data. The per-step curves are not part of the check: at the ends of
    a large travel the rigid bar's torsion law (sin of the twist) and the beam's
    (small-angle, co-rotated) part by a few percent, a difference of model, not of data.
    """
    out = []
    for rigid, limit in pairs:
        for c in compare(rigid, limit)[1]:
            tol = LIMIT_FRACTION * c.tolerance
            out.append(replace(c, tolerance=tol,
                               verdict='Rigid' if c.max_difference <= tol else 'Flexible'))
    return out


def rigid_limit_line(cells: Sequence[Cell]) -> str:
    """Return the table's line on the rigid-limit check."""
    worst = max(cells, key=lambda c: c.max_difference / c.tolerance if c.tolerance else 0.0)
    failed = [c for c in cells if c.verdict != 'Rigid']
    head = ('rigid limit: the flexible model with its components '
            f"{RIGID_LIMIT_SCALE:.0e} times stiffer (the bar's arms {RIGID_LIMIT_BAR_SCALE:.0e}, "
            'its torsion part as it is) ')
    share = f'{worst.max_difference / worst.tolerance * LIMIT_FRACTION:.2%}'
    if failed:
        return head + (f'does NOT reproduce the rigid model: {len(failed)} of {len(cells)} '
                       f'metrics differ by more than {LIMIT_FRACTION:.0%} of their verdict '
                       f'tolerance, worst {worst.quantity} ({worst.event}): {share} of it')
    return head + (f'reproduces all {len(cells)} rigid metrics within {LIMIT_FRACTION:.0%} of '
                   f'their verdict tolerance (worst {worst.quantity}, {worst.event}: {share} '
                   'of it): both models see the same data')


def build_table(pairs: Sequence[tuple[EventOutcome, EventOutcome]], components: Sequence[str],
                tolerances: Mapping[str, float] | None = None,
                limit: Sequence[Cell] = ()) -> Table:
    """
    Build the table of one axle from (rigid, flexible) outcome pairs.

    ``limit``: the rigid-limit cells of the axle (:func:`rigid_limit_cells`), stated in
    the table's first note.
    """
    first = pairs[0][0]
    cells: list[Cell] = []
    metrics: list[Cell] = []
    for rigid, flexible in pairs:
        c, m = compare(rigid, flexible, tolerances)
        cells += c
        metrics += m
    notes = ((rigid_limit_line(limit),) if limit else ()) + (
             f"Rigid: worst |change flexible - change rigid| over the steps without a stop "
             f"engaged <= max(absolute tolerance, {RELATIVE:.0%} of the quantity's range in "
             f"the event); wheel load tolerance {LOAD_FRACTION:.0%} of the design wheel load; "
             f"* = flexible needed where a bump or rebound stop is engaged; metrics Rigid "
             f"within {METRIC_RELATIVE:.0%}",)
    return Table(first.configuration, first.data_hash, first.axle, tuple(components),
                 tuple(cells), tuple(metrics), notes, tuple(limit))


def to_msg(table: Table, stamp=None):

    def cell(c: Cell) -> CapabilityCell:
        return CapabilityCell(event=c.event, quantity=c.quantity, unit=c.unit,
                              max_difference=float(c.max_difference),
                              tolerance=float(c.tolerance), verdict=c.verdict,
                              stop_engaged=c.stop_engaged,
                              stop_difference=float(c.stop_difference),
                              stop_needs_flexible=c.stop_needs_flexible,
                              design_offset=float(c.design_offset),
                              rigid_value=float(c.rigid_value),
                              flexible_value=float(c.flexible_value))

    msg = CapabilityTable(configuration=table.configuration, data_hash=table.data_hash,
                          axle=table.axle, flexible_components=list(table.components),
                          cells=[cell(c) for c in table.cells],
                          metrics=[cell(c) for c in table.metrics], notes=list(table.notes))
    if stamp is not None:
        msg.stamp = stamp
    return msg


def from_msg(msg) -> Table:
    def cell(c) -> Cell:
        return Cell(c.event, c.quantity, c.unit, c.max_difference, c.tolerance, c.verdict,
                    c.stop_engaged, c.stop_difference, c.stop_needs_flexible, c.design_offset,
                    c.rigid_value, c.flexible_value)

    return Table(msg.configuration, msg.data_hash, msg.axle, tuple(msg.flexible_components),
                 tuple(cell(c) for c in msg.cells), tuple(cell(c) for c in msg.metrics),
                 tuple(msg.notes))


TOPIC = '/vd/capability/table'


def run_study(master, study, configuration: str, axles: Sequence[str], out,
              parameters: Sequence[str] = (), tolerances: Mapping[str, float] | None = None,
              progress=None, on_done=None) -> list[Table]:
    """
    Run every K&C event rigid and flexible on ``axles`` and record them; return the tables.

    ``on_done(RunOutcome)`` hears each run as it completes.

    Solved in-process (``orchestration.inprocess``, as ``vd run``); both runs of every
    event -- their EventResults and per-step KcStates and wheel frames as the solver
    answers a goal, on the process's time axis --
    and each axle's table go to one bag, ``out/capability_<configuration>``.

    One bag for the study: a recorder per run would cost more than the runs themselves.
    """
    out = Path(out)
    config = study.configurations[configuration]
    defined = flex_components(config.groups)
    requests = []
    for axle in axles:
        if axle not in defined:
            raise DataError(f"configuration '{configuration}' has no flexible components on "
                            f"the {axle} axle (no {axle}_flex group): nothing to compare",
                            file=str(master))
        for event in EVENTS:
            if event == 'steering' and (axle != 'front' or 'steering' not in config.groups):
                continue
            for fidelity in ('rigid', 'flexible'):
                requests.append(RunRequest(
                    event=event, configuration=configuration, model='kc', fidelity=fidelity,
                    axle=axle, parameters=tuple(parameters)))
    bag = out / f'capability_{configuration}'
    requests = [validate(study, request) for request in requests]
    check_bag_path(bag)
    results = run_inprocess(Path(master), requests, progress, study=study, on_done=on_done)
    errors = [r.error for r in results if r.error]
    if errors:
        raise RunError('; '.join(errors))
    tables = []
    for axle in axles:
        mine = [r for r in results if r.request.axle == axle]
        pairs = [(a.outcome, b.outcome) for a, b in zip(mine[0::2], mine[1::2])]
        # Before any verdict: the flexible model at its rigid limit must be the rigid model
        # (assembled once per axle, every event runs on it; the outcomes are kept on disk
        # per data and code, so a second study of the same data pays nothing for them).
        limit = rigid_limit_cells([
            (rigid, kc_outcome(config, rigid.event, axle, tuple(parameters),
                               fidelity='flexible', at_rigid_limit=True))
            for rigid, _ in pairs if rigid is not None])
        if any(c.verdict != 'Rigid' for c in limit):
            raise RunError(f"configuration '{configuration}', {axle} axle: "
                           + rigid_limit_line(limit) + '; the rigid and flexible data '
                           'describe different parts: no verdicts')
        chosen = [c for c in config.flexible_components if c in defined[axle]]
        tables.append(build_table(pairs, chosen or defined[axle],  # type: ignore[arg-type]
                                  tolerances, limit))
    writer = BagWriter(bag, {'vd.configuration': configuration,
                             'vd.data_hash': tables[0].data_hash,
                             'vd.master_file': str(master), 'vd.model': 'kc',
                             'vd.fidelity': 'rigid and flexible',
                             'vd.kind': 'capability study', 'vd.axles': ' '.join(axles)})
    try:
        for result in results:
            assert result.outcome is not None
            start = stamp_ns(run_stamp(result.outcome, time.time_ns()))
            for topic, msg in outcome_messages(result.outcome, start):
                writer.write(topic, msg, log_time(msg, 0), [profile_of(topic)])
        for table in tables:
            msg = to_msg(table, time_msg(TIME_AXIS.claim(time.time_ns(), 0.0)))
            writer.write(TOPIC, msg, log_time(msg, 0), [RESULTS])
        writer.close()
    except BaseException:
        writer.abort()
        raise
    return tables
