# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd replay TEST_BAG``: a vehicle log's inputs through the models, compared with the log.

The log's steering and speed drive the bicycle and the full-vehicle models of a
configuration (open-loop validation).

The replayed runs are EventOutcomes of the log's event (models ``bicycle`` and
``vehicle``), written to their own bag like any simulation, and compared with the log
they replay by :mod:`.compare` (yaw rate, lateral acceleration, sideslip where logged):
each run names its log's SHA-256 (``compare.REPLAY_NOTE``), so a study report pairs it
with that log only, never with the other logs of the same event. The bicycle model
takes the steering ratio of the full vehicle's K&C steering map of the same configuration
and its axle properties from the K&C results of the same data hash, as ``vd run`` does.
"""
from __future__ import annotations

from collections.abc import Sequence
import dataclasses
import datetime as dt
from pathlib import Path

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_events.bags.bag import check_bag_path
from vd_events.bags.outcomes import write_outcomes
from vd_events.errors import InputError
from vd_events.measured.compare import INPUTS_NOTE, REPLAY_NOTE, compare, load_outcomes
from vd_solvers import __version__
from vd_solvers.analytical.from_config import static_wheel_loads, vehicle_params
from vd_solvers.analytical.kc_link import try_kc_inputs
from vd_solvers.analytical.replay import replay_bicycle
from vd_solvers.errors import SolverError
from vd_solvers.results import Channel, EventOutcome, Metric
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.replay import replay_vehicle

MODELS = ('bicycle', 'vehicle')
NEEDED = ('time', 'steering_wheel_angle', 'speed')
#: what the replay takes from the log (not compared)
INPUTS = ('steering_wheel_angle', 'speed')
UNITS = {'time': 's', 'yaw_rate': 'rad/s', 'lateral_acceleration': 'm/s^2', 'sideslip': 'rad',
         'lateral_velocity': 'm/s', 'speed': 'm/s', 'steering_wheel_angle': 'rad',
         'steer_angle': 'rad'}


def bicycle_outcome(config, test: EventOutcome, steering_ratio: float,
                    ratio_source: str) -> EventOutcome:

    kc = try_kc_inputs(config, static_wheel_loads(config))
    p = vehicle_params(config) if isinstance(kc, str) else vehicle_params(
        config, kc.suspension, kc.compliance)
    ch = {k: test.channels[k].values for k in NEEDED}
    out = replay_bicycle(p, steering_ratio, ch['time'], ch['steering_wheel_angle'], ch['speed'])
    notes = ('open-loop replay of a log through the linear single track (RK45, inputs '
             'linear between samples)',
             f'steering ratio {steering_ratio:.3f}: {ratio_source}',
             'axle properties: ' + ('bare tire and design targets' if isinstance(kc, str)
                                    else f'K&C of data hash {config.data_hash}'))
    return EventOutcome(event=test.event, configuration=config.name, model='bicycle',
                        fidelity='rigid', axle='', data_hash=config.data_hash,
                        metrics={'steering_ratio': Metric(steering_ratio, '-', ratio_source)},
                        channels={k: Channel(UNITS[k], v) for k, v in out.items()}, notes=notes)


def replay_outcomes(config, test: EventOutcome, models: Sequence[str]) -> list[EventOutcome]:
    """Replay ``test`` on ``config`` with each of ``models``."""
    missing = [k for k in NEEDED if k not in test.channels]
    if missing:
        raise InputError(test.configuration, f"the log of '{test.event}' has no "
                         f"{', '.join(missing)}: a replay needs time, steering-wheel angle "
                         'and speed')
    unknown = [m for m in models if m not in MODELS]
    if unknown or not models:
        raise InputError('--models', f"replay models are {', '.join(MODELS)}, found "
                         f"{', '.join(unknown) or 'none'}")
    try:
        vehicle = VehicleModel(config)
        yaw_rate0 = float(test.channels['yaw_rate'].values[0]) \
            if 'yaw_rate' in test.channels else 0.0
        out = []
        for name in models:
            if name == 'vehicle':
                out.append(replay_vehicle(config, test.channels['time'].values,
                                          test.channels['steering_wheel_angle'].values,
                                          test.channels['speed'].values, event=test.event,
                                          initial_yaw_rate=yaw_rate0, model=vehicle))
            else:
                out.append(bicycle_outcome(config, test, vehicle.maps.steering_ratio,
                                           vehicle.maps.provenance['steering']))
    except SolverError as err:
        raise InputError(config.name, str(err)) from None
    return out


def replay_bag(test_bag: Path, models: Sequence[str], config_name: str | None,
               master: Path | None, bag: Path) -> dict:
    """
    Replay every vehicle log of ``test_bag``; write the runs' bag; compare.

    Returns the bag, the comparisons as JSON and (``_comparisons``) as objects, whose page
    ``reports.compare.write_compare_page`` writes.
    """
    check_bag_path(bag)
    tests = [o for o in load_outcomes(test_bag) if o.model == 'test']
    if not tests:
        raise InputError(test_bag, 'no vehicle log (model test) in the bag (vd import '
                         'writes one from a .vbo or a CSV log)')
    master = master or default_master()
    study = load_study(master)
    name = config_name or study.configuration_names[0]
    if name not in study.configurations:
        raise InputError(master, f"configuration '{name}' does not exist (available: "
                         f"{', '.join(study.configuration_names)})")
    config = study.configurations[name]
    pairs = [(dataclasses.replace(run, notes=(*run.notes, INPUTS_NOTE + ', '.join(INPUTS),
                                              REPLAY_NOTE + test.data_hash)), test)
             for test in tests for run in replay_outcomes(config, test, models)]
    runs = [run for run, _ in pairs]
    comparisons = [compare(run, test) for run, test in pairs]
    now = int(dt.datetime.now(dt.timezone.utc).timestamp()) * 1_000_000_000
    path = write_outcomes(bag, [(r, now) for r in runs], {
        'vd.kind': 'replay of a vehicle log', 'vd.configuration': name,
        'vd.data_hash': config.data_hash, 'vd.master_file': str(master),
        'vd.models': ' '.join(models), 'vd.test_bag': str(test_bag),
        'vd.software_version': __version__}, master_file=str(master))
    return {'bag': str(path),
            'comparisons': [c.to_json() for c in comparisons], '_comparisons': comparisons}


__all__ = ['replay_bag', 'replay_outcomes', 'MODELS']
