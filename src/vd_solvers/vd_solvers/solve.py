# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
One goal solved by the ROS-free cores: what a solver node does with a RunEvent goal.

The solver nodes (``vd_solvers.nodes``) and ``vd run``'s in-process path
(``vd_events.orchestration.inprocess``) both call :func:`solve_goal` with the family's run
function (:func:`run_function`), so a goal gives the same outcome, the same notes and the
same error message whether it travels over ROS or not. A goal is anything with the fields
of ``vd_interfaces/action/RunEvent``'s goal (event, configuration, model, fidelity, axle,
overrides, parameters).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
import dataclasses
from dataclasses import dataclass
import time
from typing import Any
import warnings

from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.model import Configuration
from vd_data_server.study import modified_keys
from vd_interfaces.msg import GroupStatus as GroupStatusMsg
from vd_interfaces.msg import ModifiedKey
from vd_solvers.errors import SolverError
from vd_solvers.families import FAMILIES
from vd_solvers.results import FIDELITIES, EventOutcome, run_fidelity

#: (fraction done, stage) -> None
Progress = Callable[[float, str], None]
#: (configuration, goal, progress) -> outcome
RunFn = Callable[[Configuration, Any, Progress], EventOutcome]
#: least interval between two progress reports that leave the solver, s
FEEDBACK_PERIOD = 0.1
#: how a goal's overrides are named in messages
OVERRIDES_SOURCE = 'overrides'


class Cancelled(Exception):
    """The client cancelled the goal while it was being solved."""


class GoalFailed(Exception):
    """A goal that did not give an outcome; the message names its configuration and event."""


@dataclass(frozen=True)
class Solved:
    """A goal's outcome and the configuration it ran on (with the goal's overrides)."""

    outcome: EventOutcome
    config: Configuration
    #: GroupStatus messages of the groups the goal's overrides changed
    changes: list


def goal_label(goal) -> str:
    return f"configuration '{goal.configuration}', event '{goal.event}'"


def solve_goal(run: RunFn, base: Configuration, goal, progress: Progress) -> Solved:
    """
    Solve ``goal`` on ``base`` with its overrides; GoalFailed says why it could not.

    numpy / LAPACK warnings (overflow, a singular matrix) are not printed on their own:
    they become part of the error they explain, or a note of the outcome
    (``catch_warnings`` is process-wide; the goals of one solver come one at a time).
    :class:`Cancelled` (raised by ``progress``) and KeyboardInterrupt pass through.
    """
    caught: list[warnings.WarningMessage] = []
    try:
        config = with_overrides(base, parse_set(goal.overrides, OVERRIDES_SOURCE),
                                OVERRIDES_SOURCE)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('always')
            outcome = run(config, goal, progress)
    except Cancelled:
        raise
    except (DataError, SolverError) as err:
        message = str(err) if goal.configuration in str(err) else f'{goal_label(goal)}: {err}'
        raise GoalFailed(message + _warnings_text(caught)) from None
    except Exception as err:  # noqa: BLE001 - a solver bug is the goal's error, named
        raise GoalFailed(f'{goal_label(goal)}: internal solver error {type(err).__name__}: '
                         f'{err}{_warnings_text(caught)}') from None
    if caught:
        outcome = dataclasses.replace(outcome, notes=(
            *outcome.notes, 'numerical warnings during the run: ' +
            '; '.join(_warning_messages(caught))))
    return Solved(outcome, config, set_changes(base, config))


def throttled(report: Progress, period: float = FEEDBACK_PERIOD) -> Progress:
    """Return ``report`` called at most once every ``period`` s (the first call goes out)."""
    last = [-period]

    def progress(fraction: float, stage: str) -> None:
        now = time.monotonic()
        if now - last[0] >= period:
            last[0] = now
            report(fraction, stage)
    return progress


def _warning_messages(caught) -> list[str]:
    """Return the caught warnings' messages, each once, at most five."""
    return list(dict.fromkeys(str(w.message) for w in caught or ()))[:5]


def _warnings_text(caught) -> str:
    """`` (numerical warnings: overflow encountered in exp; ...)``, or ""."""
    texts = _warning_messages(caught)
    return f" (numerical warnings: {'; '.join(texts)})" if texts else ''


def set_changes(base: Configuration, config: Configuration) -> list:
    """GroupStatus messages for the groups a run's ``--set`` overrides changed."""
    out = []
    for name, group in config.groups.items():
        keys = modified_keys(base.groups[name].values, group.values)
        if keys:
            out.append(GroupStatusMsg(configuration=config.name, group=name,
                                      variant=group.variant, state=GroupStatusMsg.MODIFIED,
                                      consistency=GroupStatusMsg.DIFFERS,
                                      modified_keys=[ModifiedKey(key=k.key,
                                                                 data_value=k.data_value,
                                                                 master_value=k.master_value,
                                                                 unit=k.unit) for k in keys]))
    return out


def provenance_groups(status: Iterable, configuration: str, changes: list) -> list:
    """
    Return the GroupStatus list of a run's provenance.

    ``status``: the data server's GroupStatus messages (``DataStatus.status``); the groups
    of ``configuration``, each replaced by its entry in ``changes`` (the goal's overrides).
    """
    changed = {g.group: g for g in changes}
    return [changed.get(s.group, s) for s in status if s.configuration == configuration]


# --- the families' run functions ---------------------------------------------------


def _run_analytical(config: Configuration, goal, progress: Progress) -> EventOutcome:
    from vd_solvers.analytical.events import run_event

    return run_event(config, goal.event, goal.model or FAMILIES['steady_state'].default_model,
                     list(goal.parameters))


def _run_kc(config: Configuration, goal, progress: Progress) -> EventOutcome:
    from vd_solvers.kc.cache import kc_model
    from vd_solvers.kc.from_config import run_kc_event

    fidelity = run_fidelity('kc', config, goal.fidelity)
    if fidelity not in FIDELITIES:
        raise SolverError(f"configuration '{config.name}', event '{goal.event}': fidelity "
                          f"'{goal.fidelity}' is not available (fidelities: "
                          f"{', '.join(FIDELITIES)})")
    # the process assembles each (data, axle, fidelity) once and runs every goal on it
    return run_kc_event(config, goal.event, goal.axle, list(goal.parameters), progress,
                        fidelity, build=kc_model)


def _run_vehicle(config: Configuration, goal, progress: Progress) -> EventOutcome:
    from vd_solvers.vehicle.events import run_vehicle_event

    # an empty goal.fidelity follows the configuration's switch (results.run_fidelity)
    return run_vehicle_event(config, goal.event, list(goal.parameters), goal.fidelity, progress)


#: family -> its run function (the solver nodes and ``vd run`` in-process)
RUN_FUNCTIONS: dict[str, RunFn] = {'steady_state': _run_analytical, 'kc': _run_kc,
                                   'vehicle': _run_vehicle}


def run_function(family: str) -> RunFn:
    """Return the run function of ``family`` (its modules are imported at the first goal)."""
    return RUN_FUNCTIONS[family]


__all__ = ['Cancelled', 'GoalFailed', 'Solved', 'solve_goal', 'throttled', 'set_changes',
           'provenance_groups', 'run_function', 'RUN_FUNCTIONS', 'FEEDBACK_PERIOD',
           'OVERRIDES_SOURCE', 'goal_label']
