# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
One run's bag written without a ROS graph, as the recorder writes it from the graph.

``vd run``'s in-process path (``vd_events.orchestration.inprocess``): the topics resolved
in the run's namespace, each recorded with the QoS its publisher in the graph offers
(``vd_data_server.ros.qos.profile_of`` as discovery reports it, ``bag.as_offered``), the
recorder's metadata (``bag.RECORDER_DATA``, ``bag.provenance_data``) and each message
logged at its own stamp (``bag.log_time``).
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
import time

from vd_data_server.ros import names
from vd_data_server.ros.qos import profile_of
from vd_events.bags.bag import (
    RECORDER_DATA,
    BagWriter,
    as_offered,
    cannot_write,
    log_time,
    provenance_data,
)


class RunBag:
    """
    One run's bag, written as the recorder writes it from the graph.

    Created as ``<bag>.partial`` (BagError: the path cannot be written); :meth:`start`
    writes the run's configuration and the data status (the latched topics the recorder
    receives first), :meth:`finish` the provenance and the run's messages and gives the
    bag its final name; :meth:`abort` removes the partial bag.
    """

    def __init__(self, path: Path, namespace: str) -> None:
        self.namespace = namespace
        self.writer = BagWriter(path, RECORDER_DATA)
        self._qos: dict[str, list] = {}

    def start(self, configuration, status) -> None:
        self._write([(names.CONFIGURATION, configuration), (names.DATA_STATUS, status)])

    def finish(self, provenance, messages: Sequence[tuple[str, object]]) -> Path:
        """Write the run's provenance and messages, close the bag and return its path."""
        for key, value in provenance_data(provenance).items():
            self.writer.set_custom_data(key, value)
        self._write([(names.PROVENANCE, provenance), *messages])
        try:
            return self.writer.close()
        except OSError as err:
            raise cannot_write(self.writer.path, err) from None

    def abort(self) -> None:
        self.writer.abort()

    def _write(self, messages: Sequence[tuple[str, object]]) -> None:
        try:
            for topic, msg in messages:
                bag_topic = topic if topic.startswith('/') else names.resolve(self.namespace,
                                                                              topic)
                if bag_topic not in self._qos:  # what the topic's publisher in the graph offers
                    self._qos[bag_topic] = [as_offered(profile_of(bag_topic))]
                self.writer.write(bag_topic, msg, log_time(msg, time.time_ns()),
                                  self._qos[bag_topic])
        except OSError as err:
            raise cannot_write(self.writer.path, err) from None


__all__ = ['RunBag']
