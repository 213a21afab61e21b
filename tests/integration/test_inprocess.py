# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd run`` in-process gives what the ROS graph gives: the same outcome, the same bag.

One request of each solver family (analytical, K&C, full vehicle) runs through the
embedded graph (data server, solver node, recorder node, DDS) and through the in-process
path (the solver's core called directly, the bag written directly). The outcome's JSON
must be equal, and so must every bag message (deserialised with rosbags, field by field),
every topic's type and offered QoS and the bag's metadata. Stamps are compared on the
run's own time axis (relative to its provenance stamp): where the axis starts is the wall
clock at the run, the one thing that differs between two runs.
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

pytestmark = [pytest.mark.ros, pytest.mark.slow]

#: one request per solver family: (event, model, axle, parameters)
REQUESTS = {
    'steady_state': ('steady_state_circular', 'two_track', '', ('steps=7',)),
    'kc': ('parallel_wheel_travel', 'kc', 'front', ()),
    'vehicle': ('step_steer', 'vehicle', '', ('duration=3 s',)),
}
#: the topics the data server publishes (stamped when it published them, not by the run)
DATA_TOPICS = ('/vd/configuration', '/vd/data_status')


def _plain(value, origin: int | None):
    """
    Return a rosbags message as nested plain values, every stamp relative to ``origin``.

    ``origin`` None: stamps are left out (the data server's publishing time).
    """
    if dataclasses.is_dataclass(value):
        fields = {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
        if value.__msgtype__ == 'builtin_interfaces/msg/Time':
            ns = fields['sec'] * 1_000_000_000 + fields['nanosec']
            return None if origin is None else ns - origin
        return {k: _plain(v, origin) for k, v in fields.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v, origin) for v in value]
    if isinstance(value, (float, np.floating)) and math.isnan(value):
        return 'NaN'  # a field the model does not compute: equal when NaN both ways
    return value


def _bag(path: Path) -> dict:
    """Return a bag's topics (type, offered QoS, messages) and its metadata, comparable."""
    from vd_events.bags.bag import bag_metadata, read_bag

    messages = list(read_bag(path))
    (provenance,) = [m for m in messages if m.topic == '/vd/provenance']
    stamp = provenance.msg.stamp
    origin = stamp.sec * 1_000_000_000 + stamp.nanosec
    topics: dict[str, dict] = {}
    for m in messages:
        own = None if m.topic in DATA_TOPICS else origin
        entry = topics.setdefault(m.topic, {'type': m.msgtype, 'messages': []})
        entry['messages'].append((None if own is None else m.timestamp - own,
                                  _plain(m.msg, own)))
    info = bag_metadata(path)
    for t in info['topics_with_message_count']:
        meta = t['topic_metadata']
        topics[meta['name']].update(count=t['message_count'], type_meta=meta['type'],
                                    qos=meta['offered_qos_profiles'])
    return {'topics': topics, 'custom_data': info['custom_data'],
            'ros_distro': info['ros_distro'], 'storage': info['storage_identifier'],
            'files': [Path(f['path']).name for f in info['files']]}


@pytest.mark.parametrize('family', list(REQUESTS))
def test_inprocess_run_equals_the_graph_run(tmp_path, sedan_master, family):
    from vd_data_server.study import load_study
    from vd_events.orchestration.inprocess import run_inprocess
    from vd_events.orchestration.requests import RunRequest, validate
    from vd_events.orchestration.runner import run_embedded

    event, model, axle, parameters = REQUESTS[family]
    study = load_study(sedan_master)
    runs = {}
    for way, run in (('graph', run_embedded), ('inprocess', run_inprocess)):
        # the same bag name both ways (the MCAP file is named after it)
        request = validate(study, RunRequest(event=event, configuration='baseline', model=model,
                                             axle=axle, parameters=parameters,
                                             bag=tmp_path / way / 'run'))
        (result,) = run(sedan_master, [request], study=study)
        assert result.error is None, result.error
        assert result.bag == request.bag
        runs[way] = (result.outcome.to_json(None), _bag(result.bag))
    (graph_json, graph_bag), (inprocess_json, inprocess_bag) = runs['graph'], runs['inprocess']
    assert graph_json['event'] == event and graph_json['channels']
    assert inprocess_json == graph_json
    assert set(inprocess_bag['topics']) == set(graph_bag['topics'])
    for topic, expected in graph_bag['topics'].items():
        assert inprocess_bag['topics'][topic] == expected, topic
    assert inprocess_bag == graph_bag
