# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
K&C results on demand, cached by the configuration's data hash.

The lower rungs (effective axle characteristics of the bicycle and two-track
models) and the full-vehicle rung (its suspension maps) need K&C results of the
*same* configuration and data hash. They ask here: a result that exists in this
process is returned, a missing one is computed with the ROS-free K&C core. A
changed configuration has a new data hash, so a result of older data is never
returned.

    from vd_solvers.kc.cache import kc_result
    par = kc_result(config, "front", "parallel_wheel_travel", steps=41)
    par.channels["toe"]           # (n, 2) rad

The key is (data hash, axle, fidelity, event, sorted parameters); the cache
holds at most ``MAX_ENTRIES`` results and ``MODEL_ENTRIES`` assembled models (least
recently used go first); a model's key adds whether it is the flexible model's rigid limit.

Results are also kept on disk (:mod:`vd_data_server.disk_cache`, kind ``kc``, at most
``DISK_ENTRIES``), so a new process (every ``vd run`` of the bicycle or two-track, whose
understeer budget takes twelve K&C events) reads them instead of solving again: the key
adds the hash of the sources of vd_solvers and vd_data_server and the numpy and scipy
versions, so other code never reads a result of this one. The result read is the pickled
result computed from the same data by the same code: the same to the last bit.

:func:`kc_outcome` keeps whole event outcomes (:func:`.from_config.run_kc_event`, with
their metrics and notes) there under the same discipline: the capability study's
rigid-limit check, the flexible model at its rigid limit run on every event of both axles,
is paid once per data and code, not by every ``vd capability``.
"""
from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from threading import Lock

import numpy as np
import scipy

from vd_data_server import disk_cache
from vd_data_server.model import Configuration
from vd_solvers.errors import SolverError
from vd_solvers.results import FIDELITIES, EventOutcome

from .events import EventResult, KCModel
from .model import without_bar

#: results kept per process
MAX_ENTRIES = 256
#: assembled models kept per process (a flexible axle holds about 2 MB): a solver node
#: asked for many variants of the data keeps the latest
MODEL_ENTRIES = 32
#: results kept on disk (module doc)
DISK_ENTRIES = 1024
#: the kind of the disk entries (:func:`vd_data_server.disk_cache.folder`)
KIND = 'kc'

#: the opposite-wheel-travel run without the anti-roll bar (roll stiffness split)
NO_BAR = 'opposite_wheel_travel_no_bar'

_results: OrderedDict[tuple, EventResult] = OrderedDict()
_models: OrderedDict[tuple, KCModel] = OrderedDict()
_lock = Lock()


def _remember(store: OrderedDict, key: tuple, value, entries: int = MAX_ENTRIES):
    store[key] = value
    store.move_to_end(key)
    while len(store) > entries:
        store.popitem(last=False)
    return value


def kc_model(config: Configuration, axle: str, fidelity: str = 'rigid', label: str = '',
             at_rigid_limit: bool = False) -> KCModel:
    """
    Return the assembled K&C model of ``axle`` of ``config`` (cached by data hash).

    ``label`` prefixes the messages of a model that cannot be built (default: the
    configuration and axle); the model returned carries the label of the call that built
    it. ``at_rigid_limit``: the flexible model at its rigid limit
    (:func:`.from_config.rigid_limit`). The arguments are those of
    :func:`.from_config.build_kc_model`, so a run may take either
    (:func:`.from_config.run_kc_event`). A run leaves the model as it was (its System
    keeps no state between evaluations), so every run of the same data may share it.
    """
    from .from_config import build_kc_model, rigid_limit, suspension_input

    if fidelity not in FIDELITIES and not label:
        raise SolverError(f"configuration '{config.name}', axle '{axle}': K&C fidelity "
                          f"'{fidelity}' is not available (available: {', '.join(FIDELITIES)})")
    key = (config.data_hash, axle, fidelity, at_rigid_limit)
    with _lock:
        model = _models.get(key)
        if model is not None:
            _models.move_to_end(key)
            return model
    if label:
        model = build_kc_model(config, axle, fidelity, label, at_rigid_limit)
    else:
        inp = suspension_input(config, axle, fidelity)
        model = KCModel(rigid_limit(inp) if at_rigid_limit else inp,
                        f"configuration '{config.name}', axle '{axle}'")
    with _lock:
        return _remember(_models, key, model, MODEL_ENTRIES)


def kc_result(config: Configuration, axle: str, event: str, fidelity: str = 'rigid',
              **params: float) -> EventResult:
    """
    One K&C event of ``config`` on ``axle``: cached, or computed now.

    ``event`` is a K&C event name or ``opposite_wheel_travel_no_bar`` (the same
    sweep with the anti-roll bar removed; SolverError if the axle has none).
    ``params`` are the event's keyword parameters (SI).
    """
    key = (config.data_hash, axle, fidelity, event, tuple(sorted(params.items())))
    with _lock:
        hit = _results.get(key)
        if hit is not None:
            _results.move_to_end(key)
            return hit
    stored_as = disk_cache.key_of(_code(), repr(key))
    stored = disk_cache.load(KIND, stored_as)
    if isinstance(stored, EventResult):
        with _lock:
            return _remember(_results, key, stored)
    model = kc_model(config, axle, fidelity)
    if event == NO_BAR:
        if model.inp.stabilizer is None:
            raise SolverError(f"configuration '{config.name}', axle '{axle}': no anti-roll bar")
        bare = KCModel(without_bar(model.inp), model.label, solved=True)
        result = bare.run('opposite_wheel_travel', None, **params)
    else:
        result = model.run(event, None, **params)
    disk_cache.store(KIND, stored_as, result, DISK_ENTRIES)
    with _lock:
        return _remember(_results, key, result)


def kc_outcome(config: Configuration, event: str, axle: str, params: Sequence[str] = (),
               fidelity: str = 'rigid', at_rigid_limit: bool = False) -> EventOutcome:
    """
    Return one K&C event's outcome, as :func:`.from_config.run_kc_event` returns it.

    From the disk, or run now on this process's model (:func:`kc_model`) and kept there.
    The key is the configuration's name and data hash, the axle, fidelity, rigid limit,
    event and the parameters as given (``'steps=41'``), beside the code of :func:`_code`.
    """
    from .from_config import run_kc_event

    key = ('outcome', config.name, config.data_hash, axle, fidelity, at_rigid_limit, event,
           tuple(params))
    stored_as = disk_cache.key_of(_code(), repr(key))
    stored = disk_cache.load(KIND, stored_as)
    if isinstance(stored, EventOutcome):
        return stored
    outcome = run_kc_event(config, event, axle, tuple(params), fidelity=fidelity,
                           at_rigid_limit=at_rigid_limit, build=kc_model)
    disk_cache.store(KIND, stored_as, outcome, DISK_ENTRIES)
    return outcome


@lru_cache(maxsize=1)
def _code() -> str:
    """Return what besides the data decides a result: the sources and the numerics' versions."""
    packages = Path(__file__).resolve().parents[1], Path(disk_cache.__file__).resolve().parent
    return f'{disk_cache.sources_hash(*packages)} numpy {np.__version__} scipy {scipy.__version__}'


def clear() -> None:
    """Forget every cached model and result of this process (tests; the disk keeps its own)."""
    with _lock:
        _results.clear()
        _models.clear()


__all__ = ['kc_result', 'kc_model', 'kc_outcome', 'clear', 'MAX_ENTRIES', 'MODEL_ENTRIES',
           'FIDELITIES', 'NO_BAR']
