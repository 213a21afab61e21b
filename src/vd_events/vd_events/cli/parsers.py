# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ``vd`` command line's grammar (ARCHITECTURE §5): every verb, its arguments, its handler.

Only argparse here, so ``vd --help`` and a bad argument cost nothing else. Each verb names
its handler as ``module:function`` (:func:`handler`); ``cli.main`` imports that module when
the verb runs.
"""
from __future__ import annotations

import argparse

#: how ``vd import`` tells an Excel master workbook from measured data
XLSX = 'xlsx'


def handler(target: str):
    """Return the ``set_defaults`` of a verb whose handler is ``module:function``."""
    return {'handler': f'vd_events.cli.{target}'}


def _master(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--master', help='master file (default: the bundled sample study)')


def _namespace(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--namespace', default=None, metavar='NS',
                        help='ROS namespace of the nodes (default: /vd): /car2 gives '
                        '/car2/configuration, /car2/kc/run_event, ...')


def _json(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--json', action='store_true', help='machine-readable output')


def _data(sub) -> None:
    data = sub.add_parser('data', help='vehicle data and master files').add_subparsers(
        dest='data_command', required=True)
    for name, helptext in (('status', 'overview: variant, UNCHANGED/MODIFIED, SAME/DIFFERS'),
                           ('show', 'the resolved configuration in SI'),
                           ('check', 'validate the master file and every data file')):
        cmd = data.add_parser(name, help=helptext)
        if name == 'show':
            cmd.add_argument('config')
        _master(cmd)
        _json(cmd)
        cmd.set_defaults(**handler(f'data:cmd_{name}'))


def _run(sub) -> None:
    run = sub.add_parser('run', help='run one event on one configuration')
    run.add_argument('event')
    run.add_argument('--config', default=None,
                     help="configuration (default: the first; 'all': every configuration)")
    run.add_argument('--model', default=None, help='bicycle | two_track | kc | vehicle')
    run.add_argument('--fidelity', default='', help="rigid | flexible (K&C and vehicle; "
                     "default: the configuration's 'flexible' switch in the master file)")
    run.add_argument('--axle', default='', help='front | rear (K&C events)')
    run.add_argument('--set', dest='overrides', action='append', default=[],
                     metavar='KEY=VALUE', help="temporary override, e.g. "
                     "front_alignment.camber='-1 deg'")
    run.add_argument('--param', dest='parameters', action='append', default=[],
                     metavar='NAME=VALUE', help="event parameter, e.g. radius='40 m'")
    _master(run)
    run.add_argument('--bag', help='bag directory to write (must not exist)')
    run.add_argument('--distributed', action='store_true',
                     help='through the ROS graph, one process per node (DDS on loopback), '
                     'instead of solving in this process without a graph')
    _namespace(run)
    _json(run)
    run.set_defaults(**handler('run:cmd_run'))


def _study(sub) -> None:
    study = sub.add_parser('study', help='many events x configurations x models')
    study.add_argument('plan', help='study plan YAML')
    study.add_argument('--bag', help='folder for the bags (default: out/<plan name>/bags)')
    study.add_argument('--report', help='folder for the report (default: out/<plan name>)')
    study.add_argument('--distributed', action='store_true')
    _namespace(study)
    _json(study)
    study.set_defaults(**handler('study:cmd_study'))

    report = sub.add_parser('report', help='HTML report + PNG plots from bags')
    report.add_argument('bags', nargs='+')
    report.add_argument('--out', default='out/report', help='report folder')
    report.set_defaults(**handler('study:cmd_report'))


def _launch(sub) -> None:
    launch = sub.add_parser('launch', help='start the nodes and keep them running')
    launch.add_argument('--distributed', action='store_true')
    _master(launch)
    _namespace(launch)
    launch.add_argument('--allow-edits', action='store_true',
                        help='start the data server with allow_edits:=true (set_override)')
    launch.add_argument('--solvers', default='', metavar='FAMILY=N,...', help='solver '
                        'instances per family, e.g. kc=2 (default one of each)')
    launch.add_argument('--lockstep', action='store_true',
                        help='the lock-step vehicle and the example path follower, closed loop')
    launch.add_argument('--config', default='', help='lock-step configuration (default: first)')
    launch.add_argument('--duration', type=float, default=20.0,
                        help='lock-step simulated time, s')
    launch.add_argument('--radius', type=float, default=40.0, help='lock-step circle radius, m')
    launch.add_argument('--speed', type=float, default=12.0, help='lock-step speed, m/s')
    launch.add_argument('--bag', help='lock-step: bag directory to write (must not exist)')
    _json(launch)
    launch.set_defaults(**handler('launch:cmd_launch'))


def _capability(sub) -> None:
    cap = sub.add_parser('capability', help='rigid vs flexible K&C: which model each '
                         'event and quantity needs (thesis Tables 5.2.1/5.2.2)')
    cap.add_argument('--config', default=None, help='configuration (default: the first)')
    cap.add_argument('--axle', default='', help='front | rear (default: both)')
    _master(cap)
    cap.add_argument('--out', default=None, help='folder for the bag of the runs and tables '
                     '(default: a new numbered folder out/capability/<configuration>/NNN; '
                     'a folder given must not hold it yet)')
    cap.add_argument('--param', dest='parameters', action='append', default=[],
                     metavar='NAME=VALUE', help='event parameter for every event, e.g. steps=41')
    _json(cap)
    cap.set_defaults(**handler('capability:cmd_capability'))


def _sweeps(sub) -> None:
    for name, helptext in (('sweep', 'DOE over override factors; table + report pages'),
                           ('optimize', 'reach targets by changing factors; writes a '
                                        'configuration')):
        cmd = sub.add_parser(name, help=helptext)
        cmd.add_argument('plan', help='sweep plan YAML (docs/sweeps.md)')
        cmd.add_argument('--solvers', help='solver processes to start: N of each family the '
                         'runs need, or FAMILY=N,... (e.g. kc=2); default 2. With --attach: '
                         'the instances to wait for before the runs start (default 1)')
        cmd.add_argument('--attach', action='store_true', help='use the solver instances '
                         'already running on ROS_DOMAIN_ID (vd launch --solvers, other hosts) '
                         'instead of starting any')
        cmd.add_argument('--out', help='output folder (default: out/<plan name>)')
        if name == 'optimize':
            cmd.add_argument('--write-master', metavar='PATH', help='master file the '
                             "configuration is written to, anywhere (the plan's "
                             "optimize.write_master must lie under the study's data root)")
        _json(cmd)
        cmd.set_defaults(**handler(f'sweep:cmd_{name}'))


def _log_checks(parser: argparse.ArgumentParser) -> None:
    """Add the options of reading a vehicle log (vd import, vd grade; docs/testdata.md)."""
    parser.add_argument('--repair', action='append', default=[], metavar='WHAT',
                        help="'glitches': replace one-sample logger glitches linearly between "
                        'their neighbours (said in the notes); without it a glitch is refused')
    parser.add_argument('--yaw-sign', default='check', metavar='HOW',
                        help='check (default: refuse a yaw rate that opposes the GPS heading '
                        'rate), auto (reverse it when it does, with a note), reversed (the '
                        'logger writes positive clockwise)')
    parser.add_argument('--from', dest='start', type=float, metavar='S',
                        help='import from this time, s from the first sample')
    parser.add_argument('--to', dest='end', type=float, metavar='S',
                        help='import up to this time, s from the first sample')
    parser.add_argument('--window', default='', metavar='auto',
                        help="'auto': only the manoeuvre, found by its steering (the event's "
                        'rule), inside one gap-free stretch')
    parser.add_argument('--imu-position', metavar='X,Y,Z',
                        help='the IMU from the CoG in m, body axes (x forward, y left, z up): '
                        'its lateral acceleration is moved to the CoG (and roll-corrected '
                        'with a logged roll angle)')
    parser.add_argument('--event', default=None, help='the manoeuvre of the log(s) '
                        '(overrides the column map): sine_with_dwell, slowly_increasing_steer, '
                        'step_steer, constant_radius_turn, vehicle_test')


def _measured(sub) -> None:
    imp = sub.add_parser('import', help='rig / vehicle-test data (CSV, VBOX .vbo) into a bag '
                         '(vd import FILE... --bag DIR), or a master workbook into a master '
                         'file (vd import xlsx WORKBOOK --out MASTER)')
    imp.add_argument('files', nargs='+', metavar='FILE',
                     help="measured data files, or 'xlsx' and the workbook")
    imp.add_argument('--map', help='column map YAML (docs/testdata.md; needed for tables, '
                     'optional for .vbo)')
    imp.add_argument('--bag', help='bag directory to write (must not exist; measured data)')
    imp.add_argument('--out', help='master file to write (xlsx: its folder decides the data '
                     'root, as for any master file; a previous file is kept as .bak)')
    _log_checks(imp)
    _json(imp)
    imp.set_defaults(**handler('measured:cmd_import'))

    cmp = sub.add_parser('compare', help='simulation vs test: overlays, error metrics, verdicts')
    cmp.add_argument('sim_bag', metavar='SIM_BAG')
    cmp.add_argument('test_bag', metavar='TEST_BAG')
    cmp.add_argument('--out', default='out/compare', help='report folder')
    cmp.add_argument('--tolerances', help='tolerance YAML (channel: {rms, max, bias, '
                     'gradient}); default: docs/testdata.md')
    _json(cmp)
    cmp.set_defaults(**handler('measured:cmd_compare'))

    rep = sub.add_parser('replay', help='drive the bicycle and full-vehicle models with the '
                         'steering and speed of a vehicle log and compare (open-loop '
                         'validation)')
    rep.add_argument('test_bag', metavar='TEST_BAG')
    rep.add_argument('--config', default=None, help='configuration (default: the first)')
    _master(rep)
    rep.add_argument('--models', default='bicycle,vehicle', help='bicycle,vehicle')
    rep.add_argument('--bag', help='bag for the replayed runs (must not exist; default: '
                     '<out>/replay)')
    rep.add_argument('--out', default='out/replay', help='report folder')
    _json(rep)
    rep.set_defaults(**handler('measured:cmd_replay'))

    grade = sub.add_parser('grade', help='grade measured logs and simulated runs by their '
                           'standard: FMVSS 126 / UN R140 sine with dwell, ISO 7401 step '
                           'steer, ISO 4138 constant radius')
    grade.add_argument('inputs', nargs='+', metavar='FILE|BAG',
                       help='vehicle logs (.vbo, CSV with --map) or bags (vd import, vd run)')
    grade.add_argument('--map', help='column map YAML of the log files')
    grade.add_argument('--sis', nargs='+', default=[], metavar='FILE|BAG',
                       help='slowly-increasing-steer runs of the same set: A (S7.6)')
    grade.add_argument('--a-reference', type=float, metavar='DEG',
                       help='A in deg, when no slowly-increasing-steer run is given')
    grade.add_argument('--gvwr', type=float, metavar='KG', help='gross vehicle weight rating '
                       '(the displacement limit, S5.2.3; default: <= 3500 kg)')
    grade.add_argument('--steering-ratio', type=float, metavar='R', help='overall steering '
                       'ratio (ISO 4138 understeer gradient; simulations carry their own)')
    grade.add_argument('--wheelbase', type=float, metavar='M', help='wheelbase, m (ISO 4138: '
                       'the Ackermann angle of the radius actually driven)')
    grade.add_argument('--out', default='out/grade', help='report folder (grade.html)')
    _log_checks(grade)
    _json(grade)
    grade.set_defaults(**handler('grade:cmd_grade'))

    cor = sub.add_parser('correlate', help='correlate the model with repeated test runs by '
                         'ISO 19364 (steady-state circular), ISO 19365 (sine with dwell) or '
                         'ISO 22140 (lateral transient): tolerance bands and verdicts')
    cor.add_argument('inputs', nargs='+', metavar='BAG',
                     help='the simulation bags, then the test bags (vd import), in any order; '
                     'vehicle logs (.vbo, CSV with --map) are read as vd import reads them')
    cor.add_argument('--method', choices=('iso19364', 'iso19365', 'iso22140'),
                     help="validation method (default: the test runs' event's)")
    cor.add_argument('--bands', metavar='FILE', help='tolerance-band file (default: the '
                     'shipped, versioned one; docs/testdata.md)')
    cor.add_argument('--force', action='store_true', help='correlate a manoeuvre with fewer '
                     'test runs than the method asks for (the verdict says so)')
    cor.add_argument('--map', help='column map YAML of the log files')
    cor.add_argument('--out', default='out/correlate', help='report folder (correlate.html)')
    _json(cor)
    cor.set_defaults(**handler('correlate:cmd_correlate'))

    ident = sub.add_parser('identify', help='fit parameters of a configuration to measured '
                           'logs (least squares on replays); write it as a new configuration')
    ident.add_argument('plan', metavar='PLAN.yaml', help='identification plan '
                       '(docs/testdata.md)')
    ident.add_argument('--out', default='out/identify', help='report folder '
                       '(<plan name>/identify.html)')
    ident.add_argument('--write-master', metavar='FILE', help="master file the configuration "
                       "is added to (default: the plan's output.write_master, else its master; "
                       "a new file is a copy of the plan's master)")
    ident.add_argument('--dry-run', action='store_true', help='fit and report, write no '
                       'configuration')
    _json(ident)
    ident.set_defaults(**handler('identify:cmd_identify'))


def _workbench(sub) -> None:
    gui = sub.add_parser('gui', help='the master-file workbench in a browser (127.0.0.1)')
    _master(gui)
    gui.add_argument('--port', type=int, default=8765, help='port on 127.0.0.1 (default 8765; '
                     '0: any free port)')
    gui.add_argument('--edits', action='store_true', help='allow edits of the master file '
                     'from the page (off by default)')
    gui.add_argument('--screenshots', metavar='DIR', help='save a screenshot of every tab '
                     'into DIR (headless Chromium) and exit')
    gui.set_defaults(**handler('workbench:cmd_gui'))

    export = sub.add_parser('export', help='export the study (vd export xlsx; back with: vd '
                            'import xlsx WORKBOOK --out MASTER)').add_subparsers(
        dest='export_format', required=True)
    xlsx = export.add_parser(XLSX, help='the overview and group tabs as an Excel workbook')
    _master(xlsx)
    xlsx.add_argument('--out', default=None, help='workbook to write (default: '
                      'out/<master file name>.xlsx)')
    xlsx.set_defaults(**handler('workbench:cmd_export'))


def _tire(sub) -> None:
    tire = sub.add_parser('tire', help="a .tir file's key data and its Fx, Fy, Mz curves")
    tire.add_argument('file', help='TeimOrbit .tir property file (PAC2002, MF 5.2, 6.1, 6.2)')
    tire.add_argument('--out', default='out', help='folder of the PNG (default: out)')
    tire.add_argument('--side', choices=('LEFT', 'RIGHT'), help='evaluate the tire mounted '
                      'on this side (default: as measured, TYRESIDE)')
    tire.add_argument('--pressure', help='inflation pressure with its unit, e.g. "2.4 bar" '
                      "(default: the file's INFLPRES / IP)")
    tire.add_argument('--aligning-normalisation', choices=('mf-tyre', 'book'),
                      default='mf-tyre', help='load the trail and the Fx arm of Mz are '
                      'normalised by: FNOMIN (mf-tyre) or FNOMIN LFZO (book)')
    _json(tire)
    tire.set_defaults(**handler('tire:cmd_tire'))


def _bench(sub) -> None:
    bench = sub.add_parser('bench', help='the benchmark suite')
    _json(bench)
    bench.set_defaults(**handler('bench:cmd_bench'))


def build_parser() -> argparse.ArgumentParser:
    """Return the parser of every ``vd`` verb."""
    parser = argparse.ArgumentParser(prog='vd', description='vd: vehicle-dynamics simulation '
                                     'on one shared vehicle data set')
    sub = parser.add_subparsers(dest='command', required=True)
    for add in (_data, _run, _study, _launch, _capability, _sweeps, _bench, _measured,
                _workbench, _tire):
        add(sub)
    return parser


__all__ = ['build_parser', 'handler', 'XLSX']
