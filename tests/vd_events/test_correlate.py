# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd correlate``'s core: tolerance bands around a simulation, verdicts, alignment.

The signals are constructed here, so the band edge is known in closed form from the band
file's numbers (never from the code's output): a test run exactly on the edge passes and
one a hair outside fails; a steady-state run is correlated on the same lateral
acceleration as the simulation; a transient is aligned on its manoeuvre's start.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import vbox_logs as vb
from vd_events.bags.outcomes import write_outcomes
from vd_events.cli.main import main
from vd_events.errors import InputError
from vd_events.measured.compare import REPLAY_NOTE
from vd_events.measured.correlate import DEFAULT_BANDS, correlate, load_bands
from vd_solvers.results import Channel, EventOutcome

DEG = math.pi / 180.0
#: the band of these tests: absolute 1 deg/s, 10 % of the peak, no time shift; steady
#: state: 2 deg + 10 % of |sim|, lateral-acceleration shift as the test asks
BANDS = """version: 7
name: test bands
methods:
  iso22140:
    title: lateral transient
    abscissa: time
    tests: [step_steer, vehicle_test]
    simulations: [step_steer, vehicle_test]
    window: [-0.5 s, 4 s]
    min_runs: 2
    channels:
      yaw_rate: {{absolute: 1 deg/s, relative: 0.1, shift: 0 s, source: test}}
  iso19364:
    title: steady-state circular
    abscissa: lateral_acceleration
    tests: [constant_radius_turn]
    simulations: [steady_state_circular]
    min_runs: 2
    channels:
      steering_wheel_angle: {{absolute: 2 deg, relative: 0.1, shift: {shift} m/s^2,
                              source: test}}
"""


def _bands(tmp_path: Path, shift: float = 0.0):
    path = tmp_path / 'bands.yaml'
    path.write_text(BANDS.format(shift=shift))
    return load_bands(path)


def _outcome(event: str, model: str, data_hash: str, notes=(), **channels) -> EventOutcome:
    units = {'time': 's', 'yaw_rate': 'rad/s', 'steering_wheel_angle': 'rad',
             'lateral_acceleration': 'm/s^2', 'speed': 'm/s'}
    return EventOutcome(event=event, configuration='car', model=model,
                        fidelity='measured' if model == 'test' else 'rigid', axle='',
                        data_hash=data_hash, metrics={},
                        channels={k: Channel(units[k], np.asarray(v, dtype=float))
                                  for k, v in channels.items()}, notes=tuple(notes))


def _replay_pair(offset: np.ndarray, run: str = 'a'):
    """Return a replay (10 Hz: not low-passed) and its log, the log = simulation + offset."""
    t = np.arange(0.0, 6.0, 0.1)
    r = 20.0 * DEG * np.sin(2.0 * np.pi * 0.5 * t)
    sim = _outcome('vehicle_test', 'bicycle', 'cfg', notes=(REPLAY_NOTE + run,),
                   time=t, yaw_rate=r)
    test = _outcome('vehicle_test', 'test', run, notes=(f'source: {run}.vbo',),
                    time=t, yaw_rate=r + offset)
    return sim, test


def test_verdict_flips_exactly_at_the_band_edge(tmp_path: Path) -> None:
    bands = _bands(tmp_path)
    # the band's half-width: 1 deg/s + 10 % of the simulated peak (20 deg/s)
    width = 1.0 * DEG + 0.1 * 20.0 * DEG
    on_edge = np.zeros(60)
    on_edge[17] = width
    sims, tests = zip(_replay_pair(on_edge, 'a'), _replay_pair(-on_edge, 'b'))
    result = correlate(list(sims), list(tests), 'iso22140', bands)
    assert result.verdict == 'PASS'
    outside = on_edge.copy()
    outside[17] = width * (1.0 + 1e-9)
    sims, tests = zip(_replay_pair(outside, 'a'), _replay_pair(on_edge, 'b'))
    result = correlate(list(sims), list(tests), 'iso22140', bands)
    (m,) = result.manoeuvres
    assert m.verdict == 'FAIL'
    runs = {c.run: c for c in m.channels}
    assert runs['a.vbo'].verdict == 'FAIL' and runs['b.vbo'].verdict == 'PASS'
    assert np.count_nonzero(~runs['a.vbo'].inside) == 1
    assert runs['a.vbo'].excess == pytest.approx(width * 1e-9, rel=1e-3)


def test_steady_state_on_the_same_lateral_acceleration(tmp_path: Path) -> None:
    """Simulation and test sampled at other a_y: the band is read at the test's a_y."""
    shift = 0.2
    bands = _bands(tmp_path, shift)
    k = 5.0 * DEG  # rad of steering-wheel angle per m/s^2, the simulated curve
    ay_sim = np.linspace(0.0, 8.0, 9)
    sim = _outcome('steady_state_circular', 'two_track', 'cfg', time=np.arange(9.0),
                   lateral_acceleration=ay_sim, steering_wheel_angle=k * ay_sim)
    ay = np.linspace(0.3, 7.5, 7)
    # the upper edge of a rising curve: sim(a_y + shift) + 2 deg + 10 % |sim(a_y)|, here
    # to the round-off of the interpolation (1e-12), outside by 1e-9 rad below
    edge = (k * (ay + shift) + 2.0 * DEG + 0.1 * k * ay) * (1.0 - 1e-12)
    tests = [_outcome('constant_radius_turn', 'test', h, time=np.arange(7.0),
                      lateral_acceleration=ay, steering_wheel_angle=edge)
             for h in ('r1', 'r2')]
    assert correlate([sim], tests, 'iso19364', bands).verdict == 'PASS'
    beyond = edge.copy()
    beyond[3] += 1e-9
    tests[1] = _outcome('constant_radius_turn', 'test', 'r2', time=np.arange(7.0),
                        lateral_acceleration=ay, steering_wheel_angle=beyond)
    (m,) = correlate([sim], tests, 'iso19364', bands).manoeuvres
    assert [c.verdict for c in m.channels] == ['PASS', 'FAIL']
    # a test point beyond the simulated a_y is left out and said
    far = _outcome('constant_radius_turn', 'test', 'r3', time=np.arange(8.0),
                   lateral_acceleration=np.append(ay, 9.0),
                   steering_wheel_angle=np.append(edge, 0.0))
    (m,) = correlate([sim], [tests[0], far], 'iso19364', bands).manoeuvres
    assert m.verdict == 'PASS'
    assert any('1 of 8 test points lie outside' in n for n in m.notes)


def _step(t: np.ndarray, t50: float, angle: float = 40.0 * DEG, ramp: float = 0.1
          ) -> np.ndarray:
    """Return a steering-wheel step, 50 % at ``t50`` (linear ramp of ``ramp`` s)."""
    return angle * np.clip((t - (t50 - ramp / 2.0)) / ramp, 0.0, 1.0)


def _response(t: np.ndarray, t50: float, gain: float = 15.0 * DEG, tau: float = 0.2
              ) -> np.ndarray:
    return gain * (1.0 - np.exp(-np.clip(t - t50, 0.0, None) / tau))


def test_transient_aligned_on_the_manoeuvre_start(tmp_path: Path) -> None:
    """The same step 1.3 s later in the log: aligned on t50 it lies inside a tight band."""
    bands = _bands(tmp_path)
    t = np.arange(0.0, 8.0, 0.01)
    sim = _outcome('step_steer', 'bicycle', 'cfg', time=t,
                   steering_wheel_angle=_step(t, 1.0), yaw_rate=_response(t, 1.0))
    tests = [_outcome('step_steer', 'test', h, notes=(f'source: {h}.vbo',), time=t,
                      steering_wheel_angle=_step(t, 2.3), yaw_rate=_response(t, 2.3))
             for h in ('s1', 's2')]
    (m,) = correlate([sim], tests, 'iso22140', bands).manoeuvres
    assert m.verdict == 'PASS'
    assert any('simulation time +1.300 s' in n for n in m.notes)
    # the window: 0.5 s before t50 to 4 s after it, on the log's time
    for c in m.channels:
        assert c.x[0] == pytest.approx(2.3 - 0.5, abs=0.011)
        assert c.x[-1] == pytest.approx(2.3 + 4.0, abs=0.011)
    # the response 0.3 s late against its own steer: alignment is on the steer, so it fails
    late = [_outcome('step_steer', 'test', h, notes=(f'source: {h}.vbo',), time=t,
                     steering_wheel_angle=_step(t, 2.3), yaw_rate=_response(t, 2.6))
            for h in ('s1', 's2')]
    assert correlate([sim], late, 'iso22140', bands).verdict == 'FAIL'


def test_a_single_run_is_refused_unless_forced(tmp_path: Path) -> None:
    bands = _bands(tmp_path)
    sim, test = _replay_pair(np.zeros(60))
    with pytest.raises(InputError, match=r'1 test run \(a.vbo\).*repeated runs \(at least '
                       r'2.*--force'):
        correlate([sim], [test], 'iso22140', bands)
    (m,) = correlate([sim], [test], 'iso22140', bands, force=True).manoeuvres
    assert m.forced and m.verdict == 'PASS'
    assert m.verdict_text == 'PASS (forced: 1 test run; the method asks for 2)'
    assert m.to_json()['forced'] is True


def test_the_test_event_must_be_the_methods(tmp_path: Path) -> None:
    bands = _bands(tmp_path)
    sims, tests = zip(_replay_pair(np.zeros(60), 'a'), _replay_pair(np.zeros(60), 'b'))
    with pytest.raises(InputError, match='steady-state circular correlates '
                       'constant_radius_turn; the test runs hold vehicle_test'):
        correlate(list(sims), list(tests), 'iso19364', bands)


def test_the_shipped_bands_say_where_each_number_comes_from() -> None:
    bands = load_bands()
    assert set(bands.methods) == {'iso19364', 'iso19365', 'iso22140'}
    for spec in bands.methods.values():
        assert spec.min_runs >= 2
        for band in spec.channels.values():
            assert band.source and band.absolute > 0.0
    assert 'not available' in DEFAULT_BANDS.read_text()
    steer = bands.methods['iso19364'].channels['steering_wheel_angle']
    assert steer.absolute == pytest.approx(2.0 * DEG)


@pytest.mark.parametrize(('text', 'message'), [
    ('version: 1\nmethods: {iso19365: {abscissa: time, channels: {yaw_rate: '
     '{absolute: 1 deg/s}}}}', r'yaw_rate.source: every width says where it comes from'),
    ('version: 1\nmethods: {iso19365: {abscissa: time, channels: {yaw_rate: '
     '{absolute: 1 m, source: x}}}}', r"absolute: unit 'm' cannot be converted"),
    ('version: 1\nmethods: {iso9999: {}}', 'unknown method'),
    ('version: one\nmethods: {}', 'version: expected an integer'),
])
def test_bad_band_files_are_refused(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / 'bands.yaml'
    path.write_text(text)
    with pytest.raises(InputError, match=message):
        load_bands(path)


def _bags(tmp_path: Path, offset: np.ndarray, runs: tuple[str, ...]) -> list[str]:
    out = []
    for run in runs:
        sim, test = _replay_pair(offset, run)
        for kind, o in (('sim', sim), ('test', test)):
            out.append(str(write_outcomes(tmp_path / f'{kind}_{run}', [(o, 1_700_000_000 * 10**9)],
                                          {'vd.kind': kind})))
    return out


def test_cli_correlates_bags_and_writes_the_page(tmp_path: Path, capsys) -> None:
    width = 1.0 * DEG + 0.1 * 20.0 * DEG  # the test bands' yaw-rate half-width
    offset = np.zeros(60)
    offset[30] = 1.5 * width
    bags = _bags(tmp_path, offset, ('a', 'b'))
    (tmp_path / 'bands.yaml').write_text(BANDS.format(shift=0.0))
    code = main(['correlate', *bags, '--bands', str(tmp_path / 'bands.yaml'), '--out',
                 str(tmp_path / 'page'), '--json'])
    assert code == 0
    answer = json.loads(capsys.readouterr().out)
    assert answer['method'] == 'iso22140' and answer['verdict'] == 'FAIL'
    assert answer['bands']['version'] == 7
    (m,) = answer['manoeuvres']
    assert m['test_runs'] == ['a.vbo', 'b.vbo'] and m['forced'] is False
    assert m['channel_verdicts'] == {'yaw_rate': 'FAIL'}
    assert all(c['inside'] == 59 and c['points'] == 60 for c in m['channels'])
    page = Path(answer['report'])
    assert page.is_file() and (page.parent / 'correlate_0_0.png').is_file()
    assert 'yaw_rate' in page.read_text()


def test_cli_refuses_a_single_run_with_exit_2(tmp_path: Path, capsys) -> None:
    bags = _bags(tmp_path, np.zeros(60), ('a',))
    assert main(['correlate', *bags, '--out', str(tmp_path / 'page')]) == 2
    err = capsys.readouterr().err
    assert '1 test run (a.vbo)' in err and '--force' in err
    assert not (tmp_path / 'page').exists()
    assert main(['correlate', bags[0], '--out', str(tmp_path / 'page')]) == 2
    assert 'no vehicle log among the inputs' in capsys.readouterr().err
    assert main(['correlate', *bags, '--force', '--out', str(tmp_path / 'page')]) == 0
    assert 'PASS (forced: 1 test run; the method asks for 2)' in capsys.readouterr().out


def test_sine_with_dwell_aligned_on_bos_over_the_methods_window() -> None:
    """ISO 19365 with the shipped bands: the same run 1.5 s later in the logs, on BOS."""
    t = np.arange(0.0, 10.0, 0.01)

    def run(start: float, model: str, data_hash: str) -> EventOutcome:
        steer = vb.sine_with_dwell(150.0 * DEG, 1, start)(t)
        lagged = vb.sine_with_dwell(150.0 * DEG, 1, start + 0.1)(t)
        return _outcome('sine_with_dwell', model, data_hash,
                        notes=(f'source: {data_hash}.vbo',), time=t,
                        steering_wheel_angle=steer, yaw_rate=lagged / 6.0,
                        lateral_acceleration=lagged * 2.0)

    sim = run(1.0, 'vehicle', 'cfg')
    (m,) = correlate([sim], [run(2.5, 'test', 'r1'), run(2.5, 'test', 'r2')],
                     'iso19365').manoeuvres
    assert m.verdict == 'PASS'
    assert any('simulation time +1.500 s' in n for n in m.notes)
    bos = 2.5  # the steer leaves zero at its start
    for c in m.channels:
        assert c.x[0] == pytest.approx(bos - 0.5, abs=0.02)
        assert c.x[-1] == pytest.approx(bos + 3.5, abs=0.02)
    # not aligned (the log's steer 0.3 s later than its responses): outside the bands
    late = run(2.5, 'test', 'r3')
    shifted = dict(late.channels)
    shifted['steering_wheel_angle'] = Channel('rad', vb.sine_with_dwell(150.0 * DEG, 1, 2.8)(t))
    late = EventOutcome(**{**late.__dict__, 'channels': shifted})
    assert correlate([sim], [late, run(2.5, 'test', 'r4')], 'iso19365').verdict == 'FAIL'
