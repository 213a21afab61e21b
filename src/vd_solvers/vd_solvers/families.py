# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The solver families: which node serves which models and events, under which names.

One definition, used by the solver nodes, the event runner, the recorder, ``vd launch``
and the launch files. ROS-free: the names are relative (they resolve in the node's
namespace, ``/vd`` by default, see ``vd_data_server.ros.names``).

A family's default instance (node name = its executable) serves ``<family>/run_event``;
another instance of the same executable, started under another node name (``-r
__node:=kc_solver_2``), serves ``<family>/<node name>/run_event``, so instances can be
told apart. All instances of a family publish on the family's ``result`` and ``state``
topics; each result names its configuration, event, model and data hash.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from .errors import SolverError
from .results import FIDELITIES, FLEXIBLE_MODELS


@dataclass(frozen=True)
class Family:
    """A solver family: ``ros2 run vd_solvers <executable>`` serves ``models``."""

    name: str
    executable: str
    models: tuple[str, ...]
    #: the model of a goal that leaves ``model`` empty
    default_model: str

    @property
    def result_topic(self) -> str:
        return f'{self.name}/result'

    @property
    def state_topic(self) -> str:
        return f'{self.name}/state'

    def action(self, node_name: str | None = None) -> str:
        """Return the RunEvent action of the instance ``node_name`` (None: the default one)."""
        if node_name is None or node_name == self.executable:
            return f'{self.name}/run_event'
        return f'{self.name}/{node_name}/run_event'


FAMILIES: Mapping[str, Family] = {
    'steady_state': Family('steady_state', 'analytical_solver', ('bicycle', 'two_track'),
                           'two_track'),
    'kc': Family('kc', 'kc_solver', ('kc',), 'kc'),
    'vehicle': Family('vehicle', 'vehicle_solver', ('vehicle',), 'vehicle'),
}
#: model -> the family that serves it
MODEL_FAMILY: Mapping[str, str] = {m: f.name for f in FAMILIES.values() for m in f.models}
MODELS = tuple(MODEL_FAMILY)
#: models of measured data (vd import) -> the family whose messages carry them
MEASURED_MODEL_FAMILY: Mapping[str, str] = {'test': 'vehicle', 'rig': 'kc'}
#: the full vehicle's pose, one message per recorded step (nav_msgs/Odometry)
ODOMETRY_TOPIC = 'vehicle/odom'
#: the TF tree is global (tf2's convention): every vehicle on the domain publishes here
TF_TOPIC = '/tf'
#: how the checks name a request's fields: over ROS (goal fields) and on the command line
GOAL_FIELDS = {'axle': 'axle', 'fidelity': 'fidelity'}
CLI_FIELDS = {'axle': '--axle', 'fidelity': 'fidelity'}


def message_family(model: str) -> str:
    """Return the family whose topics and state type carry results of ``model``."""
    return MODEL_FAMILY.get(model) or MEASURED_MODEL_FAMILY.get(model, 'steady_state')


def event_model(event: str) -> str:
    """
    Return the model a run of ``event`` uses when none is named (``vd run``, plans).

    two_track where it applies, else the first model that runs the event.
    """
    if event in events_for('two_track'):
        return 'two_track'
    return next((m for m in MODELS if event in events_for(m)), 'two_track')


def all_events() -> tuple[str, ...]:
    """Return every event of every model, each once (from the rungs' own event tables)."""
    return tuple(dict.fromkeys(e for model in MODELS for e in events_for(model)))


def events_for(model: str) -> tuple[str, ...]:
    """Return the events ``model`` runs (empty for an unknown model)."""
    if model in ('bicycle', 'two_track'):
        from .analytical.events import EVENT_MODELS

        return tuple(e for e, models in EVENT_MODELS.items() if model in models)
    if model == 'kc':
        from .kc.from_config import EVENT_PARAMS

        return tuple(EVENT_PARAMS)
    if model == 'vehicle':
        from .vehicle.events import EVENT_PARAMS

        return tuple(EVENT_PARAMS)
    return ()


def event_params(model: str, event: str):
    """Return the parameter specification of ``event`` on ``model``."""
    if model == 'kc':
        from .kc.from_config import EVENT_PARAMS
    elif model == 'vehicle':
        from .vehicle.events import EVENT_PARAMS
    else:
        from .analytical.events import EVENT_PARAMS
    return EVENT_PARAMS[event]


def check_request(family: str, event: str, model: str, fidelity: str, axle: str,
                  parameters, fields: Mapping[str, str] = GOAL_FIELDS) -> None:
    """
    Check what a request for ``family`` must satisfy before anything runs.

    ``fidelity`` ``""`` means the configuration's switch; ``parameters`` None: not
    checked here. Raises SolverError (or the DataError of a bad event parameter) with a
    message naming the field as ``fields`` spells it (goal fields over ROS, flags on the
    command line).
    """
    served = FAMILIES[family].models
    if model not in served:
        raise SolverError(f"model '{model}' is not served here (models: {', '.join(served)})")
    if event not in events_for(model):
        raise SolverError(f"event '{event}' does not run on model '{model}' "
                          f"(its events: {', '.join(events_for(model))})")
    if fidelity and fidelity not in FIDELITIES:
        raise SolverError(f"unknown {fields['fidelity']} '{fidelity}' "
                          f"({', '.join(FIDELITIES)})")
    if fidelity == 'flexible' and model not in FLEXIBLE_MODELS:
        raise SolverError(f"{fields['fidelity']} 'flexible' is available for models "
                          f"{' and '.join(repr(m) for m in FLEXIBLE_MODELS)} only "
                          f"(model '{model}' has no flexible components)")
    if model == 'kc' and axle not in ('front', 'rear'):
        raise SolverError(f"K&C events need {fields['axle']} front or rear (found '{axle}')")
    if model != 'kc' and axle:
        raise SolverError(f"model '{model}' is a whole-vehicle model: no {fields['axle']}")
    if parameters is not None:
        from .event_params import parse_params

        parse_params(event, event_params(model, event), list(parameters))
