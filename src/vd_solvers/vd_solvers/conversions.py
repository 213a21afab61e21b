"""EventOutcome <-> vd_interfaces messages (EventResult, Sample)."""
from __future__ import annotations

import numpy as np
from vd_interfaces.msg import Channel as ChannelMsg, EventResult, NamedScalar, Sample

from vd_solvers.results import Channel, EventOutcome, Metric


def outcome_to_msg(outcome: EventOutcome, stamp=None) -> EventResult:
    msg = EventResult(event=outcome.event, configuration=outcome.configuration,
                      model=outcome.model, fidelity=outcome.fidelity, axle=outcome.axle,
                      data_hash=outcome.data_hash, notes=list(outcome.notes))
    msg.metrics = [NamedScalar(name=k, value=float(m.value), unit=m.unit, source=m.source)
                   for k, m in outcome.metrics.items()]
    msg.channels = [ChannelMsg(name=k, unit=c.unit, values=[float(v) for v in c.values])
                    for k, c in outcome.channels.items()]
    if stamp is not None:
        msg.stamp = stamp
    return msg


def outcome_from_msg(msg: EventResult) -> EventOutcome:
    return EventOutcome(
        event=msg.event, configuration=msg.configuration, model=msg.model,
        fidelity=msg.fidelity, axle=msg.axle, data_hash=msg.data_hash,
        metrics={m.name: Metric(float(m.value), m.unit, m.source) for m in msg.metrics},
        channels={c.name: Channel(c.unit, np.asarray(c.values, dtype=float))
                  for c in msg.channels},
        notes=tuple(msg.notes))


def outcome_samples(outcome: EventOutcome) -> list[Sample]:
    """One Sample per step (channel names in every message, for plotting tools)."""
    names = [k for k, c in outcome.channels.items() if len(c.values) == outcome.n_steps]
    columns = np.column_stack([outcome.channels[k].values for k in names]) if names else None
    samples = []
    for step in range(outcome.n_steps):
        sample = Sample(event=outcome.event, configuration=outcome.configuration,
                        model=outcome.model, step=step, names=names,
                        values=[float(v) for v in columns[step]] if columns is not None else [])
        sample.header.frame_id = "vehicle"
        samples.append(sample)
    return samples
