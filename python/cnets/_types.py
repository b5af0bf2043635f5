"""The value classes of cnets: polylines, quad meshes, polygon meshes and cone-nets.

They hold numpy arrays (no Python object per vertex) and are what the engine returns and accepts.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np

from . import _cnets

__all__ = ["Polyline", "QuadMesh", "PolygonMesh", "ConeNet", "from_compas"]


class Polyline:
    """A polyline: ``points`` an (n, 3) float64 array, ``closed`` whether the last point connects
    back to the first (default ``False``: open, as a plain (n, 3) array-like passed where a
    polyline is expected)."""

    __slots__ = ("points", "closed")

    def __init__(self, points: Any, closed: bool = False) -> None:
        self.points = _point_array(points, "points", 2)
        if not isinstance(closed, (bool, np.bool_)):
            raise _cnets.CnetsError(f"closed: expected True or False, got {_describe(closed)}")
        self.closed = bool(closed)

    def __len__(self) -> int:
        return len(self.points)

    def __repr__(self) -> str:
        return f"Polyline({len(self.points)} points, closed={self.closed})"

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, Polyline)
            and self.closed == other.closed
            and np.array_equal(self.points, other.points)
        )


class QuadMesh:
    """A regular quad-grid mesh: ``vertices`` an (N, M, 3) float64 array (row i, column j),
    ``wrap_rows`` / ``wrap_cols`` whether quads join the last row (column) to the first."""

    def __init__(self, vertices: Any, wrap_rows: bool = False, wrap_cols: bool = False) -> None:
        self.vertices = _point_array(vertices, "vertices", 3)
        for name, flag in (("wrap_rows", wrap_rows), ("wrap_cols", wrap_cols)):
            if not isinstance(flag, (bool, np.bool_)):
                raise _cnets.CnetsError(f"{name}: expected True or False, got {_describe(flag)}")
        self.wrap_rows = bool(wrap_rows)
        self.wrap_cols = bool(wrap_cols)

    @property
    def shape(self) -> tuple:
        """(N, M): rows (generatrix points) and columns (directrix points)."""
        return self.vertices.shape[:2]

    def faces(self) -> np.ndarray:
        """The quads as an (F, 4) int array of indices into ``vertices.reshape(-1, 3)``
        (vertex ``i * M + j``), row by row, wrapping quads included."""
        n, m = self.vertices.shape[:2]
        return _cnets.quad_faces(n, m, self.wrap_rows, self.wrap_cols)

    def to_compas(self) -> Any:
        """A ``compas.datastructures.Mesh`` of the quads (needs ``pip install cnets[compas]``):
        vertex ``i * M + j`` is row i, column j, with the very doubles of ``vertices``; faces as
        ``faces()``, wrapping quads included."""
        return _to_compas(self.vertices.reshape(-1, 3), self.faces().tolist())

    def __repr__(self) -> str:
        n, m = self.vertices.shape[:2]
        return f"{type(self).__name__}({n} × {m} vertices)"


class PolygonMesh:
    """A general polygon mesh: ``vertices`` a (V, 3) array, ``faces`` a list of vertex-index
    lists. A structure joined from several nets (``mesh.join``) names its parts: ``parts`` the
    names, ``face_parts`` the part of every face (an index into ``parts``); both ``None`` for a
    mesh of one net."""

    def __init__(self, vertices: Any, faces: List[List[int]],
                 parts: Optional[List[str]] = None,
                 face_parts: Optional[List[int]] = None) -> None:
        self.vertices = _point_array(vertices, "vertices", 2)
        self.parts = None if parts is None else [str(p) for p in parts]
        self.face_parts = None if face_parts is None else [_index(i) for i in face_parts]
        try:
            self.faces = [[_index(i) for i in f] for f in faces]
        except (TypeError, ValueError) as e:
            raise _cnets.CnetsError(
                f"faces: expected lists of vertex indices, got {_describe(faces)} ({e})") from None
        count = len(self.vertices)
        for k, f in enumerate(self.faces):
            if len(f) < 3 or any(not 0 <= i < count for i in f):
                raise _cnets.CnetsError(
                    f"faces[{k}]: a face needs 3 or more vertex indices in 0..{count - 1}, got {f}")
        if (self.parts is None) != (self.face_parts is None):
            raise _cnets.CnetsError("parts and face_parts go together: give both or neither")
        if self.parts is not None and (
                len(self.face_parts) != len(self.faces)
                or any(not 0 <= p < len(self.parts) for p in self.face_parts)):
            raise _cnets.CnetsError(
                f"face_parts: one index into parts (0..{len(self.parts) - 1}) a face "
                f"({len(self.faces)} faces), got {len(self.face_parts)}")

    def to_compas(self) -> Any:
        """A ``compas.datastructures.Mesh`` with these vertices (keys 0…V−1, the same doubles)
        and faces (needs ``pip install cnets[compas]``)."""
        return _to_compas(self.vertices, self.faces)

    def __repr__(self) -> str:
        return f"PolygonMesh({len(self.vertices)} vertices, {len(self.faces)} faces)"


class ConeNet(QuadMesh):
    """A constructed cone-net (the outputs of ``cnets.construct`` and its siblings).

    - ``vertices``: (N, M, 3) float64; row i is a generatrix point, column j a directrix point.
    - ``apex``: (M−1,) the apex values a_j used (after normalization and correction).
    - ``apices``: (M−1, 3) the cone apices C_j, NaN rows where the apex is at infinity.
    - ``planes``: (N, M−1, 3) the construction-plane normals P_ij.
    - ``configurations``: N lists of M−1 labels ``"++"``, ``"--"``, ``"+-"``, ``"-+"``.
    - ``corrections``: the corrections made, one line each.
    - ``quality``: ``max_planarity``, ``mean_planarity``, ``max_cone_residual``, configuration
      counts, ``first_bad``…
    - ``faces()``: (F, 4) vertex indices into ``vertices.reshape(-1, 3)``.
    - ``to_3dm(path, layers=True)``: a Rhino file (needs ``pip install cnets[rhino]``).
    """

    def __init__(
        self,
        vertices: Any,
        wrap_rows: bool = False,
        wrap_cols: bool = False,
        apex: Any = None,
        apices: Any = None,
        planes: Any = None,
        configurations: Any = None,
        corrections: Optional[List[str]] = None,
        quality: Optional[Dict[str, Any]] = None,
        directrix: Any = None,
        generatrix: Any = None,
    ) -> None:
        super().__init__(vertices, wrap_rows, wrap_cols)
        n, m = self.vertices.shape[:2]
        self.apex = _floats(apex).reshape(-1)
        self.apices = _apices(apices, max(m - 1, 0))
        self.planes = _floats(planes).reshape(n, max(m - 1, 0), 3)
        # (codes, labels) from the engine: the lists are built on first access.
        self._configurations = configurations if configurations is not None else []
        self.corrections = list(corrections or [])
        self.quality = dict(quality or {})
        self.directrix = directrix
        self.generatrix = generatrix

    @property
    def configurations(self) -> List[List[str]]:
        """N lists of M−1 configuration labels ``"++"``, ``"--"``, ``"+-"``, ``"-+"``."""
        c = self._configurations
        if isinstance(c, tuple):
            codes, labels = c
            c = np.asarray(labels, dtype=object)[codes].tolist() if codes.size else [
                [] for _ in range(codes.shape[0])]
            self._configurations = c
        return c

    @property
    def configuration_codes(self) -> np.ndarray:
        """The configurations as an (N, M−1) uint8 array indexing ``("++", "--", "+-", "-+")``."""
        c = self._configurations
        if isinstance(c, tuple):
            codes, labels = c
            order = {"++": 0, "--": 1, "+-": 2, "-+": 3}
            remap = np.asarray([order.get(x, 255) for x in labels], dtype=np.uint8)
            return remap[codes] if codes.size else codes.astype(np.uint8)
        order = {"++": 0, "--": 1, "+-": 2, "-+": 3}
        return np.asarray([[order[x] for x in row] for row in c], dtype=np.uint8).reshape(
            self.vertices.shape[0], -1)

    @classmethod
    def _from_outputs(cls, out: Dict[str, Any], directrix: Any = None, generatrix: Any = None) -> "ConeNet":
        mesh = out["mesh"]
        return cls(
            mesh.vertices,
            mesh.wrap_rows,
            mesh.wrap_cols,
            apex=out.get("apex"),
            apices=out.get("apices"),
            planes=out.get("planes"),
            configurations=out.get("configurations"),
            corrections=out.get("corrections") or [],
            quality=out.get("quality") or {},
            directrix=directrix,
            generatrix=generatrix,
        )

    def to_3dm(self, path: Any, layers: bool = True, **kwargs: Any) -> None:
        """Writes the net to a Rhino file: the quad mesh, the directrix and generatrix as
        polylines, the node axes and a support layer, on coloured layers when ``layers``.
        Keywords: ``support`` (factor, or ``None``), ``axes`` (bool), ``version``, ``axes_as``
        (``"family"``: the axes as one group; ``"lines"``), ``colours`` (see
        ``cnets.write_3dm``)."""
        from .rhino import write_cone_net

        write_cone_net(path, self, layers=layers, **kwargs)


def _compas_mesh_class() -> Any:
    try:
        from compas.datastructures import Mesh
    except ImportError as e:
        raise ImportError(
            "cnets' COMPAS bridge needs the compas package (version 2 or later), which is not "
            "installed: pip install \"cnets[compas]\" (or pip install \"compas>=2\")"
        ) from e
    return Mesh


def _to_compas(vertices: np.ndarray, faces: List[List[int]]) -> Any:
    mesh_class = _compas_mesh_class()
    return mesh_class.from_vertices_and_faces(np.asarray(vertices, dtype=np.float64).tolist(), faces)


def from_compas(mesh: Any) -> PolygonMesh:
    """A ``PolygonMesh`` from a ``compas.datastructures.Mesh`` — e.g. a reference surface for
    ``measure.surface_distance`` or ``fit.symmetric``: its vertices in the mesh's vertex order
    (the same doubles), its faces as indices into them (vertex keys need not be 0…V−1). Needs
    ``pip install cnets[compas]``; anything but a COMPAS mesh raises ``CnetsError``."""
    mesh_class = _compas_mesh_class()
    if not isinstance(mesh, mesh_class):
        raise _cnets.CnetsError(f"mesh: expected a compas.datastructures.Mesh, got {_describe(mesh)}")
    index = {}
    coordinates = []
    for k, key in enumerate(mesh.vertices()):
        index[key] = k
        coordinates.append(mesh.vertex_coordinates(key))
    if not coordinates:
        raise _cnets.CnetsError("mesh: the COMPAS mesh has no vertices")
    faces = [[index[v] for v in mesh.face_vertices(f)] for f in mesh.faces()]
    return PolygonMesh(np.asarray(coordinates, dtype=np.float64).reshape(-1, 3), faces)


def _apices(apices: Any, count: int) -> np.ndarray:
    if apices is None:
        return np.full((count, 3), np.nan)
    # The engine's point outputs always come back as an (n, 3) array (NaN rows at infinity).
    return np.asarray(apices, dtype=np.float64).reshape(-1, 3)


def _describe(x: Any) -> str:
    """A value's type (and short repr) for messages."""
    if x is None:
        return "None"
    text = repr(x)
    kind = type(x).__name__
    if isinstance(x, np.ndarray):
        return f"a numpy array of shape {x.shape} and dtype {x.dtype}"
    article = "an" if kind[:1] in "aeiou" else "a"
    if isinstance(x, (list, tuple)) and len(text) > 40:
        return f"{article} {kind} of {len(x)} item{'' if len(x) == 1 else 's'}"
    return f"{article} {kind} ({text})" if len(text) <= 40 else f"{article} {kind}"


def _index(i: Any) -> int:
    if isinstance(i, (bool, np.bool_)) or not isinstance(i, (int, np.integer)):
        raise TypeError(f"{i!r} is not an int")
    return int(i)


def _point_array(x: Any, name: str, ndim: int) -> np.ndarray:
    """``x`` as a float64 array of points: (n, 3) when ``ndim`` is 2, (N, M, 3) when 3. A float64
    array is kept as it is (a view is not copied); anything that is not numbers raises
    ``CnetsError`` naming ``name``."""
    if isinstance(x, np.ndarray) and x.dtype == np.float64:
        arr = x
    else:
        if isinstance(x, (str, bytes, dict)) or x is None:
            raise _cnets.CnetsError(f"{name}: expected an array of points, got {_describe(x)}")
        if isinstance(x, np.ndarray) and x.dtype.kind not in "fiub":
            raise _cnets.CnetsError(f"{name}: expected an array of numbers, got {_describe(x)}")
        if isinstance(x, np.ndarray):  # the float64 copy must fit the memory budget
            _cnets.check_memory(x.size, f"{name}: an array of shape {list(x.shape)}")
        try:
            arr = np.asarray(x, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise _cnets.CnetsError(
                f"{name}: expected an array of points, got {_describe(x)} ({e})") from None
    shape = "(n, 3)" if ndim == 2 else "(N, M, 3)"
    if arr.ndim != ndim or arr.shape[-1] != 3:
        raise _cnets.CnetsError(f"{name}: expected an {shape} array of points, got shape {arr.shape}")
    return arr


def _floats(x: Any) -> np.ndarray:
    if isinstance(x, np.ndarray) and x.dtype == np.float64:
        return x
    return np.asarray([] if x is None else x, dtype=np.float64)
