"""cnets in Grasshopper through McNeel's Hops component: ``python -m cnets.hops [--port 5000]
[--library DIR] [--max-body 64MB] [--max-memory SIZE] [--workers N] [--queue 32] [--timeout 60]``
serves the components below over HTTP on 127.0.0.1 (werkzeug's threaded server). In Grasshopper:
a Hops component, Path ``http://localhost:5000/cnets_construct``.

Components (inputs → outputs):

- ``/cnets_construct``: ``Directrix`` curve, ``Generatrix`` curve, ``Apex`` number list, ``Ratios``
  number list or tree, ``Assistance`` number → ``Mesh`` (the cone-net, a quad mesh), ``Apex`` (the
  apex values used), ``Quality`` (the largest planarity defect).
- ``/cnets_construct_coplanar``: ``Directrix``, ``Generatrix``, ``Apex``, ``RulingRatios``,
  ``PlaneRatios``, ``Assistance`` → ``Mesh``, ``Apex``, ``Quality``.
- ``/cnets_graph_to_apex``: ``Widths`` number list, ``Normalized`` boolean, ``Directrix`` curve,
  ``Scale`` number (0: the directrix length / 5) → ``Apex``.
- ``/cnets_support``: ``Directrix`` curve, ``Mesh`` (a cone-net from ``/cnets_construct``),
  ``Apex`` (its apex output), ``Factor`` number → ``Axes`` (the torsion-free node axes, lines),
  ``Support`` (a conical second layer, a mesh).
- one component per graph file of ``--library`` that has ``graph.input`` / ``graph.output`` nodes,
  at ``/<file name without .ron>`` (percent-encoded in URLs: ``my tube.ron`` is ``/my%20tube``),
  with the graph's inputs and outputs, named as the built-ins' are (``closure_gap`` is
  ``ClosureGap``) and reading the same inputs (one number broadcasts to a list or table port). A
  file whose name cannot be a URL of its own (``...ron``, a name of a built-in component, two
  names that differ only in case) is skipped with the reason at start-up.

The server parses Hops' requests and encodes its answers itself: numbers are read straight from
the request, curves decoded with rhino3dm, meshes written in bulk from the engine's arrays with
double-precision vertices (``cnets._opennurbs``), nothing printed per request. Every failure —
a body that is not JSON or nested more than ``MAX_JSON_DEPTH`` (100) deep, an input of the wrong
kind, a node that fails, a body over ``--max-body`` (HTTP 413) — is answered with a Hops response
whose error is one sentence; the solves run under the engine's memory budget (``--max-memory``).

Solves run in worker processes (``cnets._hops_workers``), so a slow one — rhino3dm's decoder can
spend a minute on 100 bytes while holding the interpreter lock — delays neither GETs nor other
solves: at most ``--workers`` solves at once, ``--queue`` more waiting (beyond: 503 with
``Retry-After``), each stopped after ``--timeout`` seconds (503 naming the limit; its worker is
killed and replaced). SIGTERM and Ctrl+C kill the workers and stop the server at once.

Curves: a polyline curve gives its vertices; any other Rhino curve (NURBS, arc…) is sampled at
``--samples`` points (default 33).
"""

from __future__ import annotations

import argparse
import functools
import json
import logging
import math
import os
import signal
import sys
import unicodedata
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union
from urllib.parse import quote, unquote, urlsplit

import numpy as np

from . import _cnets
from ._opennurbs import encode_mesh_json
from ._types import PolygonMesh, Polyline, QuadMesh

__all__ = ["HopsServer", "create_app", "main", "DEFAULT_MAX_BODY", "DEFAULT_WORKERS",
           "DEFAULT_QUEUE", "DEFAULT_TIMEOUT", "MAX_JSON_DEPTH"]

#: The default limit of a request body: 64 MB.
DEFAULT_MAX_BODY = 64_000_000
#: The default number of worker processes, each solving one request at a time.
DEFAULT_WORKERS = max(1, min(4, os.cpu_count() or 1))
#: The default number of requests that may wait for a free worker (more: 503 at once).
DEFAULT_QUEUE = 32
#: The default time limit of a solve, in seconds (and of a wait for a free worker).
DEFAULT_TIMEOUT = 60.0
#: The deepest nesting of JSON arrays and objects read, in a body or in an item's data (a Hops
#: request is 6 levels deep); deeper JSON is refused before it is parsed.
MAX_JSON_DEPTH = 100

_log = logging.getLogger("cnets.hops")

ITEM, LIST, TREE = "item", "list", "tree"


class HopsError(Exception):
    """A request that cannot be answered with a solution: its one-sentence message goes back to
    Grasshopper as the component's error, with an HTTP status."""

    def __init__(self, message: str, status: int = 400, retry_after: Optional[int] = None) -> None:
        super().__init__(message)
        self.status = status
        self.retry_after = retry_after


def _sentence(message: str) -> str:
    """One line, ending with a full stop."""
    text = " ".join(part.strip() for part in str(message).splitlines() if part.strip())
    text = text or "unknown error"
    return text if text.endswith((".", "!", "?")) else text + "."


# -------------------------------------------------------------------------------------------
# JSON, its nesting checked before it is parsed


class JsonTooDeep(ValueError):
    """JSON nested deeper than the limit (a ``ValueError``: read as "not JSON" where that is what
    is caught)."""


_SCAN_CHUNK = 1 << 22
# Every byte but the quote and the four brackets (deleted before the scan).
_NOT_STRUCTURE = bytes(b for b in range(256) if b not in b'"[]{}')


def _nesting_exceeds(data: bytes, limit: int) -> bool:
    """Whether UTF-8 JSON ``data`` nests arrays and objects more than ``limit`` deep, brackets
    inside strings not counted: a linear scan (C loops and numpy). Up to the first syntax error
    it reads the text as the JSON parser does, so JSON that passes cannot make the parser recurse
    deeper than ``limit``."""
    if data.count(b"[") + data.count(b"{") <= limit:
        return False  # the common case: too few brackets to be too deep
    # Escapes first, left to right as the parser reads them: an escaped backslash, then an
    # escaped quote; what is left of a string is text between two quotes.
    structure = data.replace(b"\\\\", b"").replace(b'\\"', b"").translate(None, _NOT_STRUCTURE)
    codes = np.frombuffer(structure, dtype=np.uint8)
    depth, inside = 0, 0  # at the end of the previous piece; inside: 1 within a string
    for start in range(0, len(codes), _SCAN_CHUNK):
        piece = codes[start:start + _SCAN_CHUNK]
        in_string = (np.cumsum(piece == 34, dtype=np.int32) + inside) & 1
        step = (piece == 91).astype(np.int32) + (piece == 123) - (piece == 93) - (piece == 125)
        level = np.cumsum(step * (in_string == 0), dtype=np.int32) + depth
        if int(level.max()) > limit:
            return True
        depth, inside = int(level[-1]), int(in_string[-1])
    return False


def _json_loads(data: Union[str, bytes], limit: int = MAX_JSON_DEPTH) -> Any:
    """``json.loads``, with JSON nested deeper than ``limit`` refused (``JsonTooDeep``) before
    the parser recurses into it."""
    if isinstance(data, str):
        scan = data.encode("utf-8", "surrogatepass")
    else:
        data = bytes(data)
        encoding = json.detect_encoding(data)
        if encoding == "utf-8":
            scan = data
        else:  # UTF-16/32 (or a BOM): read as the parser would, scanned as UTF-8
            data = data.decode(encoding, "surrogatepass")
            scan = data.encode("utf-8", "surrogatepass")
    if _nesting_exceeds(scan, limit):
        raise JsonTooDeep(f"JSON arrays and objects nested more than {limit} levels deep")
    return json.loads(data)


# -------------------------------------------------------------------------------------------
# Parameters


@dataclass
class Param:
    """A Hops parameter: its Grasshopper type, access (one item, a list or a tree) and default.
    ``metadata()`` is what Hops reads when it asks the component's URL."""

    name: str
    nickname: str
    description: str
    kind: str  # Curve, Number, Integer, Boolean, Text, Point, Vector, Mesh, Line
    access: str = ITEM
    default: Any = None
    optional: bool = False

    _RESULT_TYPES = {
        "Curve": "Rhino.Geometry.Curve",
        "Number": "System.Double",
        "Integer": "System.Int32",
        "Boolean": "System.Boolean",
        "Text": "System.String",
        "Point": "Rhino.Geometry.Point3d",
        "Vector": "Rhino.Geometry.Vector3d",
        "Mesh": "Rhino.Geometry.Mesh",
    }

    def metadata(self) -> Dict[str, Any]:
        """The parameter as Hops reads it (the fields ghhops-server writes)."""
        at_least, at_most = {ITEM: (1, 1), LIST: (1, 2147483647), TREE: (-1, -1)}[self.access]
        data: Dict[str, Any] = {
            "Name": self.name,
            "Nickname": self.nickname,
            "Description": self.description,
            "ParamType": self.kind,
            "ResultType": self._RESULT_TYPES[self.kind],
            "AtLeast": at_least,
            "AtMost": at_most,
        }
        if self.default is not None:
            data["Default"] = self.default
        return data


@dataclass
class Component:
    """A Hops component: ``solve`` takes the decoded inputs by name and returns the outputs in
    order (each a value or a list of values, already encoded as Hops items)."""

    path: str  # the decoded URL path, "/cnets_construct"
    name: str
    nickname: str
    description: str
    subcategory: str
    inputs: List[Param]
    outputs: List[Param]
    solve: Callable[[Dict[str, Any]], List[List[Dict[str, str]]]]
    category: str = "cnets"
    #: Other names a request may give an input by (a library graph's port names, which Hops
    #: components saved before the inputs were Capitalised send) → the input's name.
    aliases: Dict[str, str] = field(default_factory=dict)

    @property
    def uri(self) -> str:
        """The component's URL path, percent-encoded (``/my%20tube``)."""
        return quote(self.path)

    def metadata(self) -> Dict[str, Any]:
        """The component as Hops reads it from its URL (``GET /<component>``)."""
        return {
            "Uri": self.uri,
            "Name": self.name,
            "Nickname": self.nickname,
            "Description": self.description,
            "Category": self.category,
            "Subcategory": self.subcategory,
            "Inputs": [p.metadata() for p in self.inputs],
            "Outputs": [p.metadata() for p in self.outputs],
        }


# -------------------------------------------------------------------------------------------
# Reading Hops items

_KIND_WORDS = {
    "System.Double": "a number",
    "System.Int32": "an integer",
    "System.Boolean": "a boolean",
    "System.String": "a text",
}


def _what(item_type: str) -> str:
    if item_type in _KIND_WORDS:
        return f"{_KIND_WORDS[item_type]} ({item_type})"
    if item_type.startswith("Rhino.Geometry."):
        return f"a {item_type[len('Rhino.Geometry.'):]} ({item_type})"
    return f"a {item_type or 'value of no type'}"


def _branches(param: Param, entry: Any) -> List[Tuple[str, List[Any]]]:
    """The branches of one input of the request, in path order, checked for shape."""
    tree = entry.get("InnerTree") if isinstance(entry, dict) else None
    if tree is None:
        return []
    if not isinstance(tree, dict):
        raise HopsError(f"{param.name}: \"InnerTree\" must map tree paths to lists of items")
    branches = []
    for path, items in tree.items():
        if not isinstance(items, list):
            raise HopsError(f"{param.name}: the branch {path} is not a list of items")
        branches.append((path, items))
    try:
        branches.sort(key=lambda b: [int(p) for p in b[0].strip("{}").split(";") if p.strip()])
    except ValueError:
        raise HopsError(f"{param.name}: a tree path is not a list of integers such as {{0;1}}") from None
    return branches


def _item_parts(param: Param, item: Any, where: str) -> Tuple[str, str]:
    if not isinstance(item, dict) or not isinstance(item.get("data"), str):
        raise HopsError(f"{param.name}: item {where} must be an object with a \"type\" and a "
                        "\"data\" text")
    return str(item.get("type") or ""), item["data"]


def _decode_number(param: Param, item: Any, where: str, integer: bool = False) -> Any:
    item_type, data = _item_parts(param, item, where)
    text = data.strip().strip('"')
    try:
        value = float(text)
    except ValueError:
        raise HopsError(f"{param.name}: item {where} is {_what(item_type)} ({data[:40]!r}), not a "
                        "number") from None
    if not math.isfinite(value):
        raise HopsError(f"{param.name}: item {where} ({data[:40]!r}) is not a finite number")
    if integer:
        if value != int(value):
            raise HopsError(f"{param.name}: item {where} ({data[:40]!r}) is not a whole number")
        return int(value)
    return value


def _fast_numbers(items: List[Any]) -> Optional[List[float]]:
    """A branch of plain finite numbers read in one pass (the common case: a ratio tree of
    15 000 items); ``None`` when any item is not one."""
    try:
        values = [float(item["data"]) for item in items]
    except (TypeError, KeyError, ValueError):
        return None
    return values if all(map(math.isfinite, values)) else None


def _decode_boolean(param: Param, item: Any, where: str) -> bool:
    item_type, data = _item_parts(param, item, where)
    text = data.strip().strip('"').lower()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    raise HopsError(f"{param.name}: item {where} is {_what(item_type)} ({data[:40]!r}), not True "
                    "or False")


def _decode_text(param: Param, item: Any, where: str) -> str:
    _, data = _item_parts(param, item, where)
    try:
        value = _json_loads(data)
    except ValueError:
        return data
    return value if isinstance(value, str) else data


def _decode_geometry(param: Param, item: Any, where: str,
                     decode: Optional[Callable[[Dict[str, Any]], Any]] = None) -> Any:
    import rhino3dm

    item_type, data = _item_parts(param, item, where)
    expected = "a curve" if param.kind in ("Curve", "Line") else "a mesh"
    if not item_type.startswith("Rhino.Geometry."):
        raise HopsError(f"{param.name}: item {where} is {_what(item_type)}, expected {expected}")
    try:
        encoded = _json_loads(data)
        decode = decode or rhino3dm.CommonObject.Decode
        geometry = decode(encoded) if isinstance(encoded, dict) else None
    except Exception:  # rhino3dm raises plain exceptions on bad archives
        geometry = None
    if geometry is None:
        raise HopsError(f"{param.name}: item {where} ({item_type}) could not be decoded as Rhino "
                        "geometry")
    wanted = rhino3dm.Curve if param.kind in ("Curve", "Line") else rhino3dm.Mesh
    if not isinstance(geometry, wanted):
        raise HopsError(f"{param.name}: item {where} is a {type(geometry).__name__}, expected "
                        f"{expected}")
    return geometry


def _decode_point(param: Param, item: Any, where: str) -> List[float]:
    item_type, data = _item_parts(param, item, where)
    try:
        p = _json_loads(data)
        return [float(p["X"]), float(p["Y"]), float(p["Z"])]
    except (ValueError, TypeError, KeyError):
        raise HopsError(f"{param.name}: item {where} is {_what(item_type)}, expected a point with "
                        "X, Y and Z") from None


def _decoder(param: Param, decode_geometry: Optional[Callable] = None
             ) -> Callable[[Param, Any, str], Any]:
    def geometry(p: Param, i: Any, w: str) -> Any:
        return _decode_geometry(p, i, w, decode_geometry)

    return {
        "Number": _decode_number,
        "Integer": lambda p, i, w: _decode_number(p, i, w, integer=True),
        "Boolean": _decode_boolean,
        "Text": _decode_text,
        "Curve": geometry,
        "Line": geometry,
        "Mesh": geometry,
        "Point": _decode_point,
        "Vector": _decode_point,
    }[param.kind]


def read_input(param: Param, entry: Any, decode_geometry: Optional[Callable] = None) -> Any:
    """One input of a request as Python values: an item (or ``None`` when empty), a list, or a
    list of branches (a tree), decoded by the parameter's kind (Rhino geometry by
    ``decode_geometry``, default ``rhino3dm.CommonObject.Decode``)."""
    decode = _decoder(param, decode_geometry)
    branches = _branches(param, entry)
    decoded = []
    for path, items in branches:
        values = _fast_numbers(items) if param.kind == "Number" else None
        if values is None:  # not plain numbers: item by item, for a precise message
            values = [decode(param, item, f"{k} of branch {path}") for k, item in enumerate(items)]
        decoded.append(values)
    decoded = [b for b in decoded if b]
    if param.access == TREE:
        return decoded
    flat = [v for b in decoded for v in b]
    if param.access == LIST:
        return flat
    if len(flat) > 1:
        raise HopsError(f"{param.name}: expected one item, got {len(flat)}")
    return flat[0] if flat else None


# -------------------------------------------------------------------------------------------
# Writing Hops items


def _number_item(x: Any) -> Dict[str, str]:
    return {"type": "System.Double", "data": repr(float(x))}


def _mesh_item(mesh: Any) -> Dict[str, str]:
    if isinstance(mesh, QuadMesh):
        data = encode_mesh_json(mesh.vertices.reshape(-1, 3), mesh.faces())
    elif isinstance(mesh, PolygonMesh):
        data = encode_mesh_json(mesh.vertices, _polygon_faces(mesh.faces))
    else:
        raise HopsError(f"the output is a {type(mesh).__name__}, not a mesh", 500)
    return {"type": "Rhino.Geometry.Mesh", "data": data}


def _polygon_faces(faces: Sequence[Sequence[int]]) -> np.ndarray:
    """Faces as Rhino's quads and triangles (a triangle repeats its third index; larger
    polygons are fanned into triangles)."""
    out: List[Tuple[int, int, int, int]] = []
    for f in faces:
        if len(f) == 4:
            out.append((f[0], f[1], f[2], f[3]))
        elif len(f) >= 3:
            out.extend((f[0], f[k], f[k + 1], f[k + 1]) for k in range(1, len(f) - 1))
    return np.asarray(out, dtype=np.int64).reshape(-1, 4)


def _curve_item(points: np.ndarray, closed: bool) -> Dict[str, str]:
    import rhino3dm

    pts = [rhino3dm.Point3d(*p) for p in np.asarray(points, dtype=np.float64).tolist()]
    if closed and pts:
        pts.append(pts[0])
    curve = rhino3dm.LineCurve(pts[0], pts[1]) if len(pts) == 2 else rhino3dm.PolylineCurve(pts)
    kind = "LineCurve" if len(pts) == 2 else "PolylineCurve"
    return {"type": f"Rhino.Geometry.{kind}", "data": json.dumps(curve.Encode())}


def _point_item(p: Any, kind: str) -> Dict[str, str]:
    x, y, z = (float(c) for c in np.asarray(p, dtype=np.float64).reshape(3))
    return {"type": f"Rhino.Geometry.{'Point3d' if kind == 'Point' else 'Vector3d'}",
            "data": json.dumps({"X": x, "Y": y, "Z": z})}


def write_output(param: Param, value: Any) -> List[Dict[str, str]]:
    """A cnets value as the list of Hops items of one output."""
    if value is None:
        return []
    kind = param.kind
    if kind == "Mesh":
        items = value if isinstance(value, list) else [value]
        return [_mesh_item(m) for m in items]
    if kind in ("Curve", "Line"):
        if isinstance(value, Polyline):
            return [_curve_item(value.points, value.closed)]
        if isinstance(value, np.ndarray) and value.ndim == 3 and value.shape[1:] == (2, 3):
            return [_curve_item(line, False) for line in value]
        if isinstance(value, list):
            return [item for v in value for item in write_output(param, v)]
        raise HopsError(f"{param.name}: the output is a {type(value).__name__}, not a curve", 500)
    if kind in ("Point", "Vector"):
        arr = np.asarray(value, dtype=np.float64)
        return [_point_item(p, kind) for p in arr.reshape(-1, 3)]
    if kind == "Number":
        return [_number_item(x) for x in np.asarray(value, dtype=np.float64).reshape(-1)]
    if kind == "Integer":
        return [{"type": "System.Int32", "data": str(int(x))}
                for x in np.asarray(value).reshape(-1)]
    if kind == "Boolean":
        flat = value if isinstance(value, list) else [value]
        return [{"type": "System.Boolean", "data": "true" if v else "false"} for v in flat]
    flat = value if isinstance(value, list) else [value]
    return [{"type": "System.String", "data": json.dumps(_text(v))} for v in flat]


def _text(v: Any) -> str:
    if isinstance(v, str):
        return v
    if isinstance(v, dict):
        return json.dumps({k: (x.tolist() if isinstance(x, np.ndarray) else x) for k, x in v.items()},
                          default=str)
    if isinstance(v, np.ndarray):
        return json.dumps(v.tolist())
    return str(v)


# -------------------------------------------------------------------------------------------
# cnets values from Rhino geometry


def curve_polyline(param_name: str, curve: Any, samples: int) -> Polyline:
    """A Rhino curve as a cnets polyline (see ``cnets.rhino.curve_points``)."""
    from .rhino import curve_points

    try:
        return curve_points(curve, samples)
    except _cnets.CnetsError as e:
        raise HopsError(f"{param_name}: {e}") from None


def grid_from_rhino(param_name: str, mesh: Any) -> QuadMesh:
    """The quad grid of a Rhino mesh written by cnets (row-major vertices, quads
    ``(i·M+j, i·M+j+1, (i+1)·M+j+1, (i+1)·M+j)``, the wrapping row last), with its vertices at
    full precision."""
    from .rhino import mesh_from_rhino

    poly = mesh_from_rhino(mesh)
    faces = np.asarray([f if len(f) == 4 else f + [f[-1]] for f in poly.faces], dtype=np.int64)
    count = len(poly.vertices)
    bad = HopsError(f"{param_name}: the mesh is not a quad grid as cnets writes it (use the Mesh "
                    "output of a cnets component)")
    if len(faces) == 0 or faces.shape[1] != 4:
        raise bad
    cols = int(faces[0, 3] - faces[0, 0])
    if cols < 2 or count % cols:
        raise bad
    rows = count // cols
    i = np.arange(rows)[:, None]
    j = np.arange(cols - 1)[None, :]
    a = i * cols + j
    grid = np.stack([a, a + 1, (a + 1 + cols) % count, (a + cols) % count], axis=-1)
    open_faces = grid[:-1].reshape(-1, 4)
    if len(faces) == len(open_faces) and np.array_equal(faces, open_faces):
        wrap = False
    elif len(faces) == rows * (cols - 1) and np.array_equal(faces, grid.reshape(-1, 4)):
        wrap = True
    else:
        raise bad
    return QuadMesh(poly.vertices.reshape(rows, cols, 3), wrap_rows=wrap)


# -------------------------------------------------------------------------------------------
# The server


class HopsServer:
    """The cnets components and the WSGI application that serves them to Hops (a werkzeug
    application: ``make_server(host, port, server, threaded=True)``).

    POSTs are solved in ``workers`` worker processes (``cnets._hops_workers``): at most
    ``workers`` at once, up to ``queue`` more waiting, each stopped after ``timeout`` seconds
    (503 naming the limit; the worker is killed and replaced). ``workers=0`` solves in the
    calling thread, without a time limit. The workers start with the first POST or ``start()``;
    ``close()`` (or leaving a ``with`` block) kills them. ``decode_geometry`` replaces
    ``rhino3dm.CommonObject.Decode`` for Rhino geometry items; it runs in the workers, so it must
    be picklable (a module-level function)."""

    def __init__(self, library: Optional[str] = None, samples: int = 33,
                 max_body: int = DEFAULT_MAX_BODY, max_memory: Any = None, *,
                 workers: int = DEFAULT_WORKERS, queue: int = DEFAULT_QUEUE,
                 timeout: float = DEFAULT_TIMEOUT,
                 decode_geometry: Optional[Callable[[Dict[str, Any]], Any]] = None) -> None:
        if int(workers) < 0 or int(queue) < 0:
            raise ValueError("workers and queue must be 0 or more")
        if not float(timeout) > 0:
            raise ValueError("timeout must be a positive number of seconds")
        self.samples = int(samples)
        self.max_body = int(max_body)
        self.max_memory = max_memory
        self.workers = int(workers)
        self.queue = int(queue)
        self.timeout = float(timeout)
        self.decode_geometry = decode_geometry
        self.library = [str(library)] if library else []
        self._pool: Any = None
        if self.workers and decode_geometry is not None:
            import pickle

            try:
                pickle.dumps(decode_geometry)
            except Exception as e:
                raise ValueError("decode_geometry must be a module-level function the worker "
                                 f"processes can import ({type(e).__name__}: {e})") from None
        if self.workers:
            from ._hops_workers import SolvePool

            options = {"library": library, "samples": self.samples, "max_body": self.max_body,
                       "max_memory": max_memory, "decode_geometry": decode_geometry}
            self._pool = SolvePool(options, self.workers, self.queue, self.timeout)
        self.components: Dict[str, Component] = {}
        #: Library files that are not served, with the reason (reported at start-up).
        self.skipped: List[str] = []
        for component in _builtin_components(self):
            self.components[component.path] = component
        if library:
            self._add_library(Path(library))

    # -- the workers

    def start(self) -> "HopsServer":
        """Starts the worker processes now (else the first POST does); they get ready in the
        background."""
        if self._pool is not None:
            self._pool.start()
        return self

    def close(self) -> None:
        """Kills the worker processes at once; later POSTs are answered 503."""
        if self._pool is not None:
            self._pool.close()

    def worker_pids(self) -> List[int]:
        """The process ids of the live worker processes."""
        return self._pool.pids() if self._pool is not None else []

    def __enter__(self) -> "HopsServer":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    # -- the engine

    def eval(self, node_type: str, inputs: Dict[str, Any], outputs: Optional[List[str]] = None,
             title: str = "") -> Dict[str, Any]:
        """Evaluates a node under the server's memory budget; a failure is a ``HopsError`` whose
        message starts with the component's ``title``."""
        try:
            return _cnets.eval(node_type, {k: v for k, v in inputs.items() if v is not None},
                               outputs=outputs, max_memory=self.max_memory,
                               library=self.library or None)
        except _cnets.CnetsError as e:
            # A node's failure carries its reason apart from the node type (CnetsError.reason);
            # other errors (a bad input, the memory budget) are said as they are.
            message = getattr(e, "reason", None) or str(e)
            raise HopsError(f"{title or node_type}: {message}") from None

    def curve(self, name: str, value: Any, required: bool = True) -> Optional[Polyline]:
        """The Rhino curve of input ``name`` as a polyline (``None`` when absent and not
        ``required``)."""
        if value is None:
            if required:
                raise HopsError(f"{name}: no curve given")
            return None
        return curve_polyline(name, value, self.samples)

    # -- the library

    def _add_library(self, folder: Path) -> None:
        taken = {unicodedata.normalize("NFC", p).casefold(): p for p in self.components}
        taken["/solve"] = "/solve"
        for path in sorted(folder.glob("*.ron")):
            name = path.name[: -len(".ron")]
            reason = _unsafe_name(name)
            url = "/" + name
            key = unicodedata.normalize("NFC", url).casefold()
            if reason is None and key in taken:
                reason = (f"its URL {quote(url)} would be the same as {quote(taken[key])}'s "
                          "(URLs that differ only in case or Unicode form are not told apart)")
            if reason is not None:
                self.skipped.append(f"{path.name}: skipped: {reason}")
                continue
            try:
                component = _library_component(self, path, url)
            except _cnets.CnetsError as e:
                self.skipped.append(f"{path.name}: skipped: {_sentence(e)}")
                continue
            if component is None:
                continue  # a graph without an interface: not a component
            taken[key] = url
            self.components[url] = component

    # -- HTTP

    def __call__(self, environ: Dict[str, Any], start_response: Callable) -> Any:
        from werkzeug.exceptions import ClientDisconnected, HTTPException, RequestEntityTooLarge
        from werkzeug.wrappers import Request, Response

        request = Request(environ)
        request.max_content_length = self.max_body
        headers: Dict[str, str] = {}
        try:
            status, body = self.handle(request)
        except RequestEntityTooLarge:
            status, body = 413, self._too_large(request)
        except ClientDisconnected:
            status, body = 400, {"values": [], "errors": [
                "The request ended before its body was complete (the client disconnected)."]}
        except HTTPException as e:
            status, body = e.code or 400, {"values": [], "errors": [_sentence(
                f"the request could not be read ({e.description})")]}
        except HopsError as e:
            status, body = e.status, {"values": [], "errors": [_sentence(e)]}
            if e.retry_after is not None:
                headers["Retry-After"] = str(e.retry_after)
        except Exception as e:  # a bug: one sentence to Grasshopper, the traceback to the log
            _log.exception("internal error on %s %s", request.method, request.path)
            status, body = 500, {"values": [], "errors": [_sentence(
                f"internal error of the cnets Hops server ({type(e).__name__}: {e})")]}
        if status >= 400 and isinstance(body, (dict, _Answer)):
            errors = body.errors if isinstance(body, _Answer) else body.get("errors", [])
            _log.warning("%s %s: %d %s", request.method, request.path, status, "; ".join(errors))
        if isinstance(body, _Answer):
            data = body.data
        else:
            data = body.encode() if isinstance(body, str) else json.dumps(body).encode()
        response = Response(data, status=status, mimetype="application/json", headers=headers)
        return response(environ, start_response)

    def _too_large(self, request: Any) -> Dict[str, Any]:
        size = request.content_length
        what = f"the request body ({_cnets.format_bytes(size)})" if size else "the request body"
        return {"values": [], "errors": [_sentence(
            f"{what} is over this server's limit of {_cnets.format_bytes(self.max_body)}; send less "
            "data (fewer or coarser items) or start the server with a larger --max-body")]}

    def handle(self, request: Any) -> Tuple[int, Any]:
        """Answers one request: ``(status, JSON body)`` (a POST's body comes encoded, as an
        ``_Answer``)."""
        path = request.path  # already percent-decoded by the server ("/my tube")
        if request.method in ("GET", "HEAD"):
            if path == "/":
                return 200, [c.metadata() for c in self.components.values()]
            if path == "/solve":
                raise HopsError("/solve takes a POST with the inputs", 405)
            component = self.components.get(path)
            if component is None:
                raise HopsError(f"no component at {quote(path)}; GET / lists them", 404)
            return 200, component.metadata()
        if request.method != "POST":
            raise HopsError(f"{request.method} is not supported: GET a component, POST its inputs",
                            405)
        if request.content_length is not None and request.content_length > self.max_body:
            from werkzeug.exceptions import RequestEntityTooLarge

            raise RequestEntityTooLarge()
        raw = request.get_data(cache=False)
        if self._pool is None:
            status, errors, data = self.answer_post(path, raw)
        else:
            from ._hops_workers import PoolError

            try:
                status, errors, data = self._pool.run(path, raw)
            except PoolError as e:
                raise HopsError(str(e), e.status, e.retry_after) from None
        return status, _Answer(data, errors)

    def answer_post(self, path: str, raw: bytes) -> Tuple[int, List[str], bytes]:
        """Answers the body of a POST to ``path`` in this process (what a worker runs): the
        status, the errors and the JSON answer; never raises."""
        try:
            status, body = 200, self._post(path, raw)
        except HopsError as e:
            status, body = e.status, {"values": [], "errors": [_sentence(e)]}
        except Exception as e:  # a bug: one sentence to Grasshopper, the traceback to the log
            _log.exception("internal error on POST %s", path)
            status, body = 500, {"values": [], "errors": [_sentence(
                f"internal error of the cnets Hops server ({type(e).__name__}: {e})")]}
        return status, list(body.get("errors", [])), json.dumps(body).encode()

    def _post(self, path: str, raw: bytes) -> Dict[str, Any]:
        try:
            payload = _json_loads(raw)
        except JsonTooDeep:
            raise HopsError(f"the request body nests JSON arrays and objects more than "
                            f"{MAX_JSON_DEPTH} levels deep, which this server does not read (a "
                            "Hops request is 6 levels deep)") from None
        except ValueError as e:
            raise HopsError(f"the request body is not JSON ({e})") from None
        if not isinstance(payload, dict):
            raise HopsError("the request body must be a JSON object with \"values\"")
        if path == "/solve":
            pointer = payload.get("pointer")
            if not isinstance(pointer, str) or not pointer.strip():
                raise HopsError("a request to /solve must name its component in \"pointer\" "
                                "(for example \"/cnets_construct\")")
            target = unquote(urlsplit(pointer.strip()).path or "/")
            if not target.startswith("/"):
                target = "/" + target
            component = self.components.get(target)
            if component is None:
                raise HopsError(f"the pointer {pointer!r} names no component of this server; "
                                "GET / lists them", 404)
        else:
            component = self.components.get(path)
            if component is None:
                raise HopsError(f"no component at {quote(path)}; GET / lists them", 404)
        return self.solve(component, payload)

    def solve(self, component: Component, payload: Dict[str, Any]) -> Dict[str, Any]:
        """Decodes the inputs of a request, solves the component and encodes its outputs."""
        values = payload.get("values")
        if not isinstance(values, list):
            raise HopsError("the request has no \"values\" list of inputs")
        by_name: Dict[str, Any] = {}
        params = {p.name: p for p in component.inputs}
        for entry in values:
            name = entry.get("ParamName") if isinstance(entry, dict) else None
            if not isinstance(name, str):
                raise HopsError("every entry of \"values\" needs a \"ParamName\"")
            if name.startswith("RH_IN:"):
                name = name[len("RH_IN:"):]
            name = name if name in params else component.aliases.get(name, name)
            if name not in params:
                raise HopsError(f"{component.name} has no input {name!r} (its inputs: "
                                f"{', '.join(params)})")
            by_name[name] = read_input(params[name], entry, self.decode_geometry)
        inputs = {}
        for p in component.inputs:
            value = by_name.get(p.name)
            if value is None or (p.access != ITEM and not value):
                value = None
            inputs[p.name] = value
        outputs = component.solve(inputs)
        return {
            "values": [{"ParamName": p.name, "InnerTree": {"{0}": items}}
                       for p, items in zip(component.outputs, outputs)],
            "errors": [],
            "warnings": [],
        }


@dataclass
class _Answer:
    """A POST's JSON answer, already encoded (by a worker), and its errors (for the log)."""

    data: bytes
    errors: List[str]


def _unsafe_name(name: str) -> Optional[str]:
    """Why a file name cannot be a component's URL (``None`` when it can)."""
    if not name:
        return "its name is empty"
    if set(name) == {"."}:
        return f"its name {name!r} is made of dots only ('.' and '..' are not URL paths of their own)"
    if any(unicodedata.category(c).startswith("C") for c in name):
        return "its name contains control characters"
    if "/" in name or "\\" in name:
        return "its name contains a slash"
    if name != name.strip():
        return "its name starts or ends with a space"
    return None


def _broadcast(x: Any) -> Any:
    """A decoded Hops input (an item, a list, or a tree's branches) as the value of an engine
    port, broadcast as Grasshopper does: a tree of one branch is that branch's list, a list of
    one item is that item — one number given to a list or table port is that number, which the
    node repeats; a tree of several branches is a table (a list of lists). The built-in and the
    library components read their inputs through it alike."""
    if isinstance(x, list) and len(x) == 1:
        x = x[0]
        if isinstance(x, list) and len(x) == 1:  # a tree of one branch of one item
            x = x[0]
    return x


def _hops_name(port: str) -> str:
    """The name Hops shows for an engine port: its words Capitalised and joined, as the built-in
    components name theirs (``ratios`` is ``Ratios``, ``ruling_ratios`` ``RulingRatios``; a
    library graph's ``closure_gap`` is ``ClosureGap``)."""
    words = [w for w in port.replace("-", "_").replace(" ", "_").split("_") if w]
    return "".join(w[:1].upper() + w[1:] for w in words) or port


def _port(port: str, nickname: str, description: str, kind: str, access: str = ITEM,
          default: Any = None, optional: bool = False) -> Param:
    """The Hops parameter of an engine port, named by ``_hops_name`` (the built-in components'
    parameters and the library graphs' alike)."""
    return Param(_hops_name(port), nickname, description, kind, access, default, optional)


_DECLARED = object()


@functools.lru_cache(maxsize=1)
def _declared_ports() -> Dict[Tuple[str, str, str], Dict[str, Any]]:
    """Every node type's ports by (node id, "in" or "out", port name), as the nodes declare them."""
    ports: Dict[Tuple[str, str, str], Dict[str, Any]] = {}
    for node in _cnets.node_types():
        for side in ("inputs", "outputs"):
            for p in node[side]:
                ports[(node["id"], "in" if side == "inputs" else "out", p["name"])] = p
    return ports


def _node_port(node: str, port: str, nickname: str, kind: str, access: str = ITEM, *,
               output: bool = False, default: Any = _DECLARED, optional: bool = False,
               note: str = "") -> Param:
    """The Hops parameter of a node type's port, its description (and an input's default) read
    from the node's own declaration, so the built-in components say what the nodes say; ``note``
    adds what Hops does beside (NURBS curves are sampled), ``default`` overrides where Hops needs
    a value the node leaves empty."""
    declared = _declared_ports()[(node, "out" if output else "in", port)]
    doc = declared["doc"] + (f" {note[:1].upper()}{note[1:]}." if note else "")
    if default is _DECLARED:
        default = None if output else declared["default"]
    return _port(port, nickname, doc, kind, access, default, optional)


def _builtin_components(server: HopsServer) -> List[Component]:
    construct_outputs = [
        _node_port("cnets.construct", "mesh", "M", "Mesh", output=True),
        _node_port("cnets.construct", "apex", "A", "Number", LIST, output=True),
        _port("quality", "Q", "The largest planarity defect of a face (0: every face planar)",
              "Number"),
    ]

    def construction(node: str, title: str, extra: List[str]) -> Callable:
        def solve(inputs: Dict[str, Any]) -> List[List[Dict[str, str]]]:
            values = {
                "directrix": server.curve("Directrix", inputs["Directrix"]),
                "generatrix": server.curve("Generatrix", inputs["Generatrix"]),
                "apex": _broadcast(inputs["Apex"]),
                "assistance": inputs["Assistance"],
            }
            for port in extra:
                values[port] = _broadcast(inputs[_hops_name(port)])
            out = server.eval(node, values, outputs=["mesh", "apex", "quality"], title=title)
            return [
                write_output(construct_outputs[0], out["mesh"]),
                write_output(construct_outputs[1], out["apex"]),
                write_output(construct_outputs[2], out["quality"]["max_planarity"]),
            ]
        return solve

    curves_sampled = "any curve; NURBS curves are sampled"
    curve_in = [
        _node_port("cnets.construct", "directrix", "X", "Curve", note=curves_sampled),
        _node_port("cnets.construct", "generatrix", "G", "Curve", note=curves_sampled),
    ]
    components = [
        Component(
            "/cnets_construct", "CNets Construct", "CNets",
            "CNets Construct (paper Sec. 4.4.1): a cone-net swept from the generatrix along the "
            "directrix; ratios pick each plane's ruling; assistance repairs folded configurations.",
            "Cone-nets",
            curve_in + [
                _node_port("cnets.construct", "apex", "A", "Number", LIST),
                _node_port("cnets.construct", "ratios", "R", "Number", TREE),
                _node_port("cnets.construct", "assistance", "α", "Number"),
            ],
            construct_outputs,
            construction("cnets.construct", "CNets Construct", ["ratios"]),
        ),
        Component(
            "/cnets_construct_coplanar", "CNets Construct Coplanar", "CNetsCop",
            "CNets Construct Coplanar: one plane per directrix vertex, so every generatrix-aligned "
            "polyline is planar.",
            "Cone-nets",
            curve_in + [
                _node_port("cnets.construct_coplanar", "apex", "A", "Number", LIST),
                _node_port("cnets.construct_coplanar", "ruling_ratios", "ρ", "Number", LIST),
                _node_port("cnets.construct_coplanar", "plane_ratios", "τ", "Number", LIST),
                _node_port("cnets.construct_coplanar", "assistance", "α", "Number"),
            ],
            [_port("mesh", "M", "The cone-net; every column is planar", "Mesh"),
             construct_outputs[1], construct_outputs[2]],
            construction("cnets.construct_coplanar", "CNets Construct Coplanar",
                         ["ruling_ratios", "plane_ratios"]),
        ),
    ]

    apex_out = _node_port("cnets.graph_to_apex", "apex", "A", "Number", LIST, output=True)

    def graph_to_apex(inputs: Dict[str, Any]) -> List[List[Dict[str, str]]]:
        values: Dict[str, Any] = {"widths": inputs["Widths"] or [],
                                  "normalized": bool(inputs["Normalized"])}
        values["directrix"] = server.curve("Directrix", inputs["Directrix"], required=False)
        if inputs["Scale"]:
            values["scale"] = inputs["Scale"]
        out = server.eval("cnets.graph_to_apex", values, title="CNets Graph to Apex")
        return [write_output(apex_out, out["apex"])]

    components.append(Component(
        "/cnets_graph_to_apex", "CNets Graph to Apex", "G2A",
        "The widths y_j of the support strips give the apex function a_j = y_j / y_{j−1}.",
        "Cone-nets",
        [
            _node_port("cnets.graph_to_apex", "widths", "Y", "Number", LIST),
            _node_port("cnets.graph_to_apex", "normalized", "N", "Boolean"),
            _node_port("cnets.graph_to_apex", "directrix", "X", "Curve", optional=True,
                       note=curves_sampled),
            # Hops has no empty number: 0 stands for the node's empty scale.
            _node_port("cnets.graph_to_apex", "scale", "L", "Number", default=0.0,
                       note="in Hops, 0 stands for empty"),
        ],
        [apex_out],
        graph_to_apex,
    ))

    support_out = [
        _node_port("cnets.torsion_free_axes", "axes", "Ax", "Curve", LIST, output=True),
        # Named for what it is: cnets.conical_support's port is "mesh".
        Param("Support", "S", "The conical support layer", "Mesh"),
    ]

    def support(inputs: Dict[str, Any]) -> List[List[Dict[str, str]]]:
        d = server.curve("Directrix", inputs["Directrix"])
        if inputs["Mesh"] is None:
            raise HopsError("Mesh: no mesh given")
        grid = grid_from_rhino("Mesh", inputs["Mesh"])
        axes = server.eval("cnets.torsion_free_axes", {"directrix": d, "mesh": grid},
                           title="CNets Support")["axes"]
        values = {"directrix": d, "mesh": grid, "apex": inputs["Apex"] or [],
                  "factor": inputs["Factor"]}
        layer = server.eval("cnets.conical_support", values, title="CNets Support")["mesh"]
        return [write_output(support_out[0], axes), write_output(support_out[1], layer)]

    components.append(Component(
        "/cnets_support", "CNets Support", "Support",
        "The torsion-free node axes of a cone-net and a conical support layer (a second cone-net "
        "with the same apices, its first column scaled by Factor about X_0).",
        "Cone-nets",
        [
            _node_port("cnets.conical_support", "directrix", "X", "Curve", note=curves_sampled),
            _node_port("cnets.conical_support", "mesh", "M", "Mesh",
                       note="the Mesh output of CNets Construct"),
            _node_port("cnets.conical_support", "apex", "A", "Number", LIST,
                       note="the Apex output of CNets Construct"),
            _node_port("cnets.conical_support", "factor", "λ", "Number"),
        ],
        support_out,
        support,
    ))
    return components


# Engine port types → Hops parameter kinds.
_KINDS = {
    "number": "Number",
    "integer": "Integer",
    "boolean": "Boolean",
    "text": "Text",
    "point": "Point",
    "vector": "Vector",
    "polyline": "Curve",
    "quad_mesh": "Mesh",
    "mesh": "Mesh",
    "lines": "Curve",
}


def _port_param(port: Dict[str, Any], name: Optional[str] = None) -> Tuple[Param, str]:
    """A Hops parameter for a graph's port (named ``name``, else by ``_hops_name`` as the
    built-ins' are), and the port's base type."""
    ty: str = port["type"]
    access, base = ITEM, ty
    for prefix, a in (("list<", LIST), ("tree<", TREE), ("table<", TREE)):
        if ty.startswith(prefix) and ty.endswith(">"):
            access, base = a, ty[len(prefix):-1]
    if base == "lines":
        access = LIST
    kind = _KINDS.get(base, "Text")
    default = port.get("default")
    if not isinstance(default, (int, float, str, bool)):
        default = None
    name = name or _hops_name(port["name"])
    return Param(name, name, port.get("doc") or port["name"], kind, access, default,
                 bool(port.get("optional"))), base


def _hops_names(ports: List[Dict[str, Any]]) -> List[str]:
    """The Hops names of a graph's inputs or outputs: ``_hops_name`` of each, or the port's own
    name where two would come out the same (``a_b`` and ``aB``)."""
    names = [_hops_name(p["name"]) for p in ports]
    return [n if names.count(n) == 1 else p["name"] for n, p in zip(names, ports)]


def _to_cnets(value: Any, base: str, param: Param, server: HopsServer) -> Any:
    """A decoded Hops input as a cnets value for a port of base type ``base``."""
    if value is None:
        return None
    if isinstance(value, list):
        items = [_to_cnets(v, base, param, server) for v in value]
        if base == "lines":
            return np.asarray(items, dtype=np.float64).reshape(-1, 2, 3)
        return items
    if base == "lines":
        poly = curve_polyline(param.name, value, server.samples)
        return [poly.points[0].tolist(), poly.points[-1].tolist()]
    if param.kind == "Curve":
        return curve_polyline(param.name, value, server.samples)
    if param.kind == "Mesh":
        if base == "quad_mesh":
            return grid_from_rhino(param.name, value)
        from .rhino import mesh_from_rhino

        return mesh_from_rhino(value)
    return value


def _library_component(server: HopsServer, path: Path, url: str) -> Optional[Component]:
    """The component of a graph file with an interface (``None`` without one)."""
    node_type = f"cluster:{path}"
    try:
        interface = _cnets.node_interface(node_type, server.library or None)
    except _cnets.NoInterfaceError:
        return None
    ins = [_port_param(p, n) for p, n in zip(interface["inputs"],
                                              _hops_names(interface["inputs"]))]
    outs = [_port_param(p, n) for p, n in zip(interface["outputs"],
                                               _hops_names(interface["outputs"]))]
    title = path.name[: -len(".ron")]

    def solve(inputs: Dict[str, Any]) -> List[List[Dict[str, str]]]:
        values = {}
        for (param, base), port in zip(ins, interface["inputs"]):
            value = inputs[param.name]
            # A list of lines stays a list (an array of lines), one line included.
            v = _to_cnets(value if base == "lines" else _broadcast(value), base, param, server)
            if v is not None:
                values[port["name"]] = v
        out = server.eval(node_type, values, title=title)
        return [write_output(param, out.get(port["name"]))
                for (param, _), port in zip(outs, interface["outputs"])]

    doc = interface.get("doc") or f"The graph {path.name}"
    aliases = {port["name"]: param.name for (param, _), port in zip(ins, interface["inputs"])
               if port["name"] != param.name}
    return Component(url, title, title[:12], doc, "Library", [p for p, _ in ins],
                     [p for p, _ in outs], solve, aliases=aliases)


def create_app(library: Optional[str] = None, samples: int = 33,
               max_body: int = DEFAULT_MAX_BODY, max_memory: Any = None, *,
               workers: int = DEFAULT_WORKERS, queue: int = DEFAULT_QUEUE,
               timeout: float = DEFAULT_TIMEOUT,
               decode_geometry: Optional[Callable[[Dict[str, Any]], Any]] = None) -> HopsServer:
    """The Hops application with every cnets component (and the library's graphs): a WSGI
    application. Its POSTs are solved in ``workers`` worker processes, ``queue`` more waiting,
    ``timeout`` seconds each (see ``HopsServer``); ``close()`` it when done."""
    return HopsServer(library=library, samples=samples, max_body=max_body, max_memory=max_memory,
                      workers=workers, queue=queue, timeout=timeout,
                      decode_geometry=decode_geometry)


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{value} is negative")
    return value


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"{text} is not a positive number of seconds")
    return value


class _Stop(Exception):
    """SIGTERM: stop serving."""


def _size(text: str) -> int:
    try:
        return _cnets.parse_size(text)
    except _cnets.CnetsError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def main(argv: Optional[Sequence[str]] = None) -> None:
    """``python -m cnets.hops``: serves the components until interrupted."""
    parser = argparse.ArgumentParser(
        prog="python -m cnets.hops",
        description="Serve cnets to Grasshopper's Hops component.",
    )
    parser.add_argument("--port", type=int, default=5000, help="TCP port (default 5000)")
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1)")
    parser.add_argument("--library", help="a folder of graph files to serve as components")
    parser.add_argument("--samples", type=int, default=33,
                        help="points sampled on a curve that is not a polyline (default 33)")
    parser.add_argument("--max-body", type=_size, default=DEFAULT_MAX_BODY, metavar="SIZE",
                        help="largest request body (default 64MB); larger ones get HTTP 413")
    parser.add_argument("--max-memory", type=_size, default=None, metavar="SIZE",
                        help="memory budget of a solve (default: half the machine's memory)")
    parser.add_argument("--workers", type=_count, default=DEFAULT_WORKERS, metavar="N",
                        help="worker processes solving requests, one each at a time (default: "
                        f"the processor count up to 4, here {DEFAULT_WORKERS}; 0: solve in the "
                        "server process, without a time limit)")
    parser.add_argument("--queue", type=_count, default=DEFAULT_QUEUE, metavar="N",
                        help=f"requests that may wait for a free worker (default {DEFAULT_QUEUE}); "
                        "more are answered 503 with Retry-After")
    parser.add_argument("--timeout", type=_seconds, default=DEFAULT_TIMEOUT, metavar="SECONDS",
                        help=f"time limit of a solve (default {DEFAULT_TIMEOUT:g}): a slower one "
                        "is answered 503 and its worker killed; also the longest wait for a "
                        "free worker")
    args = parser.parse_args(argv)
    if args.library and not Path(args.library).is_dir():
        parser.error(f"--library {args.library}: not a folder")
    if args.samples < 2:
        parser.error("--samples must be at least 2")
    missing = _missing_dependency()
    if missing:
        print(f"python -m cnets.hops: {missing}", file=sys.stderr)
        sys.exit(2)
    from werkzeug.serving import WSGIRequestHandler, make_server

    class Handler(WSGIRequestHandler):
        timeout = 120  # seconds a silent client may hold its connection

        def log_request(self, code: Any = "-", size: Any = "-") -> None:
            pass  # no line per request: errors are logged by the application

    logging.basicConfig(level=logging.INFO, format="cnets.hops: %(message)s", stream=sys.stderr)
    logging.getLogger("werkzeug").setLevel(logging.ERROR)
    server = create_app(library=args.library, samples=args.samples, max_body=args.max_body,
                        max_memory=args.max_memory, workers=args.workers, queue=args.queue,
                        timeout=args.timeout)
    for line in server.skipped:
        _log.warning("%s", line)

    def stop(signum: int, frame: Any) -> None:
        raise _Stop()

    try:
        httpd = make_server(args.host, args.port, server, threaded=True, request_handler=Handler)
        # SIGTERM stops the server as Ctrl+C does: the workers are killed, the port closed, at
        # once (requests still running are dropped).
        signal.signal(signal.SIGTERM, stop)
        server.start()
        library = sum(1 for c in server.components.values() if c.subcategory == "Library")
        print(f"cnets.hops: serving {len(server.components)} components ({library} from the "
              f"library) on http://{args.host}:{httpd.server_port}/", flush=True)
        try:
            httpd.serve_forever()
        finally:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            server.close()
            httpd.server_close()
    except (KeyboardInterrupt, _Stop):
        pass
    finally:
        server.close()


def _missing_dependency() -> Optional[str]:
    """What the server needs and cannot import, said plainly (``None`` when all is there)."""
    for package in ("werkzeug", "rhino3dm"):
        try:
            __import__(package)
        except ImportError as e:
            missing = e.name or package
            via = "" if missing == package else f" (needed by {package})"
            return (f"the Hops server needs the Python package '{missing}'{via}, which is not "
                    f"installed: pip install \"cnets[hops]\" (or pip install {missing})")
    return None


if __name__ == "__main__":
    main()
