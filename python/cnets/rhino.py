"""Rhino files (.3dm) through McNeel's official ``rhino3dm`` package (``pip install cnets[rhino]``),
and conversions between Rhino geometry and cnets values (used by the Hops server).

- ``write_3dm(path, objects, layers=True, *, axes_as="family", colours=None)``: cone-nets, quad
  meshes, polygon meshes, polylines and line sets, each on its own named layer: a cone-net written
  under a name gets a parent layer of that name and its parts on sublayers (``Facade::Cone-net``,
  Rhino's nested layers), every layer with its colour.
- ``ConeNet.to_3dm(path, layers=True)``: the net as a quad mesh on layer ``Cone-net``, the directrix
  and generatrix as polylines on ``Directrix`` / ``Generatrix``, the torsion-free node axes on
  ``Axes`` and a conical support layer on ``Support`` (both computed by the node library:
  ``cnets.torsion_free_axes``, ``cnets.conical_support``; left out, with a warning, where they are
  undefined: a generatrix point on the directrix).

Line sets ((K, 2, 3) arrays: node axes, beams) are written one object per family, not one per
line: segments that follow each other (each starting where the one before ends) are one
``PolylineCurve``; segments that do not connect (the torsion-free axes: one per vertex, each from
its directrix point) are grouped — one Rhino group per family, named after its layer path, so that
a click selects the family — because Rhino has no valid single curve for disjoint segments (a
``PolyCurve`` with gaps fails ``IsValid``: "Polycurve end of segment[0] != start of segment[1]",
and ``PolyCurve.Append`` moves each segment's start onto the previous end, changing the geometry).
``axes_as="lines"`` writes one ungrouped line object per segment, as before.

Every coordinate is written in double precision — mesh vertices too (``cnets._opennurbs`` builds
the mesh from the arrays in bulk, with Rhino's double-precision vertex list), so a file read back
gives the very numbers cnets computed, far from the origin as well.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple, Union

import warnings

import numpy as np

from . import _cnets
from ._opennurbs import encode_mesh
from ._types import ConeNet, PolygonMesh, Polyline, QuadMesh, _describe

__all__ = [
    "AXES_AS",
    "KIND_COLOURS",
    "LAYER_COLOURS",
    "curve_points",
    "mesh_from_rhino",
    "quad_mesh_to_rhino",
    "polyline_to_rhino",
    "write_3dm",
    "write_cone_net",
]

#: Layer colours (RGBA) by layer name (the last part of a nested layer's path); a layer named
#: otherwise gets the colour of what it holds (``KIND_COLOURS``), a cone-net's parent layer the
#: colour of its ``Cone-net`` sublayer. ``write_3dm(colours=…)`` overrides any of them.
LAYER_COLOURS: Dict[str, Tuple[int, int, int, int]] = {
    "Cone-net": (40, 110, 200, 255),
    "Directrix": (220, 60, 40, 255),
    "Generatrix": (40, 160, 70, 255),
    "Axes": (120, 120, 120, 255),
    "Support": (200, 140, 30, 255),
}

#: Colours of layers named otherwise, by what they hold: meshes, curves (polylines), line sets.
KIND_COLOURS: Dict[str, Tuple[int, int, int, int]] = {
    "mesh": (40, 110, 200, 255),
    "curve": (220, 60, 40, 255),
    "lines": (120, 120, 120, 255),
}

#: How ``write_3dm`` writes line sets: ``"family"`` one object per family (a connected family as
#: one ``PolylineCurve``, a disconnected one as one group of lines), ``"lines"`` one ungrouped line
#: object per segment (the files before nested layers).
AXES_AS = ("family", "lines")

#: Rhino's separator of nested layer names (``Layer.PathSeparator``).
SEPARATOR = "::"


def _rhino3dm():
    try:
        import rhino3dm
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "cnets' Rhino files need the rhino3dm package: pip install cnets[rhino]"
        ) from e
    return rhino3dm


def quad_mesh_to_rhino(mesh: QuadMesh) -> Any:
    """A ``rhino3dm.Mesh`` of quads from a quad mesh: double-precision vertices (row-major,
    vertex ``i * M + j``), built in bulk."""
    r = _rhino3dm()
    return r.CommonObject.Decode(encode_mesh(mesh.vertices.reshape(-1, 3), mesh.faces()))


def polygon_mesh_to_rhino(mesh: PolygonMesh) -> Any:
    """A ``rhino3dm.Mesh`` from a polygon mesh (triangles and quads; larger faces are fanned into
    triangles), with double-precision vertices."""
    r = _rhino3dm()
    faces: List[Tuple[int, int, int, int]] = []
    for f in mesh.faces:
        if len(f) == 4:
            faces.append((f[0], f[1], f[2], f[3]))
        else:
            faces.extend((f[0], f[k], f[k + 1], f[k + 1]) for k in range(1, len(f) - 1))
    return r.CommonObject.Decode(
        encode_mesh(np.asarray(mesh.vertices, dtype=np.float64), np.asarray(faces, dtype=np.int64))
    )


def _points(points: np.ndarray, closed: bool) -> List[Any]:
    r = _rhino3dm()
    pts = [r.Point3d(x, y, z) for x, y, z in np.asarray(points, dtype=np.float64).tolist()]
    if closed and pts:
        pts.append(pts[0])
    return pts


def polyline_to_rhino(polyline: Union[Polyline, np.ndarray]) -> Any:
    """A ``rhino3dm.PolylineCurve`` from a polyline (closed: the first point repeated)."""
    r = _rhino3dm()
    if isinstance(polyline, Polyline):
        return r.PolylineCurve(_points(polyline.points, polyline.closed))
    return r.PolylineCurve(_points(np.asarray(polyline), False))


def curve_points(curve: Any, samples: int = 33) -> Polyline:
    """The points of any Rhino curve as a ``Polyline``: a polyline curve gives its vertices; any
    other curve (NURBS, arc, line…) is sampled at ``samples`` parameters evenly spaced over its
    domain. A closed curve gives a closed polyline (the seam point once). Anything but a
    ``rhino3dm.Curve`` raises ``CnetsError``."""
    r = _rhino3dm()
    if not isinstance(curve, r.Curve):
        raise _cnets.CnetsError(f"expected a curve, got {_describe(curve)}")
    closed = bool(curve.IsClosed)
    pts: List[Tuple[float, float, float]] = []
    if isinstance(curve, r.PolylineCurve):
        pts = [(p.X, p.Y, p.Z) for p in (curve.Point(k) for k in range(curve.PointCount))]
    elif isinstance(curve, r.LineCurve):
        a, b = curve.PointAtStart, curve.PointAtEnd
        pts = [(a.X, a.Y, a.Z), (b.X, b.Y, b.Z)]
    else:
        domain = curve.Domain
        n = max(2, int(samples))
        for t in np.linspace(domain.T0, domain.T1, n):
            p = curve.PointAt(float(t))
            pts.append((p.X, p.Y, p.Z))
    arr = np.asarray(pts, dtype=np.float64).reshape(-1, 3)
    if closed and len(arr) > 1 and np.allclose(arr[0], arr[-1], rtol=0.0,
                                               atol=1e-12 * (1 + np.abs(arr).max())):
        arr = arr[:-1]
    return Polyline(arr, closed=closed)


def mesh_from_rhino(mesh: Any) -> PolygonMesh:
    """A polygon mesh from a ``rhino3dm.Mesh``, with its vertices at full precision (the
    double-precision vertex list when the mesh has one)."""
    r = _rhino3dm()
    if not isinstance(mesh, r.Mesh):
        raise _cnets.CnetsError(f"expected a mesh, got {_describe(mesh)}")
    vertices = np.asarray([(p.X, p.Y, p.Z) for p in mesh.Vertices.ToPoint3dArray()],
                          dtype=np.float64).reshape(-1, 3)
    faces = []
    for k in range(mesh.Faces.Count):
        f = mesh.Faces[k]
        faces.append(list(f[:3]) if f[2] == f[3] else list(f))
    return PolygonMesh(vertices, faces)


class _Writer:
    """One file being written: its nested layers (created on first use, parents first) and its
    groups, by full layer path."""

    def __init__(self, model: Any, layers: bool, axes_as: str,
                 colours: Dict[str, Tuple[int, int, int, int]]) -> None:
        self.model = model
        self.layers = layers
        self.axes_as = axes_as
        self.colours = colours
        self.indices: Dict[str, int] = {}
        self.groups: Dict[str, int] = {}

    def colour(self, path: str, kind: str) -> Tuple[int, int, int, int]:
        leaf = path.split(SEPARATOR)[-1]
        for key in (path, leaf):
            if key in self.colours:
                return self.colours[key]
        if leaf in LAYER_COLOURS:
            return LAYER_COLOURS[leaf]
        return KIND_COLOURS.get(kind, (128, 128, 128, 255))

    def layer(self, path: str, kind: str) -> Optional[int]:
        """The index of the layer at ``path`` (``"Parent::Child"``), creating it and its parents
        with their colours (a parent's colour from ``kind`` too: what its children hold)."""
        if not self.layers:
            return None
        if path in self.indices:
            return self.indices[path]
        r = _rhino3dm()
        parts = path.split(SEPARATOR)
        parent_id = None
        for k in range(len(parts)):
            sub = SEPARATOR.join(parts[:k + 1])
            if sub not in self.indices:
                layer = r.Layer()
                layer.Name = parts[k]
                layer.Color = self.colour(sub, kind)
                if parent_id is not None:
                    layer.ParentLayerId = parent_id
                self.indices[sub] = self.model.Layers.Add(layer)
            parent_id = self.model.Layers[self.indices[sub]].Id
        return self.indices[path]

    def group(self, path: str) -> int:
        """The index of the group named ``path`` (one per family), created on first use."""
        if path not in self.groups:
            r = _rhino3dm()
            group = r.Group()
            group.Name = path
            self.model.Groups.Add(group)
            self.groups[path] = len(self.model.Groups) - 1
        return self.groups[path]


def _check_layer_name(name: str, where: str) -> None:
    parts = name.split(SEPARATOR)
    if any(not p.strip() for p in parts):
        raise _cnets.CnetsError(
            f"{where}: layer name {name!r} has an empty part: nested layers are written "
            f"\"Parent{SEPARATOR}Child\"")


def _attributes(layer: Optional[int], name: Optional[str]) -> Any:
    r = _rhino3dm()
    attr = r.ObjectAttributes()
    if layer is not None:
        attr.LayerIndex = layer
    if name:
        attr.Name = name
    return attr


def _item_kind(item: Any) -> str:
    """``"mesh"``, ``"curve"`` or ``"lines"``: what an item is written as (its layer's colour)."""
    if isinstance(item, (QuadMesh, PolygonMesh)):
        return "mesh"
    if isinstance(item, Polyline):
        return "curve"
    arr = np.asarray(item)
    if arr.ndim == 3 and arr.shape[1:] == (2, 3):
        return "lines"
    return "curve" if arr.ndim == 2 else "mesh"


def _connected(lines: np.ndarray) -> bool:
    """Whether every segment starts exactly where the one before ends (one polyline)."""
    return len(lines) > 0 and bool(np.array_equal(lines[1:, 0], lines[:-1, 1]))


def _add_lines(w: _Writer, lines: np.ndarray, attr: Any, family: Optional[str]) -> None:
    """A (K, 2, 3) line set: one ``PolylineCurve`` when its segments follow each other, else one
    line object per segment, grouped as one family (``axes_as="family"``), or loose
    (``"lines"``)."""
    r = _rhino3dm()
    model = w.model
    if w.axes_as == "family" and _connected(lines):
        points = np.concatenate([lines[:, 0], lines[-1:, 1]])
        model.Objects.AddCurve(
            r.PolylineCurve([r.Point3d(x, y, z) for x, y, z in points.tolist()]), attr)
        return
    if w.axes_as == "family" and len(lines) > 1 and not attr.GroupCount:
        attr.AddToGroup(w.group(family or "Lines"))
    add, point = model.Objects.AddLine, r.Point3d
    for (a, b) in lines.tolist():
        add(point(*a), point(*b), attr)


def _add(w: _Writer, item: Any, layer: Optional[int], name: Optional[str], where: str,
         family: Optional[str] = None, group: Optional[int] = None) -> None:
    model = w.model
    attr = _attributes(layer, name)
    if group is not None:
        attr.AddToGroup(group)
    if isinstance(item, QuadMesh):
        model.Objects.AddMesh(quad_mesh_to_rhino(item), attr)
    elif isinstance(item, PolygonMesh):
        model.Objects.AddMesh(polygon_mesh_to_rhino(item), attr)
    elif isinstance(item, Polyline):
        model.Objects.AddCurve(polyline_to_rhino(item), attr)
    else:
        arr = _geometry_array(item, where)
        if arr.ndim == 3 and arr.shape[1:] == (2, 3):
            _add_lines(w, arr, attr, family)
        elif arr.ndim == 2 and arr.shape[1] == 3:
            model.Objects.AddCurve(polyline_to_rhino(arr), attr)
        elif arr.ndim == 3 and arr.shape[2] == 3:
            model.Objects.AddMesh(quad_mesh_to_rhino(QuadMesh(arr)), attr)
        else:
            raise _cnets.CnetsError(
                f"{where}: cannot write an array of shape {arr.shape}: expected (n, 3) points, "
                "(K, 2, 3) lines or (N, M, 3) quad-mesh vertices"
            )


_WRITABLE = ("a ConeNet, QuadMesh, PolygonMesh or Polyline, or an array of (n, 3) points, (K, 2, 3) "
             "lines or (N, M, 3) quad-mesh vertices")


def _geometry_array(item: Any, where: str) -> np.ndarray:
    if isinstance(item, (str, bytes, dict)) or item is None or isinstance(item, (bool, int, float)):
        raise _cnets.CnetsError(f"{where}: cannot write {_describe(item)}: expected {_WRITABLE}")
    try:
        return np.asarray(item, dtype=np.float64)
    except (TypeError, ValueError):
        raise _cnets.CnetsError(
            f"{where}: cannot write {_describe(item)}: expected {_WRITABLE}") from None


def cone_net_layers(net: ConeNet, support: Optional[float] = 0.8, axes: bool = True) -> Dict[str, Any]:
    """What ``ConeNet.to_3dm`` writes, by layer name: ``Cone-net`` (the mesh), ``Directrix`` and
    ``Generatrix`` (polylines, when the net knows them), ``Axes`` (the torsion-free node axes,
    (K, 2, 3)) and ``Support`` (a conical support layer scaled by ``support`` about X_0)."""
    layers: Dict[str, Any] = {"Cone-net": QuadMesh(net.vertices, net.wrap_rows, net.wrap_cols)}
    if net.directrix is not None:
        layers["Directrix"] = _as_polyline(net.directrix)
    if net.generatrix is not None:
        layers["Generatrix"] = _as_polyline(net.generatrix)
    # The axes and the support layer are undefined where a generatrix point lies on the directrix
    # (G_00 = X_0, the usual start): those layers are then left out with a warning.
    if net.directrix is not None and axes:
        try:
            layers["Axes"] = _cnets.eval(
                "cnets.torsion_free_axes", {"directrix": net.directrix, "mesh": net}
            )["axes"]
        except _cnets.CnetsError as e:
            warnings.warn(f"to_3dm: no Axes layer: {e}", _cnets.CnetsWarning)
    if net.directrix is not None and support is not None:
        try:
            layers["Support"] = _cnets.eval(
                "cnets.conical_support",
                {"directrix": net.directrix, "mesh": net, "apex": net.apex, "factor": support},
            )["mesh"]
        except _cnets.CnetsError as e:
            warnings.warn(f"to_3dm: no Support layer: {e}", _cnets.CnetsWarning)
    return layers


def _as_polyline(x: Any) -> Polyline:
    if isinstance(x, Polyline):
        return x
    if hasattr(x, "points") and hasattr(x, "closed"):
        return Polyline(x.points, x.closed)
    return Polyline(np.asarray(x, dtype=np.float64), closed=False)


def _check_axes_as(axes_as: Any) -> str:
    if not isinstance(axes_as, str) or axes_as not in AXES_AS:
        raise _cnets.CnetsError(f"axes_as: expected one of {', '.join(map(repr, AXES_AS))}, got "
                                f"{_describe(axes_as)}")
    return axes_as


def _check_colours(colours: Any) -> Dict[str, Tuple[int, int, int, int]]:
    if colours is None:
        return {}
    if not isinstance(colours, dict):
        raise _cnets.CnetsError(f"colours: expected a dict of layer name → (r, g, b) or (r, g, b, a), "
                                f"got {_describe(colours)}")
    out: Dict[str, Tuple[int, int, int, int]] = {}
    for name, c in colours.items():
        ok = (isinstance(name, str) and isinstance(c, (tuple, list)) and len(c) in (3, 4)
              and all(isinstance(x, (int, np.integer)) and not isinstance(x, (bool, np.bool_))
                      and 0 <= x <= 255 for x in c))
        if not ok:
            raise _cnets.CnetsError(f"colours[{name!r}]: expected (r, g, b) or (r, g, b, a) of ints "
                                    f"0 to 255, got {_describe(c)}")
        out[name] = tuple(int(x) for x in c) + ((255,) if len(c) == 3 else ())  # type: ignore
    return out


def write_cone_net(path: Any, net: ConeNet, layers: bool = True, support: Optional[float] = 0.8,
                   axes: bool = True, version: int = 8, *, axes_as: str = "family",
                   colours: Optional[Dict[str, Any]] = None) -> None:
    """Writes a cone-net to a .3dm file (``ConeNet.to_3dm``): ``support`` is the factor of the
    conical support layer (``None``: no support layer), ``axes`` whether to write the node
    axes; ``axes_as`` and ``colours`` as in ``write_3dm``."""
    if support is not None and (isinstance(support, (bool, np.bool_))
                                or not isinstance(support, (int, float, np.integer, np.floating))):
        raise _cnets.CnetsError(f"support: expected a number or None, got {_describe(support)}")
    if not isinstance(axes, (bool, np.bool_)):
        raise _cnets.CnetsError(f"axes: expected True or False, got {_describe(axes)}")
    _check_axes_as(axes_as)
    write_3dm(path, cone_net_layers(net, support=support, axes=axes), layers=layers, version=version,
              axes_as=axes_as, colours=colours)


def write_3dm(path: Any, objects: Any, layers: bool = True, version: int = 8, *,
              axes_as: str = "family", colours: Optional[Dict[str, Any]] = None) -> None:
    """Writes geometry to a Rhino .3dm file (Rhino ``version``, 2 to 8, default 8).

    ``objects``: a dict of layer name → item (or list of items), or a sequence of items. An item
    is a ``ConeNet`` (written as ``ConeNet.to_3dm`` does: its mesh, curves, axes and support, on
    sublayers ``Cone-net``, ``Directrix``… of a parent layer named after it), a ``QuadMesh`` /
    (N, M, 3) array (a quad mesh), a ``PolygonMesh``, a ``Polyline`` / (n, 3) array (a polyline
    curve) or a (K, 2, 3) array (lines). A name ``"A::B"`` is the sublayer ``B`` of layer ``A``
    (Rhino's nested layers). With ``layers`` each name (or item kind, for a sequence) gets its own
    layer, coloured (``LAYER_COLOURS`` by name, else ``KIND_COLOURS`` by what it holds;
    ``colours``: a dict of layer name or full path → (r, g, b[, a]) overriding them); without,
    everything goes on the default layer. ``axes_as``: ``"family"`` (default) writes a line set
    as one object per family — one ``PolylineCurve`` when its segments follow each other, else
    one group of lines — and a list of items under one name as one group; ``"lines"`` one loose
    line object per segment. Coordinates are written in double precision. The file is written
    whole, then renamed into place. A bad argument raises ``CnetsError`` naming it.
    """
    import os

    try:
        path = os.fspath(path)
    except TypeError:
        raise _cnets.CnetsError(
            f"path: expected a path (a str or a pathlib.Path), got {_describe(path)}") from None
    if not isinstance(path, str) or not path:
        raise _cnets.CnetsError(f"path: expected a non-empty path, got {_describe(path)}")
    if not isinstance(layers, (bool, np.bool_)):
        raise _cnets.CnetsError(f"layers: expected True or False, got {_describe(layers)}")
    if isinstance(version, bool) or not isinstance(version, (int, np.integer)) or not 2 <= version <= 8:
        raise _cnets.CnetsError(f"version: expected a Rhino file version from 2 to 8, got "
                                f"{_describe(version)}")
    _check_axes_as(axes_as)
    r = _rhino3dm()
    model = r.File3dm()
    w = _Writer(model, bool(layers), axes_as, _check_colours(colours))
    if isinstance(objects, dict):
        for key in objects:
            if not isinstance(key, str) or not key:
                raise _cnets.CnetsError(f"objects: layer names must be non-empty str, got "
                                        f"{_describe(key)}")
            _check_layer_name(key, "objects")
        entries: List[Tuple[Optional[str], Any, str]] = [
            (k, v, f"objects[{k!r}]") for k, v in objects.items()]
    elif isinstance(objects, (ConeNet, QuadMesh, PolygonMesh, Polyline, np.ndarray)):
        entries = [(None, objects, "objects")]
    elif isinstance(objects, (list, tuple)):
        entries = [(None, o, f"objects[{k}]") for k, o in enumerate(objects)]
    else:
        raise _cnets.CnetsError(f"objects: expected a dict of layer name → geometry or a list of "
                                f"geometry, got {_describe(objects)}")
    for name, value, where in entries:
        items = [(v, f"{where}[{k}]") for k, v in enumerate(value)] if isinstance(value, list) \
            else [(value, where)]
        # A list of items under one name is one family: one group (a net's parts have layers).
        family = None
        if axes_as == "family" and name is not None and len(items) > 1 \
                and not any(isinstance(item, ConeNet) for item, _ in items):
            family = w.group(name)
        for item, at in items:
            if isinstance(item, ConeNet):
                for sub, geometry in cone_net_layers(item).items():
                    full = sub if name is None else f"{name}{SEPARATOR}{sub}"
                    _add(w, geometry, w.layer(full, "mesh"), sub, at, family=full)
                continue
            if not isinstance(item, (QuadMesh, PolygonMesh, Polyline)):
                item = _geometry_array(item, at)
            layer_name = name or _kind(item)
            _add(w, item, w.layer(layer_name, _item_kind(item)), name, at, family=layer_name,
                 group=family)
    tmp = f"{path}.{os.getpid()}.tmp"
    if not model.Write(tmp, int(version)):
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise _cnets.CnetsError(f"path: rhino3dm could not write {path}")
    os.replace(tmp, path)


def _kind(item: Any) -> str:
    if isinstance(item, QuadMesh):
        return "Quad meshes"
    if isinstance(item, PolygonMesh):
        return "Meshes"
    if isinstance(item, Polyline):
        return "Polylines"
    arr = np.asarray(item)
    if arr.ndim == 3 and arr.shape[1:] == (2, 3):
        return "Lines"
    return "Polylines" if arr.ndim == 2 else "Quad meshes"
