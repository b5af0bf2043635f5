"""Rhino files (.3dm) through McNeel's official ``rhino3dm`` package (``pip install cnets[rhino]``),
and conversions between Rhino geometry and cnets values (used by the Hops server).

- ``write_3dm(path, objects, layers=True)``: cone-nets, quad meshes, polygon meshes, polylines and
  line sets, each on its own named layer.
- ``ConeNet.to_3dm(path, layers=True)``: the net as a quad mesh on layer ``Cone-net``, the directrix
  and generatrix as polylines on ``Directrix`` / ``Generatrix``, the torsion-free node axes on
  ``Axes`` and a conical support layer on ``Support`` (both computed by the node library:
  ``cnets.torsion_free_axes``, ``cnets.conical_support``; left out, with a warning, where they are
  undefined: a generatrix point on the directrix).

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
    "LAYER_COLOURS",
    "curve_points",
    "mesh_from_rhino",
    "quad_mesh_to_rhino",
    "polyline_to_rhino",
    "write_3dm",
    "write_cone_net",
]

#: Layer colours (RGBA) by layer name; other layers are grey.
LAYER_COLOURS: Dict[str, Tuple[int, int, int, int]] = {
    "Cone-net": (40, 110, 200, 255),
    "Directrix": (220, 60, 40, 255),
    "Generatrix": (40, 160, 70, 255),
    "Axes": (120, 120, 120, 255),
    "Support": (200, 140, 30, 255),
}


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


def _layer(model: Any, name: str, cache: Dict[str, int]) -> int:
    if name not in cache:
        colour = LAYER_COLOURS.get(name, (128, 128, 128, 255))
        cache[name] = model.Layers.AddLayer(name, colour)
    return cache[name]


def _attributes(layer: Optional[int], name: Optional[str]) -> Any:
    r = _rhino3dm()
    attr = r.ObjectAttributes()
    if layer is not None:
        attr.LayerIndex = layer
    if name:
        attr.Name = name
    return attr


def _add(model: Any, item: Any, layer: Optional[int], name: Optional[str], where: str) -> None:
    attr = _attributes(layer, name)
    if isinstance(item, QuadMesh):
        model.Objects.AddMesh(quad_mesh_to_rhino(item), attr)
    elif isinstance(item, PolygonMesh):
        model.Objects.AddMesh(polygon_mesh_to_rhino(item), attr)
    elif isinstance(item, Polyline):
        model.Objects.AddCurve(polyline_to_rhino(item), attr)
    else:
        arr = _geometry_array(item, where)
        if arr.ndim == 3 and arr.shape[1:] == (2, 3):
            r = _rhino3dm()
            for (a, b) in arr.tolist():
                model.Objects.AddLine(r.Point3d(*a), r.Point3d(*b), attr)
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


def write_cone_net(path: Any, net: ConeNet, layers: bool = True, support: Optional[float] = 0.8,
                   axes: bool = True, version: int = 8) -> None:
    """Writes a cone-net to a .3dm file (``ConeNet.to_3dm``): ``support`` is the factor of the
    conical support layer (``None``: no support layer), ``axes`` whether to write the node
    axes."""
    if support is not None and (isinstance(support, (bool, np.bool_))
                                or not isinstance(support, (int, float, np.integer, np.floating))):
        raise _cnets.CnetsError(f"support: expected a number or None, got {_describe(support)}")
    if not isinstance(axes, (bool, np.bool_)):
        raise _cnets.CnetsError(f"axes: expected True or False, got {_describe(axes)}")
    write_3dm(path, cone_net_layers(net, support=support, axes=axes), layers=layers, version=version)


def write_3dm(path: Any, objects: Any, layers: bool = True, version: int = 8) -> None:
    """Writes geometry to a Rhino .3dm file (Rhino ``version``, 2 to 8, default 8).

    ``objects``: a dict of layer name → item (or list of items), or a sequence of items. An item
    is a ``ConeNet`` (written as ``ConeNet.to_3dm`` does: its mesh, curves, axes and support on
    their layers), a ``QuadMesh`` / (N, M, 3) array (a quad mesh), a ``PolygonMesh``, a
    ``Polyline`` / (n, 3) array (a polyline curve) or a (K, 2, 3) array (lines). With ``layers``
    each name (or item kind, for a sequence) gets its own layer; without, everything goes on the
    default layer. Coordinates are written in double precision. The file is written whole, then
    renamed into place. A bad argument raises ``CnetsError`` naming it.
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
    r = _rhino3dm()
    model = r.File3dm()
    cache: Dict[str, int] = {}
    if isinstance(objects, dict):
        for key in objects:
            if not isinstance(key, str) or not key:
                raise _cnets.CnetsError(f"objects: layer names must be non-empty str, got "
                                        f"{_describe(key)}")
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
        for item, at in items:
            if isinstance(item, ConeNet):
                for sub, geometry in cone_net_layers(item).items():
                    layer = _layer(model, sub if name is None else f"{name}/{sub}", cache) if layers else None
                    _add(model, geometry, layer, sub, at)
                continue
            if not isinstance(item, (QuadMesh, PolygonMesh, Polyline)):
                item = _geometry_array(item, at)
            layer_name = name or _kind(item)
            layer = _layer(model, layer_name, cache) if layers else None
            _add(model, item, layer, name, at)
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
