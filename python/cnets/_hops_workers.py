"""The Hops server's solve workers: every POST (its JSON read, its curves decoded with rhino3dm, the
solve, the answer encoded) runs in one of a few worker processes, so a request that decodes or
solves for a long time — rhino3dm's decoder holds the interpreter lock — delays no one else: the
server process only reads bodies, answers GETs and hands bodies over.

- ``workers`` processes (started with ``multiprocessing``'s 'spawn' context: the same on Linux,
  macOS and Windows, and safe beside the server's threads) solve at most ``workers`` requests at
  once; up to ``queue`` more wait for a free worker, at most ``timeout`` seconds; beyond that a
  request is answered at once with 503 and ``Retry-After``.
- A solve that runs longer than ``timeout`` seconds is answered with 503 naming the limit; its
  worker is killed (SIGKILL: it may be stuck in C code holding the lock) and replaced.
- A worker that dies (a crash in native code) is replaced; its request gets 500.
- ``close()`` kills every worker at once (the server's SIGTERM and Ctrl+C).
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import queue as _queue
import signal
import sys
import threading
import time
from typing import Any, Dict, List, Optional, Set, Tuple

_log = logging.getLogger("cnets.hops")

#: Seconds a new worker may take to import cnets and rhino3dm and say it is ready.
START_TIMEOUT = 120.0
#: The ``Retry-After`` (seconds) of a request refused because every worker is busy.
RETRY_AFTER = 5

_CONTEXT = multiprocessing.get_context("spawn")


def _seconds(t: float) -> str:
    return f"{t:g} s"


def _worker_main(conn: Any, options: Dict[str, Any]) -> None:
    """A worker process: builds the server's components, says ``("ready", pid)``, then answers
    ``(path, body)`` messages with ``(status, errors, JSON bytes)`` until its pipe closes."""
    if hasattr(signal, "SIGINT"):
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C is the server's to handle
    logging.basicConfig(level=logging.INFO, format="cnets.hops: %(message)s", stream=sys.stderr)
    try:
        from .hops import HopsServer

        server = HopsServer(workers=0, **options)
    except BaseException as e:  # noqa: BLE001 - said to the server, which refuses solves with it
        try:
            conn.send(("failed", f"{type(e).__name__}: {e}"))
        finally:
            return
    conn.send(("ready", os.getpid()))
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return  # the server closed the pipe (or died)
        if message is None:
            return
        path, body = message
        del message
        answer = server.answer_post(path, body)
        del body, path  # not held while idle (a body may be 64 MB)
        try:
            conn.send(answer)
        except (EOFError, OSError):
            return


class _Worker:
    """One worker process and the server's end of its pipe."""

    def __init__(self, options: Dict[str, Any]) -> None:
        here, there = _CONTEXT.Pipe()
        self.process = _CONTEXT.Process(target=_worker_main, args=(there, options), daemon=True,
                                        name="cnets-hops-worker")
        self.process.start()
        there.close()
        self.conn = here

    def kill(self) -> None:
        try:
            self.process.kill()
        except (OSError, ValueError, AttributeError):
            pass
        self.process.join(5)

    def close(self) -> None:
        self.kill()
        try:
            self.conn.close()
        except OSError:
            pass


class PoolError(Exception):
    """A request the pool cannot answer with a solution: an HTTP status, one sentence, and the
    ``Retry-After`` seconds when trying again later may help."""

    def __init__(self, message: str, status: int, retry_after: Optional[int] = None) -> None:
        super().__init__(message)
        self.status = status
        self.retry_after = retry_after


class SolvePool:
    """``workers`` worker processes solving POSTs with a time limit; see the module's text."""

    def __init__(self, options: Dict[str, Any], workers: int, queue: int, timeout: float) -> None:
        self.options = options
        self.workers = int(workers)
        self.queue = int(queue)
        self.timeout = float(timeout)
        self._idle: "_queue.Queue[Optional[_Worker]]" = _queue.Queue()
        self._admit = threading.BoundedSemaphore(self.workers + self.queue)
        self._lock = threading.Lock()
        self._live: Set[_Worker] = set()
        self._started = False
        self._closed = False
        self._failure: Optional[str] = None
        self._starting = 0  # the first workers not ready yet

    # -- life cycle

    def start(self) -> None:
        """Starts the workers (once); they say they are ready in the background."""
        with self._lock:
            if self._started or self._closed:
                return
            self._started = True
            self._starting = self.workers
        for _ in range(self.workers):
            self._spawn(first=True)

    def _spawn(self, first: bool = False) -> None:
        threading.Thread(target=self._boot, args=(first,), name="cnets-hops-worker-start",
                         daemon=True).start()

    def _boot(self, first: bool = False) -> None:
        """Starts one worker and, once it says it is ready, lets requests take it."""
        try:
            worker = _Worker(self.options)
        except Exception as e:  # noqa: BLE001 - cannot start a process at all
            self._fail(f"{type(e).__name__}: {e}")
            return
        with self._lock:
            if self._closed:
                worker.close()
                return
            self._live.add(worker)
        reason = None
        try:
            if worker.conn.poll(START_TIMEOUT):
                message = worker.conn.recv()
                if message[0] != "ready":
                    reason = str(message[1])
            else:
                reason = f"it was not ready within {_seconds(START_TIMEOUT)}"
        except (EOFError, OSError):
            worker.process.join(5)
            reason = f"it ended at start-up (exit code {worker.process.exitcode})"
        if reason is None:
            self._idle.put(worker)
            if first:
                with self._lock:
                    self._starting -= 1
                    all_ready = self._starting == 0
                if all_ready:  # one line at start-up, none per request
                    _log.info("%d worker process%s ready: at most %d solve%s at once, %d more "
                              "waiting, %s each", self.workers, "es" if self.workers != 1 else "",
                              self.workers, "s" if self.workers != 1 else "", self.queue,
                              _seconds(self.timeout))
            return
        self._retire(worker, replace=False)
        if not self._closed:
            self._fail(reason)

    def _fail(self, reason: str) -> None:
        """A worker could not start: it is not started again (that would fail the same way);
        once none is left, solves are refused with the reason."""
        _log.error("a solve worker could not start: %s", reason)
        with self._lock:
            self._failure = reason
            none_left = not self._live
        if none_left:
            self._idle.put(None)  # wakes a waiting request, which passes it on

    def _retire(self, worker: _Worker, replace: bool = True) -> None:
        """Kills a worker (timed out, dead or failed) and starts another unless closing."""
        worker.close()
        with self._lock:
            self._live.discard(worker)
            replace = replace and not self._closed
        if replace:
            self._spawn()

    def close(self) -> None:
        """Kills every worker now; requests still waiting are answered 503."""
        with self._lock:
            self._closed = True
            live = list(self._live)
            self._live.clear()
        for worker in live:
            try:
                worker.process.kill()
            except (OSError, ValueError, AttributeError):
                pass
        for worker in live:
            worker.process.join(2)
        self._idle.put(None)

    def pids(self) -> List[int]:
        """The process ids of the live workers."""
        with self._lock:
            return [w.process.pid for w in self._live if w.process.pid is not None]

    # -- solving

    def _closing(self) -> PoolError:
        return PoolError("the server is shutting down", 503, RETRY_AFTER)

    def _busy_error(self, waited: bool) -> PoolError:
        limits = (f"--workers {self.workers}, --queue {self.queue}, --timeout "
                  f"{self.timeout:g}")
        if waited:
            what = (f"the server is busy: no solve worker became free within the time limit of "
                    f"{_seconds(self.timeout)} ({limits})")
        else:
            what = (f"the server is busy: {self.workers} solve{'s' if self.workers != 1 else ''} "
                    f"running and {self.queue} waiting, its limits ({limits})")
        return PoolError(f"{what}; try again in a few seconds, or start the server with more "
                         "--workers", 503, RETRY_AFTER)

    def run(self, path: str, body: bytes) -> Tuple[int, List[str], bytes]:
        """Answers a POST in a worker: ``(status, errors, JSON bytes)``; raises ``PoolError``
        when the server is busy, the time limit is reached or the worker dies."""
        if self._closed:
            raise self._closing()
        self.start()
        if not self._admit.acquire(blocking=False):
            raise self._busy_error(waited=False)
        try:
            deadline = time.monotonic() + self.timeout
            while True:
                try:
                    worker = self._idle.get(timeout=max(0.0, deadline - time.monotonic()))
                except _queue.Empty:
                    raise self._busy_error(waited=True) from None
                if worker is None:  # closing, or no worker could start: pass the news on
                    self._idle.put(None)
                    if self._closed:
                        raise self._closing()
                    raise PoolError(f"no solve worker could start ({self._failure})", 500)
                if worker.process.is_alive():
                    break
                self._retire(worker)  # ended while idle (killed from outside): replaced
            return self._solve(worker, path, body)
        finally:
            self._admit.release()

    def _solve(self, worker: _Worker, path: str, body: bytes) -> Tuple[int, List[str], bytes]:
        started = time.monotonic()
        keep = False
        try:
            try:
                worker.conn.send((path, body))
                if not worker.conn.poll(self.timeout):
                    _log.warning("POST %s: the solve was stopped after %s (its worker was killed "
                                 "and is replaced)", path, f"{time.monotonic() - started:.1f} s")
                    raise PoolError(
                        f"the solve was stopped at this server's time limit of "
                        f"{_seconds(self.timeout)} per request; send less or simpler data "
                        "(fewer or coarser items, plainer curves) or start the server with a "
                        "larger --timeout", 503)
                answer = worker.conn.recv()
                keep = True
                return answer
            except (EOFError, OSError):
                if self._closed:
                    raise self._closing() from None
                worker.process.join(5)
                raise PoolError(
                    f"the worker process solving this request ended unexpectedly (exit code "
                    f"{worker.process.exitcode}); it is replaced, and the request may be what "
                    "made it fail", 500) from None
        finally:
            if keep and not self._closed:
                self._idle.put(worker)
            else:
                self._retire(worker)
