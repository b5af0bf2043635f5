"""The Hops server's limits: solves run in worker processes, so a request whose curve takes the
decoder a minute (rhino3dm holds the interpreter lock while it decodes) delays neither GETs nor
other solves; it is stopped at the time limit (503 naming it) and its worker replaced; at most
--workers solves run and --queue wait, more are refused at once (503, Retry-After); SIGTERM stops
the server and its workers at once; JSON nested deeper than 100 levels is refused (400) before it
is parsed.

The servers are real (`cnets.hops.main` in a subprocess on a loopback port of its own), their
geometry decoder a stand-in from this module: items whose JSON has `"spin": true` make it spin in
one C call that never releases the interpreter lock (as rhino3dm does on a hostile archive); items
with `"crash": true` end the worker; anything else is decoded by rhino3dm. Assertions are about
statuses, counts and order ("the GET was answered before the slow solve ended"), with generous
time bounds: CI runs on 2 busy cores."""

import concurrent.futures
import http.client
import itertools
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest

from conftest import REPO, arc, profile

import rhino3dm

TESTS = Path(__file__).resolve().parent

# Starts `python -m cnets.hops` with this module's decoder (it runs in the workers, which import
# this module by name: the spawned workers get the server's sys.path).
LAUNCH = (
    "import functools, sys\n"
    f"sys.path.insert(0, {str(TESTS)!r})\n"
    "import cnets.hops as hops, test_hops_limits as t\n"
    "hops.create_app = functools.partial(hops.create_app, decode_geometry=t.stand_in_decode)\n"
    "hops.main(sys.argv[1:])\n"
)


def stand_in_decode(encoded):
    """The geometry decoder of the test servers (see the module's text)."""
    if encoded.get("spin"):
        # One C call holding the interpreter lock for hours: only SIGKILL ends it.
        return sum(itertools.repeat(1, 10 ** 13))
    if encoded.get("crash"):
        os._exit(3)
    return rhino3dm.CommonObject.Decode(encoded)


class Server:
    """A Hops server subprocess started with `LAUNCH` and `args`, on port 0; ready once its
    workers are."""

    def __init__(self, log_path, *args, launch=LAUNCH):
        self.log_path = log_path
        self._log = open(log_path, "w+b")
        self.proc = subprocess.Popen([sys.executable, "-c", launch, "--port", "0", *args],
                                     stdout=self._log, stderr=subprocess.STDOUT, cwd=str(REPO))
        deadline = time.monotonic() + 120
        while (found := re.search(r" on http://127\.0\.0\.1:(\d+)/", self.log())) is None:
            if self.proc.poll() is not None or time.monotonic() > deadline:
                self.stop()
                raise RuntimeError(f"the Hops server did not start: {self.log()}")
            time.sleep(0.05)
        self.port = int(found.group(1))
        self.url = f"http://127.0.0.1:{self.port}"
        # The workers say once that they are ready (a solve before would wait for them).
        while "ready: at most" not in self.log():
            if self.proc.poll() is not None or time.monotonic() > deadline:
                self.stop()
                raise RuntimeError(f"the Hops workers did not start: {self.log()}")
            time.sleep(0.05)

    def log(self):
        return self.log_path.read_bytes().decode(errors="replace")

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._log.close()


@pytest.fixture
def start(tmp_path):
    """Starts servers for one test (`start(*args)`) and stops them after it."""
    servers = []

    def started(*args, **kwargs):
        server = Server(tmp_path / f"hops{len(servers)}.log", *args, **kwargs)
        servers.append(server)
        return server

    yield started
    for server in servers:
        server.stop()


def _request(url, data=None, timeout=120):
    """(status, JSON answer, headers, the monotonic time the answer arrived)."""
    req = urllib.request.Request(url, data=data, method="POST" if data is not None else "GET",
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return r.status, json.loads(r.read()), dict(r.headers), time.monotonic()
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read()), dict(e.headers), time.monotonic()


def _item(type_, data):
    return {"type": type_, "data": data}


def _polyline_item(points):
    curve = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in np.asarray(points).tolist()])
    return _item("Rhino.Geometry.PolylineCurve", json.dumps(curve.Encode()))


def _body(directrix_item):
    """A /cnets_construct request with the directrix item given."""
    return json.dumps({"values": [
        {"ParamName": "Directrix", "InnerTree": {"{0}": [directrix_item]}},
        {"ParamName": "Generatrix", "InnerTree": {"{0}": [_polyline_item(profile(4))]}},
        {"ParamName": "Apex", "InnerTree": {"{0}": [_item("System.Double", "0.9")]}},
    ]}).encode()


SPIN = _body(_item("Rhino.Geometry.NurbsCurve", json.dumps({"spin": True})))
CRASH = _body(_item("Rhino.Geometry.NurbsCurve", json.dumps({"crash": True})))
GOOD = _body(_polyline_item(arc(5)))
# The hostile round's request: 100 bytes of base64 that rhino3dm 8 decodes for 13–60 s.
HOSTILE = _body(_item("Rhino.Geometry.NurbsCurve", json.dumps(
    {"version": 10000, "archive3dm": 70, "opennurbs": -1912572328, "data": "QUFB" * 25})))


def _one_error(status, response, expected_status, *words):
    assert status == expected_status, (status, response)
    assert response["values"] == [], response
    (error,) = response["errors"]
    assert "\n" not in error and "Traceback" not in error, error
    assert error.endswith("."), error
    for w in words:
        assert w in error, (w, error)
    return error


def _in_background(fn, *args):
    pool = concurrent.futures.ThreadPoolExecutor(1)
    future = pool.submit(fn, *args)
    pool.shutdown(wait=False)
    return future


def _solve_until_answered(url, deadline_s=60):
    """A good solve, retried while the server is busy (a killed worker is being replaced)."""
    deadline = time.monotonic() + deadline_s
    while True:
        status, response, headers, _ = _request(url + "/cnets_construct", GOOD)
        if status != 503 or time.monotonic() > deadline:
            return status, response
        time.sleep(0.5)


def _gets_while(url, future, pause=0.3):
    """GETs sent one after another until `future` is done: (latency, arrival time) of each."""
    answers = []
    while not future.done():
        sent = time.monotonic()
        status, listing, _, arrived = _request(url + "/", timeout=60)
        assert status == 200 and any(c["Uri"] == "/cnets_construct" for c in listing)
        answers.append((arrived - sent, arrived))
        time.sleep(pause)
    return answers


def _none_waited(gets, slow_ended):
    """No GET waited for the slow request: each arrived before it ended, or — one sent just as it
    ended, which may arrive after it — quickly."""
    return all(arrived < slow_ended or latency < 1.0 for latency, arrived in gets)


def test_a_slow_decode_is_stopped_at_the_time_limit_while_gets_are_answered(start):
    server = start("--workers", "1", "--timeout", "4")
    slow = _in_background(_request, server.url + "/cnets_construct", SPIN)
    time.sleep(0.5)  # the solve is running (its worker was ready)
    gets = _gets_while(server.url, slow)
    status, response, headers, slow_ended = slow.result()
    _one_error(status, response, 503, "time limit of 4 s", "--timeout")
    assert "Retry-After" not in headers, "the same request would time out again"
    # GETs went on while the worker spun holding its interpreter lock: several answered, every
    # one of them before the slow solve ended, each in well under a second.
    assert len(gets) >= 3, gets
    assert _none_waited(gets, slow_ended), gets
    latencies = sorted(latency for latency, _ in gets)
    assert latencies[len(latencies) // 2] < 1.0, latencies
    print(f"GET latency while a solve spins: median {latencies[len(latencies) // 2] * 1000:.1f} "
          f"ms, max {latencies[-1] * 1000:.1f} ms over {len(latencies)}")
    # The spinning worker was killed and replaced: the next solve is answered.
    status, response = _solve_until_answered(server.url)
    assert status == 200 and response["errors"] == [], response
    assert "the solve was stopped after" in server.log()
    assert "Traceback" not in server.log()


def test_other_solves_go_on_beside_a_slow_one(start):
    server = start("--workers", "2", "--timeout", "6")
    slow = _in_background(_request, server.url + "/cnets_construct", SPIN)
    time.sleep(0.5)
    answered = []
    for _ in range(5):
        status, response, _, arrived = _request(server.url + "/cnets_construct", GOOD)
        assert status == 200 and response["errors"] == [], response
        answered.append(arrived)
    status, response, _, slow_ended = slow.result()
    _one_error(status, response, 503, "time limit of 6 s")
    assert max(answered) < slow_ended, "the good solves did not wait for the slow one"


def test_the_hostile_rhino_archive_does_not_stall_the_server(start):
    """The hostile round's 1.2 KB request, decoded by rhino3dm itself."""
    server = start("--workers", "1", "--timeout", "3")
    slow = _in_background(_request, server.url + "/cnets_construct", HOSTILE)
    time.sleep(0.5)
    gets = _gets_while(server.url, slow)
    status, response, _, slow_ended = slow.result()
    if status == 503:
        _one_error(status, response, 503, "time limit of 3 s")
    else:  # a rhino3dm that decodes it quickly says it is no curve
        _one_error(status, response, 400, "Directrix", "could not be decoded")
    assert _none_waited(gets, slow_ended), gets
    assert all(latency < 5 for latency, _ in gets), gets


def test_solves_beyond_the_workers_and_the_queue_are_refused_at_once(start):
    """--workers 2 --queue 1: 4 slow solves at once; 2 run, 1 waits, the 4th is refused with
    Retry-After before any of the others ends."""
    server = start("--workers", "2", "--queue", "1", "--timeout", "5")
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        answers = list(pool.map(lambda _: _request(server.url + "/cnets_construct", SPIN),
                                range(4)))
    refused = [a for a in answers if "running and 1 waiting" in a[1]["errors"][0]]
    timed_out = [a for a in answers if "time limit of 5 s per request" in a[1]["errors"][0]]
    waited = [a for a in answers if "no solve worker became free" in a[1]["errors"][0]]
    assert len(refused) == 1, answers
    assert len(timed_out) >= 2 and len(refused) + len(timed_out) + len(waited) == 4, answers
    status, response, headers, refused_at = refused[0]
    _one_error(status, response, 503, "the server is busy", "2 solves running and 1 waiting",
               "--workers 2", "--queue 1")
    assert headers.get("Retry-After") == "5", headers
    assert refused_at < min(a[3] for a in timed_out), "refused at once, not after a wait"
    for status, response, headers, _ in waited:
        _one_error(status, response, 503, "within the time limit of 5 s")
        assert headers.get("Retry-After") == "5"
    # GETs are not solves: answered whatever the queue holds.
    assert _request(server.url + "/cnets_construct")[0] == 200


def test_a_worker_that_dies_is_replaced(start):
    server = start("--workers", "1")
    _one_error(*_request(server.url + "/cnets_construct", CRASH)[:2], 500,
               "ended unexpectedly", "exit code 3")
    status, response = _solve_until_answered(server.url)
    assert status == 200 and response["errors"] == [], response


def test_sigterm_stops_the_server_and_its_workers_at_once(start):
    psutil = pytest.importorskip("psutil")
    server = start("--workers", "2", "--timeout", "60")
    slow = _in_background(_request, server.url + "/cnets_construct", SPIN)
    time.sleep(0.5)
    children = psutil.Process(server.proc.pid).children(recursive=True)
    assert len(children) >= 2, children  # the workers (and multiprocessing's helper)
    sent = time.monotonic()
    server.proc.send_signal(signal.SIGTERM)
    server.proc.wait(timeout=30)
    took = time.monotonic() - sent
    print(f"SIGTERM to exit: {took * 1000:.0f} ms")
    assert took < 5, took
    gone, alive = psutil.wait_procs(children, timeout=10)
    assert alive == [], alive
    # The spinning request was dropped with its worker, or answered "shutting down" if that
    # answer got out first.
    try:
        status, response, _, _ = slow.result(timeout=30)
    except (OSError, http.client.HTTPException):
        pass
    else:
        _one_error(status, response, 503, "shutting down")
    assert "Traceback" not in server.log(), server.log()


def test_deep_json_is_refused_before_it_is_parsed(start):
    server = start("--workers", "1")
    url = server.url + "/cnets_construct"
    deep = b"[" * 200_000 + b"]" * 200_000
    _one_error(*_request(url, deep)[:2], 400, "more than 100 levels deep")
    _one_error(*_request(url, b'{"values": ' + b'{"a": ' * 200_000)[:2], 400,
               "more than 100 levels deep")
    # The same in UTF-16, which the JSON parser reads too.
    _one_error(*_request(url, ("[" * 200_000).encode("utf-16"))[:2], 400,
               "more than 100 levels deep")
    # Brackets inside strings are text, and 100 levels are read.
    text = json.dumps({"values": [], "note": "[" * 200_000})
    _one_error(*_request(url, text.encode())[:2], 400, "Directrix: no curve given")
    at_limit = b'{"values": ' + b"[" * 99 + b"]" * 99 + b"}"
    _one_error(*_request(url, at_limit)[:2], 400, "\"ParamName\"")
    _one_error(*_request(url, b'{"values": ' + b"[" * 100 + b"]" * 100 + b"}")[:2], 400,
               "more than 100 levels deep")
    # Deep JSON inside an item's data: the item is what is wrong.
    item = _item("Rhino.Geometry.NurbsCurve", "[" * 200_000)
    _one_error(*_request(url, _body(item))[:2], 400, "Directrix", "could not be decoded")
    status, response, _, _ = _request(url, GOOD)
    assert status == 200, response
    assert "RecursionError" not in server.log() and "Traceback" not in server.log(), server.log()


def test_limits_on_the_command_line(tmp_path):
    for args, words in ((["--workers", "-1"], "--workers: -1 is negative"),
                        (["--queue", "x"], "--queue: 'x' is not a whole number"),
                        (["--timeout", "0"], "--timeout: 0 is not a positive number of seconds"),
                        (["--timeout", "nan"], "--timeout: nan is not a positive number")):
        result = subprocess.run([sys.executable, "-m", "cnets.hops", *args], capture_output=True,
                                text=True, timeout=60, cwd=str(tmp_path))
        assert result.returncode == 2, result
        assert words in result.stderr, result.stderr
    result = subprocess.run([sys.executable, "-m", "cnets.hops", "--help"], capture_output=True,
                            text=True, timeout=60, cwd=str(tmp_path))
    for flag in ("--workers", "--queue", "--timeout"):
        assert flag in result.stdout


def test_create_app_takes_the_limits():
    from cnets.hops import DEFAULT_QUEUE, DEFAULT_TIMEOUT, DEFAULT_WORKERS, create_app

    assert 1 <= DEFAULT_WORKERS <= 4 and DEFAULT_QUEUE == 32 and DEFAULT_TIMEOUT == 60
    with create_app(workers=3, queue=7, timeout=2.5) as app:
        assert (app.workers, app.queue, app.timeout) == (3, 7, 2.5)
        assert app.worker_pids() == [], "workers start with the first POST or start()"
    with create_app(workers=0) as app:  # solves in the calling thread
        status, errors, data = app.answer_post("/cnets_construct", b"[" * 200_000)
        assert status == 400 and "100 levels" in errors[0]
        assert json.loads(data)["errors"] == errors
    for bad in ({"workers": -1}, {"queue": -1}, {"timeout": 0}):
        with pytest.raises(ValueError):
            create_app(**bad)
    # The decoder runs in the workers: one they cannot import is refused at once.
    with pytest.raises(ValueError, match="module-level function"):
        create_app(decode_geometry=lambda encoded: None)
    with create_app(workers=0, decode_geometry=lambda encoded: None):
        pass  # in the server process, any function does


def test_workers_solve_exactly_as_the_server_process(tmp_path):
    """A solve through a worker (the default) and one in the server process (`--workers 0`)
    give the same bytes."""
    from conftest import HopsProcess

    body = _body(_polyline_item(arc(7)))
    answers = []
    for args in (["--workers", "2"], ["--workers", "0"]):
        hops = HopsProcess(tmp_path / f"hops{len(answers)}.log", *args)
        try:
            status, response, _, _ = _request(hops.url + "/cnets_construct", body)
            assert status == 200, response
            answers.append(response)
        finally:
            hops.stop()
    assert answers[0] == answers[1]
