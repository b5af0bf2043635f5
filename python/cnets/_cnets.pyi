"""Type stubs of the extension module cnets._cnets (use the cnets package instead)."""

from os import PathLike
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "PathLike[str]"]

class CnetsError(ValueError):
    """An error of cnets, with the engine's message (file:line:col for graph files); a bad
    argument's message names the argument."""

class NoInterfaceError(CnetsError):
    """A graph file named as a node (``cluster:…``) has no ``graph.input`` or ``graph.output``
    node: a graph, not a component."""

class CnetsWarning(UserWarning):
    """A warning of a node that ran (a value clamped to a slider's range…)."""

class Graph:
    """A graph file loaded for evaluation. ``Graph.load(path)``, then ``set("node.input", value)``
    and ``run()``; after an edit only what depends on it runs again (``last_run_nodes``)."""

    @staticmethod
    def load(
        path: _Path,
        allow_read: Optional[Sequence[_Path]] = None,
        max_memory: Union[int, str, None] = None,
        library: Optional[Sequence[_Path]] = None,
        out: Optional[_Path] = None,
    ) -> Graph:
        """Loads a graph file (``allow_read``: more folders to read from; ``max_memory``: bytes or
        ``"2G"``; ``library``: cluster folders; ``out``: the export folder). A file that does not
        load raises ``CnetsError`` with every problem as ``file:line:col: message``."""
        ...
    def set(self, target: str, value: Any) -> None:
        """Sets the literal value of an input, ``target`` = ``"node.input"``, converted to the
        port's type; a wrong target or type, or an input fed by a wire, raises ``CnetsError``."""
        ...
    def get(self, target: str) -> Any:
        """The literal value of an input (``"node.input"``), or ``None`` when it has none."""
        ...
    def unset(self, target: str) -> None:
        """Removes the literal value of an input (``"node.input"``): it falls back to the port's
        default."""
        ...
    def run(
        self, nodes: Union[str, Sequence[str], None] = None, check: Optional[bool] = True
    ) -> Dict[str, Dict[str, Any]]:
        """Evaluates the graph (only what changed) and returns ``{node_id: {output: value}}`` of
        the nodes evaluated now — ``nodes`` and what they depend on, or all; with ``check`` a
        failed node raises ``CnetsError``, otherwise see ``errors``."""
        ...
    def outputs(self, node_id: str) -> Dict[str, Any]:
        """The outputs of one node (``{output: value}``), evaluating it first when needed; a
        node that failed or is blocked raises ``CnetsError`` with its message."""
        ...
    def drag(
        self,
        node: str,
        vertex: Tuple[int, int],
        to: Sequence[float],
        pins: Optional[Sequence[Tuple[int, int]]] = ...,
        free: Union[str, Sequence[str], None] = ...,
        item: Optional[int] = ...,
    ) -> Dict[str, Any]:
        """Drags vertex (i, j) of a node's quad mesh to the point ``to`` (as ``cnets drag``):
        the free inputs are solved, the pins stay, the faces stay (++)(++); keeps the values.
        ``item``: which net when the node's output is a list of them."""
        ...
    def optimize(
        self,
        max_iter: Optional[int] = ...,
        method: Optional[str] = ...,
        convex: Union[str, Sequence[str], None] = ...,
    ) -> Dict[str, Any]:
        """Runs the file's optimization setup (as ``cnets optimize``) and keeps the result's
        values; ``convex`` names constructions whose faces stay (++)(++) for the whole run."""
        ...
    def save(self, path: _Path) -> None:
        """Saves the graph (with the values set) as a graph file, atomically."""
        ...
    def node_type(self, node_id: str) -> str:
        """The node type id of a node."""
        ...
    def time_ms(self, node_id: str) -> Optional[float]:
        """Milliseconds a node took on its last run (``None``: it has not run)."""
        ...
    @property
    def last_run_nodes(self) -> List[str]:
        """The ids of the nodes that ran in the last ``run`` / ``outputs`` (unchanged ones did
        not)."""
        ...
    @property
    def nodes(self) -> List[str]:
        """Node ids in file order."""
        ...
    @property
    def errors(self) -> List[Tuple[str, str]]:
        """``(node_id, message)`` of the nodes that failed or were blocked in the last
        evaluation."""
        ...
    @property
    def files(self) -> List[Path]:
        """Files the export nodes wrote in the last run."""
        ...
    @property
    def warnings(self) -> List[str]:
        """Problems found while loading that did not stop it (e.g. a required input not set)."""
        ...
    @property
    def path(self) -> Path:
        """The graph file's path."""
        ...
    @property
    def out(self) -> Optional[Path]:
        """The folder export nodes write into (``None``: ``out`` in the working folder)."""
        ...
    @out.setter
    def out(self, value: Optional[_Path]) -> None:
        """Sets the folder export nodes write into."""
        ...


def eval(
    node_type: str,
    inputs: Dict[str, Any],
    outputs: Union[str, Sequence[str], None] = None,
    max_memory: Union[int, str, None] = None,
    allow_read: Union[_Path, Sequence[_Path], None] = None,
    library: Union[_Path, Sequence[_Path], None] = None,
    out: Optional[_Path] = None,
    label_tables: bool = False,
    option_prefix: str = "",
) -> Dict[str, Any]:
    """Evaluates one node type (a registry id or ``cluster:<path>``) on ``inputs`` (a dict by
    input name) and returns its outputs by name; ``label_tables``: label rows as ``(codes,
    labels)``; ``option_prefix``: how the caller spells the options in messages."""
    ...
def last_eval_seconds() -> float:
    """Seconds the node itself took in the last ``eval`` call (inputs already converted,
    outputs not yet)."""
    ...
def quad_faces(rows: int, cols: int, wrap_rows: bool, wrap_cols: bool) -> npt.NDArray[np.int64]:
    """The quads (F, 4) of a rows × cols grid, vertex indices ``i * cols + j``, with the wrapping
    quads when the rows or columns wrap."""
    ...
def node_types() -> List[Dict[str, Any]]:
    """Every node type of the library as a dict: ``id``, ``category``, ``doc``, ``inputs``,
    ``outputs``."""
    ...
def node_interface(
    node_type: str,
    library: Union[_Path, Sequence[_Path], None] = None,
    allow_read: Union[_Path, Sequence[_Path], None] = None,
) -> Dict[str, Any]:
    """One node type by id, or a graph file's interface (``cluster:<path>``), as a dict (as
    ``node_types``); a graph file without ``graph.input`` or ``graph.output`` nodes raises
    ``NoInterfaceError``."""
    ...
def parse_size(text: str) -> int:
    """Bytes of a size text (``"64MB"``, ``"2G"``, ``"1.5GiB"``, a plain number of bytes), as
    the command line's ``--max-memory`` reads it."""
    ...
def format_bytes(bytes: int) -> str:
    """Bytes for messages, in decimal units (``64 MB``, ``1.5 GB``)."""
    ...
def check_memory(count: int, what: str, max_memory: Union[int, str, None] = None) -> None:
    """Checks that copying ``count`` numbers (8 bytes each) for ``what`` fits the memory budget
    (``max_memory``, else half the machine's memory); raises ``CnetsError`` otherwise."""
    ...
