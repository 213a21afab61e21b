# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The runs a command asks for: requests, their validation and their outcomes (ROS-free).

Shared by the in-process path (``inprocess.py``) and the ROS graph (``runner.py``):
everything a run needs is validated here before anything starts, so bad input leaves
nothing behind, and a result counts only when it answers its request
(:func:`check_result`).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
import time

from vd_data_server.errors import DataError
from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import Study
from vd_events.bags.bag import PARTIAL_SUFFIX, check_bag_path
from vd_events.errors import RunError
from vd_solvers.errors import SolverError
from vd_solvers.event_params import parse_params
from vd_solvers.families import (
    CLI_FIELDS,
    MODEL_FAMILY,
    MODELS,
    all_events,
    check_request,
    event_params,
    events_for,
)
from vd_solvers.results import EventOutcome, run_fidelity


@dataclass(frozen=True)
class RunRequest:
    event: str
    configuration: str
    model: str
    #: 'rigid' | 'flexible'; "" = the configuration's switch (results.run_fidelity),
    #: resolved by validate()
    fidelity: str = ''
    axle: str = ''
    overrides: tuple[str, ...] = ()
    parameters: tuple[str, ...] = ()
    bag: Path | None = None
    #: the data hash of the configuration (with ``overrides``) as validated; a result of
    #: other data (another study on the same domain) is refused. "" = set by validate()
    data_hash: str = ''

    @property
    def family(self) -> str:
        return MODEL_FAMILY[self.model]

    @property
    def label(self) -> str:
        return f"configuration '{self.configuration}', event '{self.event}', model '{self.model}'"


@dataclass
class RunOutcome:
    request: RunRequest
    outcome: EventOutcome | None
    bag: Path | None
    error: str | None = None
    timings: dict[str, float] = field(default_factory=dict)


def validate(study: Study, request: RunRequest) -> RunRequest:
    """
    Every check that can be made before starting: raises DataError / RunError / BagError.

    Returns the request with the fidelity it gets (``results.run_fidelity``: an empty
    one follows the configuration's ``flexible`` switch) and the data hash its result
    must carry.
    """
    # the requested model's own table first: the other rungs' modules load only when the
    # event is not one of its events (they weigh seconds on a cold start)
    served = request.model in MODELS and request.event in events_for(request.model)
    if not served and request.event not in all_events():
        raise RunError(f"unknown event '{request.event}' (events: {', '.join(all_events())})")
    if request.model not in MODELS:
        raise RunError(f"unknown model '{request.model}' (models: {', '.join(MODELS)})")
    try:  # the checks the solver's goal callback makes too, in command-line words
        check_request(request.family, request.event, request.model, request.fidelity,
                      request.axle, None, fields=CLI_FIELDS)
    except SolverError as err:
        raise RunError(str(err)) from None
    if request.configuration not in study.configurations:
        raise DataError(f"configuration '{request.configuration}' does not exist (available: "
                        f"{', '.join(study.configuration_names)})", file=str(study.master.path))
    config = with_overrides(study.configurations[request.configuration],
                            parse_set(request.overrides))
    if request.model == 'kc' and request.event == 'steering' and (
            request.axle != 'front' or 'steering' not in config.groups):
        raise RunError(f"event 'steering' needs a steered axle: the {request.axle} axle of "
                       f"'{request.configuration}' has no steering")
    fidelity = run_fidelity(request.model, config, request.fidelity)
    if fidelity == 'flexible':
        for axle in ([request.axle] if request.model == 'kc' else ['front', 'rear']):
            if f'{axle}_flex' not in config.groups:
                raise RunError(f"configuration '{request.configuration}' has no flexible "
                               f"components on the {axle} axle (no {axle}_flex group in the "
                               "master file)")
    parse_params(request.event, event_params(request.model, request.event), request.parameters)
    if request.bag is not None:
        check_bag_path(request.bag)
    return dataclasses.replace(request, fidelity=fidelity, data_hash=config.data_hash)




def check_result(request: RunRequest, result) -> None:
    """
    Check that the result answers this request, or raise RunError.

    Its configuration, event, model, axle and data hash must be the ones asked for (a
    solver of another run on the same domain, or of other data, answers with others).
    """
    asked = (request.configuration, request.event, request.model, request.axle)
    got = (result.configuration, result.event, result.model, result.axle)
    if got != asked:
        raise RunError(f"{request.label}: the result is for configuration '{got[0]}', event "
                       f"'{got[1]}', model '{got[2]}' - another run answered; not used")
    if request.data_hash and result.data_hash != request.data_hash:
        raise RunError(f"{request.label}: the result was computed from other data (data hash "
                       f"{result.data_hash or 'none'}, expected {request.data_hash}) - another "
                       "study answered on this ROS domain; not used")




class Phases:
    """Seconds spent in each phase of a run, accumulated into ``out`` (if given)."""

    def __init__(self, out: dict | None) -> None:
        self.out = out
        self.t = time.perf_counter()

    def lap(self, phase: str) -> None:
        now = time.perf_counter()
        if self.out is not None:
            self.out[phase] = self.out.get(phase, 0.0) + now - self.t
        self.t = now


def interrupted(request: RunRequest) -> str:
    """Say that ``request`` was interrupted, and that its partial bag is gone."""
    where = (f'; no bag written ({request.bag}{PARTIAL_SUFFIX} removed)'
             if request.bag is not None else '')
    return f'{request.label}: interrupted{where}'


__all__ = ['RunRequest', 'RunOutcome', 'validate', 'check_result', 'Phases', 'interrupted']
