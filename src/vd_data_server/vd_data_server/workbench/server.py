# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The master-file workbench: the thesis' overview and group tabs as a local web page.

A small HTTP server (standard library only) next to the data server: it holds the
same :class:`service.DataService` core, watches the master file and the shared data
files, and pushes every reload to the open pages as Server-Sent Events. Edits from
the page go through :mod:`masteredit` (validated with the master-file loader,
written atomically with a backup); the data server node, which watches the same
files, reloads them on its own.

Security defaults: bound to 127.0.0.1; requests whose ``Host`` is not this
server's loopback address are refused (DNS rebinding), and so are edits and runs
whose ``Origin`` is not this page; edits are off unless started with
``edits=True``; a file is served only from under the data root.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
import json
from pathlib import Path
import sys
import threading
import time
from typing import Any
from urllib.parse import parse_qs, urlsplit

from vd_data_server.errors import DataError, WorkbenchError
from vd_data_server.master import inside
from vd_data_server.masteredit import ConflictError, Edit, Fingerprint, edit_master, fingerprint
from vd_data_server.overview import study_state
from vd_data_server.service import DataService
from vd_data_server.yamlio import read_bytes

#: seconds between looks at the watched files (a change shows within a second)
WATCH_PERIOD = 0.2
#: seconds between keep-alive comments on an idle event stream
KEEPALIVE = 10.0
#: largest request body accepted, bytes
MAX_BODY = 64 * 1024
#: seconds a connection may stay idle in the middle of a request before it is dropped
IDLE_TIMEOUT = 30.0
WEB = Path(__file__).resolve().parent / 'web'
#: the only static files served: name in the URL -> (file, content type)
STATIC = {'/': ('index.html', 'text/html; charset=utf-8'),
          '/index.html': ('index.html', 'text/html; charset=utf-8'),
          '/workbench.js': ('workbench.js', 'text/javascript; charset=utf-8'),
          '/workbench.css': ('workbench.css', 'text/css; charset=utf-8')}
EDITS_OFF = 'edits are disabled (start the workbench with: vd gui --edits)'
#: runs "Update marked" starts: (configuration names) -> per configuration metrics
Runner = Callable[[Sequence[str]], Mapping[str, Any]]


class Workbench:
    """The page's state: the loaded study, its version, the open event streams."""

    def __init__(self, master_file: str | Path, *, edits: bool = False,
                 runner: Runner | None = None) -> None:
        self.master_file = Path(master_file)
        self.edits = edits
        self.runner = runner
        self.service = DataService(self.master_file)
        self._lock = threading.RLock()
        self._changed = threading.Condition(self._lock)
        self.version = 0
        self._state: dict[str, Any] = {}
        self.runs: dict[str, Any] = {}
        self._running = False
        self._stop = threading.Event()
        # the master file as the page shows it: taken before each load, so an edit made
        # from an older page than the file is refused (HTTP 409), never lost
        self._read: Fingerprint | None = self._fingerprint()
        outcome = self.service.load()
        if self.service.study is None:
            raise DataError('\n'.join(outcome.errors) or 'cannot load', file=str(master_file))
        root = self.service.study.master.data_root
        if not inside(root, self.master_file):
            raise DataError(f'is outside its data root {root}: the workbench edits only files '
                            'under the data root', file=str(master_file))
        self._rebuild()

    @property
    def data_root(self) -> Path:
        root = self.service.data_root
        assert root is not None
        return root

    def _rebuild(self) -> None:
        """Build the state from the service's study and wake every event stream."""
        with self._lock:
            study = self.service.study
            assert study is not None
            state = study_state(study)
            state['errors'] = list(self.service.errors)
            self.version += 1
            state['version'] = self.version
            state['edits'] = self.edits
            state['can_run'] = self.runner is not None
            state['runs'] = self.runs
            state['running'] = self._running
            state['master'] = str(self.master_file)
            self._state = state
            self._changed.notify_all()

    def state(self) -> dict[str, Any]:
        with self._lock:
            return self._state

    def wait_change(self, version: int, timeout: float) -> dict[str, Any] | None:
        """Return the state once its version passes ``version``; None after ``timeout`` s."""
        with self._lock:
            self._changed.wait_for(lambda: self.version > version or self._stop.is_set(),
                                   timeout)
            return self._state if self.version > version else None

    def _fingerprint(self) -> Fingerprint | None:
        try:
            return fingerprint(self.master_file)
        except (DataError, OSError):  # gone or unreadable: the load says why
            return None

    def _reload(self) -> None:
        self._read = self._fingerprint()
        self.service.load()
        self._rebuild()

    def poll(self) -> bool:
        """Reload if a watched file changed; True if the state changed."""
        with self._lock:
            read = self._fingerprint()
            outcome = self.service.poll()
            if outcome is None:
                return False
            self._read = read
            self._rebuild()
            return True

    def watch(self, period: float = WATCH_PERIOD) -> threading.Thread:
        """Look at the watched files every ``period`` s in a background thread."""
        def loop() -> None:
            while not self._stop.wait(period):
                try:
                    self.poll()
                except Exception as err:  # noqa: BLE001 - the watcher must not die
                    with self._lock:
                        self.service.errors = (f'watching failed: {type(err).__name__}: {err}',)
                        self._rebuild()

        thread = threading.Thread(target=loop, name='workbench-watch', daemon=True)
        thread.start()
        return thread

    def stop(self) -> None:
        self._stop.set()
        with self._lock:
            self._changed.notify_all()

    def edit(self, body: Mapping[str, Any]) -> str:
        """Apply one edit from the page; a refused edit raises and changes nothing."""
        if not self.edits:
            raise WorkbenchError(HTTPStatus.FORBIDDEN, EDITS_OFF)
        fields = {k: body.get(k, '') for k in ('op', 'configuration', 'group', 'key', 'value',
                                                'source')}
        bad = [k for k, v in fields.items() if not isinstance(v, str)]
        if bad:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, f"'{bad[0]}' must be a text")
        bad = [k for k, v in fields.items() if '\x00' in v]
        if bad:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, f"'{bad[0]}' holds a NUL character")
        edit = Edit(**fields)
        with self._lock:
            try:
                changed = edit_master(self.master_file, [edit], expected=self._read)
            except ConflictError as err:
                self._reload()
                raise WorkbenchError(HTTPStatus.CONFLICT, str(err)) from None
            self._reload()
        what = {'variant': f'{edit.group} = {edit.value}',
                'override': f'{edit.key} = {edit.value}' if edit.value else f'{edit.key} cleared',
                'flexible': f'flexible = {edit.value or "off"}',
                'add': f'added{" as a copy of " + edit.source if edit.source else ""}'}[edit.op]
        return f'{edit.configuration}: {what}' + ('' if changed else ' (no change)')

    def run_marked(self, names: Sequence[str]) -> str:
        """Start the runs of the marked configurations in the background."""
        if self.runner is None:
            raise WorkbenchError(HTTPStatus.NOT_IMPLEMENTED, 'this workbench runs no events '
                                 '(started without a runner)')
        study = self.service.study
        assert study is not None
        if not all(isinstance(n, str) for n in names):
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, "'configurations' must be a list of "
                                 'configuration names (texts)')
        unknown = [n for n in names if n not in study.configurations]
        if not names or unknown:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, 'mark one or more configurations '
                                 f"(available: {', '.join(study.configuration_names)})"
                                 + (f"; unknown: {', '.join(map(str, unknown))}" if unknown
                                    else ''))
        with self._lock:
            if self._running:
                raise WorkbenchError(HTTPStatus.CONFLICT, 'runs are going on; wait for them')
            self._running = True
            for name in names:
                self.runs[name] = {'status': 'running', 'metrics': [], 'error': ''}
            self._rebuild()
        runner = self.runner

        def work() -> None:
            try:
                results = runner(list(names))
                with self._lock:
                    for name in names:
                        self.runs[name] = dict(results.get(name) or {
                            'status': 'failed', 'metrics': [], 'error': 'no result'})
            except Exception as err:  # noqa: BLE001 - reported on the page
                with self._lock:
                    for name in names:
                        self.runs[name] = {'status': 'failed', 'metrics': [],
                                           'error': f'{type(err).__name__}: {err}'}
            finally:
                with self._lock:
                    self._running = False
                    self._rebuild()

        threading.Thread(target=work, name='workbench-run', daemon=True).start()
        return f"running the events of {', '.join(names)}"

    def read_data_file(self, rel: str) -> str:
        """Return a file under the data root as text (the page shows the data files)."""
        root = self.data_root
        if '\x00' in rel:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, 'a file name holds no NUL character')
        path = root / rel
        if not rel or rel.startswith('/') or not inside(root, path):
            raise WorkbenchError(HTTPStatus.FORBIDDEN, f"'{rel}' is outside the data root "
                                 f'{root}: not read')
        if not path.is_file():
            raise WorkbenchError(HTTPStatus.NOT_FOUND, f"'{rel}' is not a file under the "
                                 f'data root {root}')
        try:
            return read_bytes(path, display=rel).decode('utf-8')
        except (DataError, UnicodeDecodeError) as err:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, str(err)) from None


class _Handler(BaseHTTPRequestHandler):
    server: 'WorkbenchServer'
    protocol_version = 'HTTP/1.1'
    #: s a connection may stay silent (socket timeout): a client that stalls in its
    #: request, or stops reading, releases its thread; the page's event stream writes a
    #: keep-alive every KEEPALIVE s, well inside it
    timeout = IDLE_TIMEOUT

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 - the base's name
        if self.server.verbose:
            super().log_message(format, *args)

    # -- checks ---------------------------------------------------------------------------
    def _check_host(self) -> None:
        host = self.headers.get('Host', '')
        if not self.path.startswith('/'):  # absolute form (a proxy's request): its host too
            url = urlsplit(self.path)
            if url.scheme != 'http' or url.netloc not in self.server.hosts:
                raise WorkbenchError(HTTPStatus.FORBIDDEN, f"request for '{url.netloc}' "
                                     f'refused (the workbench answers only as '
                                     f'{self.server.origin})')
        if host not in self.server.hosts:
            raise WorkbenchError(HTTPStatus.FORBIDDEN, f"host '{host}' refused (the workbench "
                                 f'answers only as {self.server.origin})')

    def _check_origin(self) -> None:
        origin = self.headers.get('Origin')
        if origin not in self.server.origins:
            raise WorkbenchError(HTTPStatus.FORBIDDEN, f"origin '{origin or 'none'}' refused "
                                 f'(edits are accepted only from {self.server.origin})')

    def _body(self) -> dict[str, Any]:
        try:
            length = int(self.headers.get('Content-Length', '0'))
        except ValueError:
            length = -1
        if length < 0 or length > MAX_BODY:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, f'a request body of 0 to {MAX_BODY} '
                                 'bytes is expected')
        raw = self.rfile.read(length)
        try:
            body = json.loads(raw.decode('utf-8') or '{}')
        except (UnicodeDecodeError, json.JSONDecodeError):
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, 'the request body is not JSON') from None
        except RecursionError:
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, 'the request body is nested too '
                                 'deeply') from None
        if not isinstance(body, dict):
            raise WorkbenchError(HTTPStatus.BAD_REQUEST, 'the request body must be a JSON object')
        return body

    # -- answers --------------------------------------------------------------------------
    def _send(self, status: HTTPStatus, body: bytes, content_type: str) -> None:
        self.send_response(status)
        self.send_header('Content-Type', content_type)
        self.send_header('Content-Length', str(len(body)))
        self.send_header('Cache-Control', 'no-store')
        self.send_header('X-Content-Type-Options', 'nosniff')
        self.send_header('Content-Security-Policy',
                         "default-src 'self'; style-src 'self' 'unsafe-inline'")
        self.end_headers()
        self.wfile.write(body)

    def _json(self, status: HTTPStatus, payload: Any) -> None:
        self._send(status, json.dumps(payload).encode('utf-8'), 'application/json')

    def _guarded(self, action: Callable[[], None]) -> None:
        try:
            self._check_host()
            action()
        except WorkbenchError as err:
            self._json(err.status, {'ok': False, 'error': str(err)})
        except DataError as err:
            self._json(HTTPStatus.UNPROCESSABLE_ENTITY, {'ok': False, 'error': str(err)})
        except (BrokenPipeError, ConnectionResetError):
            pass
        except TimeoutError:  # a stalled client: drop the connection, say nothing
            self.close_connection = True
        except Exception as err:  # noqa: BLE001 - one failed request never ends the server
            self._json(HTTPStatus.INTERNAL_SERVER_ERROR,
                       {'ok': False, 'error': f'the request failed: {type(err).__name__}: {err}'})

    def do_GET(self) -> None:  # noqa: N802 - the base's name
        self._guarded(self._get)

    def do_POST(self) -> None:  # noqa: N802 - the base's name
        self._guarded(self._post)

    def _get(self) -> None:
        url = urlsplit(self.path)
        bench = self.server.workbench
        if url.path in STATIC:
            name, content_type = STATIC[url.path]
            self._send(HTTPStatus.OK, (WEB / name).read_bytes(), content_type)
        elif url.path == '/api/state':
            self._json(HTTPStatus.OK, bench.state())
        elif url.path == '/api/file':
            rel = parse_qs(url.query).get('path', [''])[0]
            self._send(HTTPStatus.OK, bench.read_data_file(rel).encode('utf-8'),
                       'text/plain; charset=utf-8')
        elif url.path == '/api/events':
            self._events()
        else:
            raise WorkbenchError(HTTPStatus.NOT_FOUND, f"no page '{url.path}'")

    def _post(self) -> None:
        self._check_origin()
        url = urlsplit(self.path)
        bench = self.server.workbench
        if url.path == '/api/edit':
            message = bench.edit(self._body())
        elif url.path == '/api/run':
            names = self._body().get('configurations')
            if not isinstance(names, list):
                raise WorkbenchError(HTTPStatus.BAD_REQUEST, "'configurations' must be a list")
            message = bench.run_marked(names)
        else:
            raise WorkbenchError(HTTPStatus.NOT_FOUND, f"no action '{url.path}'")
        self._json(HTTPStatus.OK, {'ok': True, 'message': message, 'state': bench.state()})

    def _events(self) -> None:
        """Server-Sent Events: the whole state now, then at every change."""
        bench = self.server.workbench
        self.send_response(HTTPStatus.OK)
        self.send_header('Content-Type', 'text/event-stream')
        self.send_header('Cache-Control', 'no-store')
        self.send_header('Connection', 'close')
        self.end_headers()
        self.close_connection = True
        state = bench.state()
        while not self.server.stopping.is_set():
            self.wfile.write(b'event: state\ndata: ' + json.dumps(state).encode('utf-8')
                             + b'\n\n')
            self.wfile.flush()
            while True:
                new = bench.wait_change(state['version'], KEEPALIVE)
                if new is not None or self.server.stopping.is_set():
                    break
                self.wfile.write(b': keep-alive\n\n')
                self.wfile.flush()
            if new is None:
                break
            state = new


class WorkbenchServer(ThreadingHTTPServer):
    """The HTTP server of one workbench, on 127.0.0.1 only."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, workbench: Workbench, port: int = 0, *, verbose: bool = False) -> None:
        super().__init__(('127.0.0.1', port), _Handler)
        self.workbench = workbench
        self.verbose = verbose
        self.stopping = threading.Event()
        self.port = self.server_address[1]
        self.origin = f'http://127.0.0.1:{self.port}'
        self.hosts = {f'127.0.0.1:{self.port}', f'localhost:{self.port}'}
        self.origins = {f'http://{h}' for h in self.hosts}

    @property
    def url(self) -> str:
        return self.origin + '/'

    def handle_error(self, request: Any, client_address: Any) -> None:
        """Say nothing of a page that went away; one line for anything else."""
        error = sys.exc_info()[1]
        if isinstance(error, (ConnectionResetError, BrokenPipeError, TimeoutError)):
            return
        print(f'workbench: a request from {client_address[0]} failed: '
              f'{type(error).__name__}: {error}', file=sys.stderr)

    def start(self) -> threading.Thread:
        """Serve and watch in background threads (tests, ``vd gui --screenshots``)."""
        self.workbench.watch()
        thread = threading.Thread(target=self.serve_forever, name='workbench-http',
                                  daemon=True)
        thread.start()
        return thread

    def stop(self) -> None:
        self.stopping.set()
        self.workbench.stop()
        self.shutdown()
        self.server_close()


def serve(master_file: str | Path, *, port: int = 8765, edits: bool = False,
          runner: Runner | None = None, announce: Callable[[str], None] = print) -> None:
    """Serve until Ctrl-C (``vd gui``)."""
    workbench = Workbench(master_file, edits=edits, runner=runner)
    server = WorkbenchServer(workbench, port)
    workbench.watch()
    announce(f'workbench of {master_file} on {server.url} (edits '
             f"{'on' if edits else 'off'}; Ctrl-C ends)")
    try:
        server.serve_forever(poll_interval=0.5)
    except KeyboardInterrupt:
        pass
    finally:
        server.stopping.set()
        workbench.stop()
        server.server_close()
        time.sleep(0)
