"""Design-space sweeps of a graph file on Dask (``pip install cnets[sweep]``).

``cnets.sweep(graph, parameters, outputs, client=None)`` evaluates the graph for every parameter
set and returns a pandas DataFrame, one row per design: the parameters, the requested outputs,
``ok`` (``True`` when every node ran and every requested figure is finite) and ``error``
(``None``, or why the design is flagged: the failed nodes' messages, the figures that are NaN or
infinite, an exception in its evaluation, a task lost with its worker). With no ``client`` it starts a ``dask.distributed``
``LocalCluster`` on this machine (and closes it afterwards); with a client it runs wherever the
client points (a SLURM cluster through ``dask-jobqueue``, Kubernetes…; see docs/python.md).

Each worker process loads the graph once (a per-worker cache keyed by the file's absolute path and
modification time) and re-evaluates incrementally: a design sets only its parameters and the
engine re-runs only what depends on the ones that changed.

A parameter node changes a value it cannot take (a slider clamps to its range, snaps to its step):
the row then holds the value actually used, and the sweep issues a ``cnets.CnetsWarning`` saying
so.
"""

from __future__ import annotations

import itertools
import os
import threading
import warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _cnets

__all__ = ["sweep", "designs", "evaluate_design"]

Parameters = Union[Dict[str, Sequence[Any]], Sequence[Dict[str, Any]]]

# Per worker process: (path, mtime, settings) → (graph, lock, initial values of set inputs).
_CACHE: Dict[Tuple[Any, ...], Tuple[Any, threading.Lock, Dict[str, Any]]] = {}
_CACHE_LOCK = threading.Lock()


def designs(parameters: Parameters) -> List[Dict[str, Any]]:
    """The parameter sets of a sweep: a dict of ``"node.input"`` → values is the full grid
    (itertools.product, the first parameter varying slowest); a list of dicts is taken as is."""
    if isinstance(parameters, dict):
        for name, values in parameters.items():
            _check_target(name, f"parameters[{name!r}]")
            if isinstance(values, (str, bytes, dict)) or not hasattr(values, "__iter__"):
                raise _cnets.CnetsError(f"parameters[{name!r}]: expected a list of values, got "
                                        f"{_describe(values)}")
        keys = list(parameters)
        values = [list(parameters[k]) for k in keys]
        return [dict(zip(keys, combo)) for combo in itertools.product(*values)]
    if isinstance(parameters, (str, bytes)) or not isinstance(parameters, (list, tuple)):
        raise _cnets.CnetsError("parameters: expected a dict of \"node.input\" → values or a list "
                                f"of dicts, got {_describe(parameters)}")
    out = []
    for k, p in enumerate(parameters):
        if not isinstance(p, dict):
            raise _cnets.CnetsError(f"parameters[{k}]: expected a dict of \"node.input\" → value, "
                                    f"got {_describe(p)}")
        for name in p:
            _check_target(name, f"parameters[{k}]")
        out.append(dict(p))
    return out


def _check_target(name: Any, where: str) -> None:
    if not isinstance(name, str) or "." not in name:
        raise _cnets.CnetsError(f"{where}: parameter {name!r} is not \"node.input\"")


def _describe(x: Any) -> str:
    from ._types import _describe as describe

    return describe(x)


def _cached_graph(path: str, settings: Tuple[Any, ...]) -> Tuple[Any, threading.Lock, Dict[str, Any]]:
    mtime = os.stat(path).st_mtime_ns
    key = (path, mtime, settings)
    with _CACHE_LOCK:
        entry = _CACHE.get(key)
        if entry is None:
            for old in [k for k in _CACHE if k[0] == path]:
                del _CACHE[old]
            allow_read, max_memory, library = settings
            graph = _cnets.Graph.load(
                path,
                allow_read=list(allow_read) or None,
                max_memory=max_memory,
                library=list(library) or None,
            )
            entry = (graph, threading.Lock(), {})
            _CACHE[key] = entry
        return entry


def _output(results: Dict[str, Dict[str, Any]], graph: Any, name: str) -> Any:
    """``node.output`` or ``node.output.field…`` (fields of a record output)."""
    parts = name.split(".")
    if len(parts) < 2:
        raise _cnets.CnetsError(f"output {name!r} is not \"node.output\"")
    node, output, fields = parts[0], parts[1], parts[2:]
    if node not in results:
        return np.nan
    if output not in results[node]:
        raise _cnets.CnetsError(f"output {name!r}: node '{node}' has no output '{output}'")
    value = results[node][output]
    for f in fields:
        if not isinstance(value, dict) or f not in value:
            raise _cnets.CnetsError(f"output {name!r}: no field '{f}'")
        value = value[f]
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value.item()
    return value


def evaluate_design(
    graph: str,
    design: Dict[str, Any],
    outputs: Sequence[str],
    index: int = 0,
    out: Optional[str] = None,
    allow_read: Sequence[str] = (),
    max_memory: Any = None,
    library: Sequence[str] = (),
) -> Dict[str, Any]:
    """Evaluates one design on this process's cached graph and returns its row: the parameters,
    the outputs, ``ok``, ``error`` and (with ``out``) the design's export folder
    ``out/design-<index>``. This is what each Dask task runs. It does not raise: a design whose
    evaluation fails, or whose figures are not finite, comes back with ``ok`` False and the
    reason in ``error``."""
    path = os.path.abspath(graph)
    g, lock, initial = _cached_graph(path, (tuple(allow_read), max_memory, tuple(library)))
    row: Dict[str, Any] = dict(design)
    notes: List[str] = []
    with lock, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", _cnets.CnetsWarning)
        try:
            # Inputs a previous design set but this one does not go back to the file's value.
            for target in list(initial):
                if target not in design:
                    g.unset(target) if initial[target] is None else g.set(target, initial[target])
            for target, value in design.items():
                if target not in initial:
                    initial[target] = g.get(target)
                g.set(target, value)
            # Parameter nodes are evaluated too: their output is the value actually used.
            params = {t.split(".")[0] for t in design
                      if g.node_type(t.split(".")[0]).startswith("param.")}
            nodes = sorted({o.split(".")[0] for o in outputs} | params)
            if out is not None:
                folder = os.path.join(out, f"design-{index:04d}")
                g.out = folder
                row["out"] = folder
                results = g.run(check=False)
            else:
                results = g.run(nodes=nodes, check=False)
            errors = [m for _, m in g.errors]
            for target, value in design.items():
                node, name = target.split(".", 1)
                if node in params and name in results.get(node, {}):
                    used = results[node][name]
                    used = used.item() if isinstance(used, np.ndarray) and used.ndim == 0 else used
                    if not _same(used, value):
                        notes.append(f"{target} = {value!r} was changed by its node to {used!r} "
                                     "(the row holds the value used)")
                    row[target] = used
            reasons = list(errors)
            for name in outputs:
                row[name] = _output(results, g, name)
                # A failed node's outputs are NaN: its message is the reason already.
                why = _not_finite(row[name]) if name.split(".")[0] in results else None
                if why:
                    reasons.append(f"{name} is not finite ({why})")
            row["error"] = "\n".join(reasons) if reasons else None
        except Exception as e:  # any failure flags this design, not the sweep
            for name in outputs:
                row.setdefault(name, np.nan)
            row["error"] = str(e) if isinstance(e, _cnets.CnetsError) else \
                f"the evaluation raised {type(e).__name__}: {e}"
        row["ok"] = row["error"] is None
        notes.extend(str(w.message) for w in caught if issubclass(w.category, _cnets.CnetsWarning))
    row["__notes__"] = notes
    return row


def _not_finite(value: Any) -> Optional[str]:
    """Why a figure is not finite (``"nan"``, ``"3 of 33 values"``), or ``None``: numbers,
    numeric arrays, and the numbers inside lists and records. Text, ``None`` and flags are no
    figures."""
    if isinstance(value, (bool, np.bool_)) or value is None:
        return None
    if isinstance(value, (int, float, np.integer, np.floating)):
        return None if np.isfinite(value) else repr(float(value))
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in "fc" or value.size == 0:
            return None
        bad = int(np.count_nonzero(~np.isfinite(value)))
        if not bad:
            return None
        return repr(float(value.reshape(-1)[0])) if value.size == 1 else \
            f"{bad} of {value.size} values"
    if isinstance(value, dict):
        parts = [f"{k}: {r}" for k, r in ((k, _not_finite(v)) for k, v in value.items()) if r]
        return ", ".join(parts) or None
    if isinstance(value, (list, tuple)):
        parts = [f"[{k}]: {r}" for k, r in ((k, _not_finite(v)) for k, v in enumerate(value)) if r]
        return ", ".join(parts) or None
    return None


def _same(a: Any, b: Any) -> bool:
    try:
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))
    except Exception:
        return False


def sweep(
    graph: Any,
    parameters: Parameters,
    outputs: Sequence[str],
    client: Any = None,
    out: Optional[Any] = None,
    allow_read: Sequence[Any] = (),
    max_memory: Any = None,
    library: Sequence[Any] = (),
    n_workers: Optional[int] = None,
) -> Any:
    """Evaluates a graph file for every parameter set on Dask; returns a pandas DataFrame with
    one row per design (in the order of ``designs(parameters)``): the parameter columns, one
    column per requested output (``"node.output"``, or ``"node.output.field"`` for a field of a
    record such as ``"net.quality.max_planarity"``), ``ok`` and ``error`` and, with ``out``, the
    design's export folder (``out/design-0000`` …).

    A bad design flags its row instead of stopping the sweep: ``ok`` is ``True`` when every node
    ran and every requested figure (numbers, numeric arrays, the numbers in records) is finite;
    otherwise ``False``, with ``error`` saying why, one reason a line — the failed nodes'
    messages (their outputs are NaN), ``"<output> is not finite (…)"`` (the value is kept: a
    cone apex at infinity is a NaN point), an exception raised while evaluating, or the task
    failing on its worker. ``df[df.ok]`` keeps the good designs.

    ``client``: a ``dask.distributed.Client``; ``None`` starts a ``LocalCluster`` (``n_workers``
    processes, one thread each) for this call. ``allow_read``, ``max_memory``, ``library`` are
    those of ``Graph.load``. The graph file and ``out`` must be reachable by the workers under
    the same path (a shared file system on a cluster).
    """
    import pandas as pd
    from dask.distributed import Client, LocalCluster

    try:
        path = os.path.abspath(os.fspath(graph))
    except TypeError:
        raise _cnets.CnetsError(f"graph: expected the path of a graph file, got {_describe(graph)}") from None
    if isinstance(outputs, str):
        outputs = [outputs]
    if not isinstance(outputs, (list, tuple)) or not all(isinstance(o, str) for o in outputs):
        raise _cnets.CnetsError(f"outputs: expected a list of \"node.output\" names, got "
                                f"{_describe(outputs)}")
    if n_workers is not None and (isinstance(n_workers, bool) or not isinstance(n_workers, int)
                                  or n_workers < 1):
        raise _cnets.CnetsError(f"n_workers: expected a positive int, got {_describe(n_workers)}")
    for name, folders in (("allow_read", allow_read), ("library", library)):
        if isinstance(folders, (str, os.PathLike)):
            raise _cnets.CnetsError(f"{name}: expected a list of folders, got {_describe(folders)}")
    # Fail here, not on every worker, when the file does not load.
    probe = _cnets.Graph.load(path, allow_read=[os.fspath(p) for p in allow_read] or None,
                              max_memory=max_memory, library=[os.fspath(p) for p in library] or None)
    for name in outputs:
        node = name.split(".")[0]
        if node not in probe.nodes:
            raise _cnets.CnetsError(f"output {name!r}: no node '{node}' in {path}")
    sets = designs(parameters)
    for target in {t for d in sets for t in d}:
        probe.get(target)  # raises on a wrong node or input
    del probe
    kwargs = dict(
        outputs=list(outputs),
        out=os.path.abspath(os.fspath(out)) if out is not None else None,
        allow_read=tuple(os.path.abspath(os.fspath(p)) for p in allow_read),
        max_memory=max_memory,
        library=tuple(os.path.abspath(os.fspath(p)) for p in library),
    )
    own = client is None
    cluster = None
    if own:
        cluster = LocalCluster(n_workers=n_workers or min(4, os.cpu_count() or 1),
                               threads_per_worker=1, processes=True, dashboard_address=":0")
        client = Client(cluster)
    try:
        futures = [
            client.submit(evaluate_design, path, d, index=k, pure=False, **kwargs)
            for k, d in enumerate(sets)
        ]
        rows = []
        for k, (design, future) in enumerate(zip(sets, futures)):
            try:
                rows.append(future.result())
            except Exception as e:  # the task itself failed: a worker lost, bad data, …
                row = dict(design)
                row.update({name: np.nan for name in outputs})
                row.update(ok=False, error=f"the design's task failed: {type(e).__name__}: {e}")
                if out is not None:
                    row["out"] = os.path.join(kwargs["out"], f"design-{k:04d}")
                rows.append(row)
    finally:
        if own:
            client.close()
            cluster.close()
    for k, row in enumerate(rows):
        for note in row.pop("__notes__", []):
            warnings.warn(f"design {k}: {note}", _cnets.CnetsWarning, stacklevel=2)
    columns: List[str] = []
    for d in sets:
        columns.extend(c for c in d if c not in columns)
    columns += [o for o in outputs if o not in columns] + ["ok", "error"]
    if out is not None:
        columns.append("out")
    return pd.DataFrame(rows, columns=columns)
