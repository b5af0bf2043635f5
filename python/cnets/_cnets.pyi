"""Type stubs of the extension module cnets._cnets (use the cnets package instead)."""

from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import CnetsError as CnetsError
from . import Graph as Graph

def eval(
    node_type: str,
    inputs: Dict[str, Any],
    outputs: Optional[Sequence[str]] = None,
    max_memory: Union[int, str, None] = None,
    allow_read: Optional[Sequence[str]] = None,
    library: Optional[Sequence[str]] = None,
    out: Optional[str] = None,
    label_tables: bool = False,
) -> Dict[str, Any]: ...
def last_eval_seconds() -> float: ...
def quad_faces(rows: int, cols: int, wrap_rows: bool, wrap_cols: bool) -> npt.NDArray[np.int64]: ...
def node_types() -> List[Dict[str, Any]]: ...
def node_interface(
    node_type: str, library: Optional[Sequence[str]] = None, allow_read: Optional[Sequence[str]] = None
) -> Dict[str, Any]: ...
