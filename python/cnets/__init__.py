"""cnets: design cone-nets — planar-quad meshes whose strips lie on discrete cones (CNets, AAG 2025)
— from Python. Every function runs the Rust node library through its registry, exactly as the
``cnets`` command line and the editor do; no geometry is computed in Python.

- ``construct``, ``ctube``, ``construct_coplanar``: build a ``ConeNet`` from a directrix and a
  generatrix (numpy (n, 3) arrays or ``Polyline``).
- ``encode``: any cone-net as C-tube construction inputs.
- ``eval(node_type, **inputs)``: any node type of ``cnets nodes``.
- ``Graph``: graph files, edited and evaluated incrementally.
- ``write_3dm`` / ``ConeNet.to_3dm``: Rhino files (``pip install cnets[rhino]``).
- ``ConeNet.to_compas()`` / ``from_compas(mesh)``: COMPAS meshes (``pip install cnets[compas]``).
- ``sweep``: a design-space sweep of a graph on Dask (``pip install cnets[sweep]``).
- ``python -m cnets.hops``: a Grasshopper Hops server.

Every bad input raises ``CnetsError`` (a ``ValueError``) naming the argument; a node's warning
(a value clamped to a slider's range…) is a ``CnetsWarning``.
"""

from __future__ import annotations

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _cnets
from ._cnets import CnetsError, CnetsWarning, Graph
from ._types import ConeNet, PolygonMesh, Polyline, QuadMesh, _describe, from_compas

__all__ = [
    "CnetsError",
    "CnetsWarning",
    "ConeNet",
    "Graph",
    "PolygonMesh",
    "Polyline",
    "QuadMesh",
    "construct",
    "construct_coplanar",
    "ctube",
    "encode",
    "eval",
    "from_compas",
    "node_types",
    "sweep",
    "write_3dm",
]

_Path = Union[str, "PathLike[str]"]
PolylineLike = Union[Polyline, npt.ArrayLike]
Numbers = Union[float, Sequence[float], npt.NDArray[np.float64]]
Table = Union[float, Sequence[float], Sequence[Sequence[float]], npt.NDArray[np.float64]]
EndPlanes = Literal["perpendicular", "mirror"]

_NODE_DOCS = {d["id"]: d for d in _cnets.node_types()}


def _doc(node_type: str, intro: str) -> str:
    """A docstring from the node's own documentation: its doc and its ports."""
    d = _NODE_DOCS[node_type]
    lines = [intro, "", d["doc"], "", "Parameters", "----------"]
    for p in d["inputs"]:
        default = "" if p["default"] is None else f" = {p['default']!r}"
        optional = ", optional" if p["optional"] else ""
        lines.append(f"{p['name']} : {p['type']}{optional}{default}")
        lines.append(f"    {p['doc']}")
    lines += ["", "Node outputs", "------------"]
    for p in d["outputs"]:
        lines.append(f"{p['name']} : {p['type']}")
        lines.append(f"    {p['doc']}")
    return "\n".join(lines)


def _inputs(**kwargs: Any) -> Dict[str, Any]:
    return {k: v for k, v in kwargs.items() if v is not None}


def _curve(x: Any, name: str) -> Any:
    """A curve argument: a ``Polyline`` (or anything with ``points`` and ``closed``) or an (n, 3)
    array-like. A numpy array is passed on as it is (the engine checks its size against the
    memory budget before copying it)."""
    if isinstance(x, Polyline) or (hasattr(x, "points") and hasattr(x, "closed")):
        return x
    if isinstance(x, np.ndarray):
        if x.dtype.kind not in "fiu" or x.ndim != 2 or x.shape[-1] != 3:
            raise CnetsError(f"{name}: expected an (n, 3) array of points or a cnets.Polyline, "
                             f"got {_describe(x)}")
        return x
    if isinstance(x, (str, bytes, dict, bool, int, float)) or x is None:
        raise CnetsError(f"{name}: expected an (n, 3) array of points or a cnets.Polyline, got "
                         f"{_describe(x)}")
    try:
        arr = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise CnetsError(f"{name}: expected an (n, 3) array of points or a cnets.Polyline, got "
                         f"{_describe(x)} ({e})") from None
    if arr.ndim != 2 or arr.shape[-1] != 3:
        raise CnetsError(f"{name}: expected an (n, 3) array of points or a cnets.Polyline, got "
                         f"shape {arr.shape}")
    return arr


def _is_number(x: Any) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def _number(x: Any, name: str, optional: bool = False) -> Optional[float]:
    """A number argument (an int or float; ``None`` when ``optional``)."""
    if x is None and optional:
        return None
    if isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "fiu":
        x = x.item()
    if not _is_number(x):
        expected = "a number or None" if optional else "a number"
        raise CnetsError(f"{name}: expected {expected}, got {_describe(x)}")
    return float(x)


def _flag(x: Any, name: str) -> bool:
    if not isinstance(x, (bool, np.bool_)):
        raise CnetsError(f"{name}: expected True or False, got {_describe(x)}")
    return bool(x)


def _choice(x: Any, name: str, choices: Sequence[str]) -> str:
    if not isinstance(x, str) or x not in choices:
        raise CnetsError(f"{name}: expected one of {', '.join(map(repr, choices))}, got "
                         f"{_describe(x)}")
    return x


def _numbers(x: Any, name: str, ndim: int, what: str) -> Any:
    """A number, or an array-like of numbers with at most ``ndim`` dimensions (``what`` says
    which shapes the node takes). A numpy array is passed on as it is (no copy: the engine checks
    its size against the memory budget first)."""
    if _is_number(x):
        return float(x)
    if isinstance(x, np.ndarray):
        if x.dtype.kind not in "fiu":
            raise CnetsError(f"{name}: expected {what}, got {_describe(x)}")
        if x.ndim > ndim:
            raise CnetsError(f"{name}: expected {what}, got an array of shape {x.shape}")
        return x if x.ndim else float(x)
    if not isinstance(x, (list, tuple)):
        raise CnetsError(f"{name}: expected {what}, got {_describe(x)}")
    try:
        arr = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise CnetsError(f"{name}: expected {what}, got {_describe(x)}") from None
    if arr.ndim > ndim or arr.size == 0:
        raise CnetsError(f"{name}: expected {what}, got {_describe(x)} (shape {arr.shape})")
    return arr


_END_PLANES = ("perpendicular", "mirror")
_APEX = "a number or a list of numbers (one per directrix edge)"


def _net(node_type: str, inputs: Dict[str, Any], directrix: Any, generatrix: Any) -> ConeNet:
    out = _cnets.eval(node_type, inputs, label_tables=True)
    return ConeNet._from_outputs(out, directrix=directrix, generatrix=generatrix)


def construct(
    directrix: PolylineLike,
    generatrix: PolylineLike,
    apex: Numbers = 1.0,
    ratios: Table = 0.5,
    assistance: float = -1.0,
    normalized: bool = False,
    scale: Optional[float] = None,
    epsilon: float = 0.01,
    end_planes: EndPlanes = "perpendicular",
) -> ConeNet:
    d = _curve(directrix, "directrix")
    g = _curve(generatrix, "generatrix")
    inputs = _inputs(
        directrix=d,
        generatrix=g,
        apex=_numbers(apex, "apex", 1, _APEX),
        ratios=_numbers(ratios, "ratios", 2, "a number, a list of M−1 numbers or an (N, M−1) table"),
        assistance=_number(assistance, "assistance"),
        normalized=_flag(normalized, "normalized"),
        scale=_number(scale, "scale", optional=True),
        epsilon=_number(epsilon, "epsilon"),
        end_planes=_choice(end_planes, "end_planes", _END_PLANES),
    )
    return _net("cnets.construct", inputs, d, g)


construct.__doc__ = _doc("cnets.construct", "CNets Construct: returns a ConeNet.")


_NORMALS = ("an (N, M−1, 3) array of plane normals (one list per row) or an (M−1, 3) array "
            "(one per directrix edge, shared by every row)")


def ctube(
    directrix: PolylineLike,
    generatrix: PolylineLike,
    apex: Numbers = 1.0,
    normals: Optional[npt.ArrayLike] = None,
    normalized: bool = False,
    scale: Optional[float] = None,
    end_planes: EndPlanes = "perpendicular",
) -> ConeNet:
    d = _curve(directrix, "directrix")
    g = _curve(generatrix, "generatrix")
    if normals is not None and isinstance(normals, np.ndarray) and normals.size == 0:
        normals = None
    if normals is not None and not isinstance(normals, np.ndarray):
        try:
            normals = np.asarray(normals, dtype=np.float64)
        except (TypeError, ValueError):
            raise CnetsError(f"normals: expected {_NORMALS}, got {_describe(normals)}") from None
    # (M−1, 3): one normal per directrix edge, shared by every row, as the node takes it.
    if normals is not None and (normals.dtype.kind not in "fiu" or normals.ndim not in (2, 3)
                                or normals.shape[-1] != 3):
        raise CnetsError(f"normals: expected {_NORMALS}, got {_describe(normals)}")
    inputs = _inputs(
        directrix=d,
        generatrix=g,
        apex=_numbers(apex, "apex", 1, _APEX),
        normals=normals,
        normalized=_flag(normalized, "normalized"),
        scale=_number(scale, "scale", optional=True),
        end_planes=_choice(end_planes, "end_planes", _END_PLANES),
    )
    return _net("ctube.construct", inputs, d, g)


ctube.__doc__ = _doc("ctube.construct", "The C-tube construction: returns a ConeNet.")


def construct_coplanar(
    directrix: PolylineLike,
    generatrix: PolylineLike,
    apex: Numbers = 1.0,
    ruling_ratios: Numbers = 0.5,
    plane_ratios: Numbers = 0.5,
    assistance: float = -1.0,
    normalized: bool = False,
    scale: Optional[float] = None,
    epsilon: float = 0.01,
    end_planes: EndPlanes = "perpendicular",
) -> ConeNet:
    d = _curve(directrix, "directrix")
    g = _curve(generatrix, "generatrix")
    per_column = "a number or a list of numbers (one per directrix edge)"
    inputs = _inputs(
        directrix=d,
        generatrix=g,
        apex=_numbers(apex, "apex", 1, _APEX),
        ruling_ratios=_numbers(ruling_ratios, "ruling_ratios", 1, per_column),
        plane_ratios=_numbers(plane_ratios, "plane_ratios", 1, per_column),
        assistance=_number(assistance, "assistance"),
        normalized=_flag(normalized, "normalized"),
        scale=_number(scale, "scale", optional=True),
        epsilon=_number(epsilon, "epsilon"),
        end_planes=_choice(end_planes, "end_planes", _END_PLANES),
    )
    return _net("cnets.construct_coplanar", inputs, d, g)


construct_coplanar.__doc__ = _doc(
    "cnets.construct_coplanar", "CNets Construct Coplanar: returns a ConeNet."
)


def encode(vertices: Union[npt.ArrayLike, QuadMesh]) -> Dict[str, Any]:
    if isinstance(vertices, QuadMesh):
        mesh = vertices
    elif isinstance(vertices, np.ndarray) and vertices.dtype.kind in "fiu":
        if vertices.ndim != 3 or vertices.shape[-1] != 3:
            raise CnetsError(f"vertices: expected an (N, M, 3) array, a QuadMesh or a ConeNet, got "
                             f"{_describe(vertices)}")
        # Passed on as it is: the engine checks its size before copying it.
        mesh = _VertexView(vertices)
    else:
        try:
            mesh = QuadMesh(vertices)
        except CnetsError as e:
            raise CnetsError(f"vertices: expected an (N, M, 3) array, a QuadMesh or a ConeNet ({e})") from None
    return _cnets.eval("cnets.encode", {"mesh": mesh})


class _VertexView:
    """An (N, M, 3) array handed to the engine as a quad mesh without a copy."""

    def __init__(self, vertices: np.ndarray) -> None:
        self.vertices = vertices


encode.__doc__ = _doc(
    "cnets.encode",
    "Encodes a cone-net ((N, M, 3) vertices, a QuadMesh or a ConeNet) as C-tube inputs: a dict "
    "with directrix, generatrix (Polyline), apex (M−1,) and normals (N, M−1, 3).",
)


def eval(
    node_type: str,
    *,
    _outputs: Optional[Sequence[str]] = None,
    _max_memory: Union[int, str, None] = None,
    _allow_read: Optional[Sequence[_Path]] = None,
    _library: Optional[Sequence[_Path]] = None,
    _out: Optional[_Path] = None,
    **inputs: Any,
) -> Dict[str, Any]:
    """Evaluates one node type (any id of ``cnets nodes``, or ``"cluster:<graph.ron>"``) on
    inputs given by name, and returns its outputs by name, as ``cnets eval`` does.

    Values: numbers, ``int``, ``bool``, ``str``; points as 3 numbers; polylines as (n, 3) arrays
    or ``Polyline``; quad meshes as (N, M, 3) arrays or ``QuadMesh``; lists and tables as lists
    or numpy arrays; records as dicts. Outputs come back as numpy arrays (numbers, points, and
    rectangular tables of them), ``Polyline``, ``QuadMesh``, ``PolygonMesh``, dicts, lists.
    Missing inputs take the node's defaults.

    Keyword options (prefixed with ``_`` so they never clash with an input name):
    ``_outputs`` computes only these outputs; ``_max_memory`` the memory budget (bytes or
    ``"2G"``); ``_allow_read`` further folders a node may read from (besides the working folder);
    ``_library`` folders of cluster graph files; ``_out`` the folder export nodes write into.
    A failed node raises ``CnetsError`` with the node's message.
    """
    return _cnets.eval(
        node_type,
        inputs,
        outputs=_outputs,
        max_memory=_max_memory,
        allow_read=_allow_read,
        library=_library,
        out=_out,
        option_prefix="_",
    )


def node_types() -> List[Dict[str, Any]]:
    """Every node type: dicts with ``id``, ``category``, ``doc``, ``inputs``, ``outputs``."""
    return _cnets.node_types()


def write_3dm(path: _Path, objects: Any, layers: bool = True, version: int = 8, *,
              axes_as: str = "family", colours: Optional[Dict[str, Any]] = None) -> None:
    """Writes cone-nets, meshes and polylines to a Rhino .3dm file, every coordinate in double
    precision (needs ``rhino3dm``: ``pip install cnets[rhino]``), on nested, coloured layers; line
    sets one object per family (``axes_as="lines"``: one per line). See ``cnets.rhino.write_3dm``."""
    from .rhino import write_3dm as _write

    _write(path, objects, layers=layers, version=version, axes_as=axes_as, colours=colours)


def sweep(
    graph: _Path,
    parameters: Union[Dict[str, Sequence[Any]], Sequence[Dict[str, Any]]],
    outputs: Sequence[str],
    client: Any = None,
    **kwargs: Any,
) -> Any:
    """Evaluates a graph file for every parameter set on Dask and returns a pandas DataFrame
    (needs ``dask[distributed]`` and ``pandas``). See ``cnets.sweeps.sweep``."""
    from .sweeps import sweep as _sweep

    return _sweep(graph, parameters, outputs, client=client, **kwargs)
