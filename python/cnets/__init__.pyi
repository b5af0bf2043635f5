"""Type stubs of the cnets package (see docs/python.md)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._types import ConeNet as ConeNet
from ._types import PolygonMesh as PolygonMesh
from ._types import Polyline as Polyline
from ._types import QuadMesh as QuadMesh

_Path = Union[str, "PathLike[str]"]
PolylineLike = Union[Polyline, npt.ArrayLike]
Numbers = Union[float, Sequence[float], npt.NDArray[np.float64]]
Table = Union[float, Sequence[float], Sequence[Sequence[float]], npt.NDArray[np.float64]]
EndPlanes = Literal["perpendicular", "mirror"]

class CnetsError(ValueError):
    """An error of cnets, with the engine's message (file:line:col for graph files)."""

class Graph:
    """A graph file loaded for evaluation; edits re-run only what depends on them."""

    @staticmethod
    def load(
        path: _Path,
        allow_read: Optional[Sequence[_Path]] = None,
        max_memory: Union[int, str, None] = None,
        library: Optional[Sequence[_Path]] = None,
        out: Optional[_Path] = None,
    ) -> Graph: ...
    def set(self, target: str, value: Any) -> None: ...
    def get(self, target: str) -> Any: ...
    def unset(self, target: str) -> None: ...
    def run(
        self, nodes: Optional[Sequence[str]] = None, check: bool = True
    ) -> Dict[str, Dict[str, Any]]: ...
    def outputs(self, node_id: str) -> Dict[str, Any]: ...
    def save(self, path: _Path) -> None: ...
    def node_type(self, node_id: str) -> str: ...
    def time_ms(self, node_id: str) -> Optional[float]: ...
    @property
    def last_run_nodes(self) -> List[str]: ...
    @property
    def nodes(self) -> List[str]: ...
    @property
    def errors(self) -> List[Tuple[str, str]]: ...
    @property
    def files(self) -> List[str]: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def path(self) -> str: ...
    out: Optional[str]

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
) -> ConeNet: ...
def ctube(
    directrix: PolylineLike,
    generatrix: PolylineLike,
    apex: Numbers = 1.0,
    normals: Optional[npt.ArrayLike] = None,
    normalized: bool = False,
    scale: Optional[float] = None,
    end_planes: EndPlanes = "perpendicular",
) -> ConeNet: ...
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
) -> ConeNet: ...
def encode(vertices: Union[npt.ArrayLike, QuadMesh]) -> Dict[str, Any]: ...
def eval(
    node_type: str,
    *,
    _outputs: Optional[Sequence[str]] = None,
    _max_memory: Union[int, str, None] = None,
    _allow_read: Optional[Sequence[_Path]] = None,
    _library: Optional[Sequence[_Path]] = None,
    _out: Optional[_Path] = None,
    **inputs: Any,
) -> Dict[str, Any]: ...
def node_types() -> List[Dict[str, Any]]: ...
def write_3dm(path: _Path, objects: Any, **kwargs: Any) -> None: ...
def sweep(
    graph: _Path,
    parameters: Union[Dict[str, Sequence[Any]], Sequence[Dict[str, Any]]],
    outputs: Sequence[str],
    client: Any = None,
    out: Optional[_Path] = None,
    allow_read: Sequence[_Path] = (),
    max_memory: Union[int, str, None] = None,
    library: Sequence[_Path] = (),
    n_workers: Optional[int] = None,
) -> Any: ...
