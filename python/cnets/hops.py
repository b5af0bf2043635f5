"""cnets in Grasshopper through McNeel's Hops component: ``python -m cnets.hops [--port 5000]
[--library DIR]`` serves the components below with ``ghhops-server``'s built-in HTTP server (no
other web framework). In Grasshopper: a Hops component, Path ``http://localhost:5000/cnets_construct``.

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
  at ``/<file name without .ron>``, with the graph's inputs and outputs.

Curves: a polyline curve gives its vertices; any other Rhino curve (NURBS, arc…) is sampled at
``--samples`` points (default 33). Errors of the engine come back to Grasshopper as the
component's error message.
"""

from __future__ import annotations

import argparse
import inspect
import json
import os
import sys
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence

import numpy as np

from . import _cnets
from ._types import PolygonMesh, Polyline, QuadMesh
from .rhino import curve_points, mesh_from_rhino, polygon_mesh_to_rhino, polyline_to_rhino, quad_mesh_to_rhino

__all__ = ["create_app", "main"]


def _hs():
    try:
        import ghhops_server
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("the Hops server needs ghhops-server: pip install cnets[hops]") from e
    return ghhops_server


def _param(cls: Any, name: str, nickname: str, desc: str, access: Any = None,
           default: Any = None, optional: bool = False) -> Any:
    """A Hops parameter that reads an empty or missing input as its default (Hops' own reader
    fails on an empty branch)."""
    hs = _hs()

    class Param(cls):  # type: ignore[misc, valid-type]
        def from_input(self, input_data):  # noqa: D401 - Hops API
            tree = input_data.get("InnerTree") or {}
            if not any(tree.values()):
                return None if self.access == hs.HopsParamAccess.ITEM else (
                    {} if self.access == hs.HopsParamAccess.TREE else [])
            return super().from_input(input_data)

    Param.__name__ = cls.__name__
    kwargs: Dict[str, Any] = {"access": access or hs.HopsParamAccess.ITEM, "optional": optional}
    if default is not None:
        kwargs["default"] = default
    return Param(name, nickname, desc, **kwargs)


def _numbers(x: Any) -> Any:
    """A Hops number input (item, list or tree) as a cnets number, list or table."""
    if x is None:
        return None
    if isinstance(x, dict):
        branches = [[float(v) for v in x[k]] for k in sorted(x, key=_path_key)]
        branches = [b for b in branches if b]
        if not branches:
            return None
        if len(branches) == 1:
            b = branches[0]
            return b[0] if len(b) == 1 else b
        return branches
    if isinstance(x, (list, tuple)):
        values = [float(v) for v in x]
        if not values:
            return None
        return values[0] if len(values) == 1 else values
    return float(x)


def _path_key(path: str) -> List[int]:
    return [int(p) for p in path.strip("{}").split(";") if p.strip().lstrip("-").isdigit()]


class _Server:
    """Builds the components on a ``ghhops_server.Hops`` app."""

    def __init__(self, samples: int = 33, library: Sequence[str] = ()) -> None:
        self.samples = samples
        self.library = [str(p) for p in library]

    def curve(self, c: Any, what: str) -> Polyline:
        if c is None:
            raise _cnets.CnetsError(f"{what}: no curve given")
        return curve_points(c, self.samples)

    def mesh_out(self, value: Any) -> Any:
        if isinstance(value, QuadMesh):
            return quad_mesh_to_rhino(value)
        if isinstance(value, PolygonMesh):
            return polygon_mesh_to_rhino(value)
        raise _cnets.CnetsError(f"not a mesh: {type(value).__name__}")

    def construct(self, node: str, inputs: Dict[str, Any]) -> tuple:
        out = _cnets.eval(node, {k: v for k, v in inputs.items() if v is not None})
        apex = [float(a) for a in np.asarray(out["apex"]).reshape(-1)]
        quality = float(out["quality"]["max_planarity"])
        return self.mesh_out(out["mesh"]), apex, quality


def create_app(library: Optional[str] = None, samples: int = 33) -> Any:
    """The Hops app with every cnets component (and the library's graphs)."""
    hs = _hs()
    hops = hs.Hops()
    server = _Server(samples=samples)
    LIST, TREE = hs.HopsParamAccess.LIST, hs.HopsParamAccess.TREE

    construct_outputs = [
        hs.HopsMesh("Mesh", "M", "The cone-net: a quad mesh, N rows (generatrix points) × M columns"),
        hs.HopsNumber("Apex", "A", "The apex values a_j used (M−1), after normalization and correction",
                      access=LIST),
        hs.HopsNumber("Quality", "Q", "The largest planarity defect of a face (0: every face planar)"),
    ]

    @hops.component(
        "/cnets_construct",
        name="CNets Construct",
        nickname="CNets",
        description="CNets Construct (paper Sec. 4.4.1): a cone-net swept from the generatrix along "
        "the directrix; ratios pick each plane's ruling; assistance repairs folded configurations.",
        category="cnets",
        subcategory="Cone-nets",
        inputs=[
            _param(hs.HopsCurve, "Directrix", "X", "Directrix X (any curve; NURBS curves are sampled)"),
            _param(hs.HopsCurve, "Generatrix", "G", "Generatrix G (closed: the mesh wraps)"),
            _param(hs.HopsNumber, "Apex", "A", "Apex function a_j: one number or one per directrix edge",
                   access=LIST, default=1.0),
            _param(hs.HopsNumber, "Ratios", "R", "Ratios r_ij: one number, a list of M−1, or a tree of "
                   "N branches of M−1", access=TREE, default=0.5),
            _param(hs.HopsNumber, "Assistance", "α", "Assisted correction: negative off, 0 planes, 1 apex",
                   default=-1.0),
        ],
        outputs=construct_outputs,
    )
    def cnets_construct(directrix, generatrix, apex, ratios, assistance):
        return server.construct("cnets.construct", {
            "directrix": server.curve(directrix, "Directrix"),
            "generatrix": server.curve(generatrix, "Generatrix"),
            "apex": _numbers(apex),
            "ratios": _numbers(ratios),
            "assistance": _numbers(assistance),
        })

    @hops.component(
        "/cnets_construct_coplanar",
        name="CNets Construct Coplanar",
        nickname="CNetsCop",
        description="CNets Construct Coplanar: one plane per directrix vertex, so every "
        "generatrix-aligned polyline is planar.",
        category="cnets",
        subcategory="Cone-nets",
        inputs=[
            _param(hs.HopsCurve, "Directrix", "X", "Directrix X (any curve; NURBS curves are sampled)"),
            _param(hs.HopsCurve, "Generatrix", "G", "Generatrix G (closed: the mesh wraps)"),
            _param(hs.HopsNumber, "Apex", "A", "Apex function a_j", access=LIST, default=1.0),
            _param(hs.HopsNumber, "RulingRatios", "ρ", "Ruling ratios ρ_j", access=LIST, default=0.5),
            _param(hs.HopsNumber, "PlaneRatios", "τ", "Plane-rotation ratios τ_j", access=LIST, default=0.5),
            _param(hs.HopsNumber, "Assistance", "α", "Assisted correction", default=-1.0),
        ],
        outputs=[
            hs.HopsMesh("Mesh", "M", "The cone-net; every column is planar"),
            hs.HopsNumber("Apex", "A", "The apex values used (M−1)", access=LIST),
            hs.HopsNumber("Quality", "Q", "The largest planarity defect of a face"),
        ],
    )
    def cnets_construct_coplanar(directrix, generatrix, apex, ruling_ratios, plane_ratios, assistance):
        return server.construct("cnets.construct_coplanar", {
            "directrix": server.curve(directrix, "Directrix"),
            "generatrix": server.curve(generatrix, "Generatrix"),
            "apex": _numbers(apex),
            "ruling_ratios": _numbers(ruling_ratios),
            "plane_ratios": _numbers(plane_ratios),
            "assistance": _numbers(assistance),
        })

    @hops.component(
        "/cnets_graph_to_apex",
        name="CNets Graph to Apex",
        nickname="G2A",
        description="The widths y_j of the support strips give the apex function a_j = y_j / y_{j−1}.",
        category="cnets",
        subcategory="Cone-nets",
        inputs=[
            _param(hs.HopsNumber, "Widths", "Y", "Widths y_0 … y_{M−1} (> 0), one per directrix point",
                   access=LIST),
            _param(hs.HopsBoolean, "Normalized", "N", "Output the normalized apex function", default=False),
            _param(hs.HopsCurve, "Directrix", "X", "The directrix (needed when normalized)", optional=True),
            _param(hs.HopsNumber, "Scale", "L", "Normalization scale L (0: directrix length / 5)",
                   default=0.0),
        ],
        outputs=[hs.HopsNumber("Apex", "A", "The apex values (M−1)", access=LIST)],
    )
    def cnets_graph_to_apex(widths, normalized, directrix, scale):
        inputs: Dict[str, Any] = {"widths": [float(w) for w in (widths or [])],
                                  "normalized": bool(normalized)}
        if directrix is not None:
            inputs["directrix"] = server.curve(directrix, "Directrix")
        if scale:
            inputs["scale"] = float(scale)
        out = _cnets.eval("cnets.graph_to_apex", inputs)
        return [float(a) for a in np.asarray(out["apex"]).reshape(-1)]

    @hops.component(
        "/cnets_support",
        name="CNets Support",
        nickname="Support",
        description="The torsion-free node axes of a cone-net and a conical support layer (a second "
        "cone-net with the same apices, its first column scaled by Factor about X_0).",
        category="cnets",
        subcategory="Cone-nets",
        inputs=[
            _param(hs.HopsCurve, "Directrix", "X", "The directrix the mesh was built from"),
            _param(hs.HopsMesh, "Mesh", "M", "The cone-net (the Mesh output of CNets Construct)"),
            _param(hs.HopsNumber, "Apex", "A", "The Apex output of CNets Construct", access=LIST),
            _param(hs.HopsNumber, "Factor", "λ", "Scale of the support's first column about X_0",
                   default=0.8),
        ],
        outputs=[
            hs.HopsCurve("Axes", "Ax", "The node axes X_j → G_ij, one line per vertex", access=LIST),
            hs.HopsMesh("Support", "S", "The conical support layer"),
        ],
    )
    def cnets_support(directrix, mesh, apex, factor):
        d = server.curve(directrix, "Directrix")
        grid = _grid_from_rhino(mesh, d)
        axes = _cnets.eval("cnets.torsion_free_axes", {"directrix": d, "mesh": grid})["axes"]
        inputs = {"directrix": d, "mesh": grid, "apex": [float(a) for a in (apex or [])]}
        if factor is not None:
            inputs["factor"] = float(factor)
        support = _cnets.eval("cnets.conical_support", inputs)["mesh"]
        return [_line_curve(a, b) for a, b in np.asarray(axes).tolist()], server.mesh_out(support)

    if library:
        for path in sorted(Path(library).glob("*.ron")):
            _register_graph(hops, server, path, [library])
    return hops


def _line_curve(a: Sequence[float], b: Sequence[float]) -> Any:
    import rhino3dm

    return rhino3dm.LineCurve(rhino3dm.Point3d(*a), rhino3dm.Point3d(*b))


def _grid_from_rhino(mesh: Any, directrix: Polyline) -> QuadMesh:
    """The quad grid of a Rhino mesh written by ``/cnets_construct``: row-major vertices, as many
    columns as the swept directrix has points."""
    if mesh is None:
        raise _cnets.CnetsError("Mesh: no mesh given")
    poly = mesh_from_rhino(mesh)
    cols = len(directrix.points) + (1 if directrix.closed else 0)
    count = len(poly.vertices)
    if cols == 0 or count % cols:
        raise _cnets.CnetsError(
            f"Mesh: {count} vertices are not rows of {cols} (the directrix's points): use the "
            "mesh of CNets Construct built on this directrix"
        )
    rows = count // cols
    wrap_rows = len(poly.faces) == rows * (cols - 1) and rows > 2
    return QuadMesh(poly.vertices.reshape(rows, cols, 3), wrap_rows=wrap_rows)


_HOPS_TYPES = {
    "number": "HopsNumber",
    "integer": "HopsInteger",
    "boolean": "HopsBoolean",
    "text": "HopsString",
    "point": "HopsPoint",
    "vector": "HopsVector",
    "polyline": "HopsCurve",
    "quad_mesh": "HopsMesh",
    "mesh": "HopsMesh",
    "lines": "HopsCurve",
}


def _port_param(hs: Any, port: Dict[str, Any], output: bool) -> Any:
    ty: str = port["type"]
    access = hs.HopsParamAccess.ITEM
    base = ty
    if ty.startswith("list<"):
        access, base = hs.HopsParamAccess.LIST, ty[5:-1]
    elif ty.startswith("tree<"):
        access, base = hs.HopsParamAccess.TREE, ty[5:-1]
    cls = getattr(hs, _HOPS_TYPES.get(base, "HopsString"))
    if base == "lines":
        access = hs.HopsParamAccess.LIST
    name = port["name"]
    doc = port.get("doc") or name
    if output:
        return cls(name, name, doc, access=access)
    default = port.get("default")
    default = default if isinstance(default, (int, float, str, bool)) else None
    return _param(cls, name, name, doc, access=access, default=default,
                  optional=bool(port.get("optional")))


def _from_rhino(value: Any, ty: str, server: _Server) -> Any:
    """A Hops input value as a cnets value for a port of type ``ty``."""
    if value is None:
        return None
    if isinstance(value, dict):  # a tree
        return [_from_rhino(v, ty, server) for k in sorted(value, key=_path_key) for v in [value[k]]]
    if isinstance(value, list):
        return [_from_rhino(v, ty, server) for v in value]
    name = type(value).__name__
    if hasattr(value, "X") and hasattr(value, "Y") and hasattr(value, "Z"):
        return [value.X, value.Y, value.Z]
    if "Curve" in name:
        return server.curve(value, "curve")
    if name == "Mesh":
        return mesh_from_rhino(value)
    return value


def _to_rhino(value: Any, ty: str, server: _Server) -> Any:
    """A cnets output value as what Hops encodes for a port of type ``ty``."""
    import rhino3dm

    base = ty[5:-1] if ty.startswith(("list<", "tree<")) else ty
    if isinstance(value, (QuadMesh, PolygonMesh)):
        return server.mesh_out(value)
    if isinstance(value, Polyline):
        return polyline_to_rhino(value)
    if isinstance(value, np.ndarray):
        if base == "lines" and value.ndim == 3:
            return [_line_curve(a, b) for a, b in value.tolist()]
        if base in ("point", "vector") and value.shape[-1:] == (3,):
            cls = rhino3dm.Point3d if base == "point" else rhino3dm.Vector3d
            if value.ndim == 1:
                return cls(*value.tolist())
            return [cls(*p) for p in value.reshape(-1, 3).tolist()]
        return value.reshape(-1).tolist() if value.ndim else value.item()
    if isinstance(value, list):
        flat: List[Any] = []
        for v in value:
            r = _to_rhino(v, base, server)
            flat.extend(r if isinstance(r, list) else [r])
        return flat
    if isinstance(value, dict):
        return json.dumps({k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in value.items()})
    return value


def _register_graph(hops: Any, server: _Server, path: Path, library: List[str]) -> None:
    """One component for a graph file with an interface; files without one are skipped."""
    hs = _hs()
    node_type = f"cluster:{path}"
    try:
        interface = _cnets.node_interface(node_type, library)
    except _cnets.CnetsError as e:
        print(f"cnets.hops: skipped {path.name}: {e}", file=sys.stderr)
        return
    ins, outs = interface["inputs"], interface["outputs"]

    def handler(*args):
        inputs = {}
        for port, value in zip(ins, args):
            v = _from_rhino(value, port["type"], server)
            if v is not None:
                inputs[port["name"]] = v
        out = _cnets.eval(node_type, inputs, library=library)
        results = tuple(_to_rhino(out.get(p["name"]), p["type"], server) for p in outs)
        return results if len(results) != 1 else results[0]

    handler.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        [inspect.Parameter(f"p{k}", inspect.Parameter.POSITIONAL_OR_KEYWORD) for k in range(len(ins))]
    )
    handler.__doc__ = interface["doc"]
    hops.component(
        f"/{path.stem}",
        name=interface.get("name") or path.stem,
        nickname=path.stem,
        description=interface["doc"] or f"The graph {path.name}",
        category="cnets",
        subcategory="Library",
        inputs=[_port_param(hs, p, False) for p in ins],
        outputs=[_port_param(hs, p, True) for p in outs],
    )(handler)


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
    args = parser.parse_args(argv)
    if args.library and not os.path.isdir(args.library):
        parser.error(f"--library {args.library}: not a folder")
    app = create_app(library=args.library, samples=args.samples)
    print(f"cnets.hops: serving on http://{args.host}:{args.port}/", flush=True)
    app.start(address=args.host, port=args.port)


if __name__ == "__main__":
    main()
