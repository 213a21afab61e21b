# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Runs events in this process without a ROS graph: ``vd run`` unless ``--distributed``.

What the embedded graph does, without rclpy.init, nodes, an executor or DDS: each goal
is solved by the solver nodes' own code (:func:`vd_solvers.solve.solve_goal` with the
family's run function), its result converted by the functions the nodes publish with
(``vd_solvers.conversions``), and its bag written directly by the recorder's writer
(:class:`vd_events.bags.bag.BagWriter`): the same topics, types, offered QoS, metadata
and stamps on the same time axis, so the outcome and the bag are those of a run
through the graph (tests/integration/test_inprocess.py compares them message by
message).

As in the graph, a run's bag is created (as ``<bag>.partial``) before the goal is
solved and becomes final only once the result is written; a failed or interrupted run
removes it and says so.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
import time

from vd_data_server.conversions import configuration_to_msg, study_to_status_msg
from vd_data_server.ros import names
from vd_data_server.study import Study, load_study
from vd_events.errors import BagError, Interrupted, RunError
from vd_events.orchestration.requests import (
    Phases,
    RunOutcome,
    RunRequest,
    check_result,
    interrupted,
)
from vd_solvers.conversions import (
    outcome_from_msg,
    outcome_messages,
    outcome_to_msg,
    provenance_to_msg,
    run_stamp,
    time_msg,
)
from vd_solvers.solve import GoalFailed, provenance_groups, run_function, solve_goal, throttled


def run_inprocess(master: Path, requests: Sequence[RunRequest],
                  progress: Callable[[RunRequest, float, str], None] | None = None,
                  namespace: str = names.DEFAULT_NAMESPACE, timings: dict | None = None,
                  study: Study | None = None,
                  on_done: Callable[[RunOutcome], None] | None = None) -> list[RunOutcome]:
    """
    Solve ``requests`` (validated) one after the other in this process; a bag per request.

    ``study``: ``master`` as the caller loaded and validated it (default: loaded here).
    ``namespace``: where the bags' topics and frames are (as a graph in it publishes
    them). ``timings`` (if given) receives the seconds of each phase (``record``: the
    bags' writing, ``solve``); ``on_done`` (if given) hears each run's outcome as soon
    as it is complete.
    """
    clock = Phases(timings)
    if study is None:
        study = load_study(master)
    # what the data server publishes once, at its start (latched)
    status = study_to_status_msg(study, (), time_msg(time.time_ns()))
    frame_prefix = names.frame_prefix(namespace)
    outcomes: list[RunOutcome] = []
    for request in requests:
        base = study.configurations[request.configuration]
        bag = None
        t0 = time.perf_counter()
        try:
            if request.bag is not None:
                # imported for a run with a bag only: it imports rclpy and rosbags
                from vd_events.bags.run_bag import RunBag

                bag = RunBag(request.bag, namespace)  # a path refused: no run starts
                bag.start(configuration_to_msg(base, time_msg(time.time_ns())), status)
            clock.lap('record')

            def report(fraction: float, stage: str, request: RunRequest = request) -> None:
                if progress is not None:
                    progress(request, fraction, stage)

            report(0.0, 'solving')
            # the request carries the fields of the RunEvent goal the graph would send
            solved = solve_goal(run_function(request.family), base, request,
                                throttled(report))
            report(1.0, 'done')
            # the result as it travels to the runner and the recorder
            result = outcome_to_msg(solved.outcome)
            check_result(request, result)
            outcome = outcome_from_msg(result)
            clock.lap('solve')
            path = None
            if bag is not None:
                stamp = run_stamp(outcome, time.time_ns())
                provenance = provenance_to_msg(
                    outcome, stamp, solved.config.master_file,
                    provenance_groups(status.status, base.name, solved.changes))
                path = bag.finish(provenance, outcome_messages(outcome, stamp, frame_prefix))
                clock.lap('record')
            outcomes.append(RunOutcome(request, outcome, path,
                                       timings={'run': time.perf_counter() - t0}))
        except (GoalFailed, RunError) as err:  # both name the run
            outcomes.append(RunOutcome(request, None, None, str(err)))
        except BagError as err:
            if bag is None:
                raise
            outcomes.append(RunOutcome(request, None, None, f'{request.label}: {err}'))
        except KeyboardInterrupt:
            raise Interrupted(interrupted(request)) from None
        finally:
            if bag is not None:
                bag.abort()  # removes the partial bag unless finish() made it final
        if on_done is not None:
            on_done(outcomes[-1])
    clock.lap('record')
    return outcomes


__all__ = ['run_inprocess']
