"""Type aliases of isogami's public signatures (``from isogami._types import Method``), a
real module so that the stubs' aliases exist at runtime and stubtest finds them."""

from typing import TYPE_CHECKING, Any, Callable, Dict, Iterable, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from ._isogami import Design, Family, Record, StoredDesign

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
Matrix = Union[Sequence[Sequence[float]], FloatArray]
Vector = Union[Sequence[float], FloatArray]
DesignLike = Union["Design", "Record", "StoredDesign", str]
# A pair of ints in any form: a tuple, a list, numpy integer scalars, a numpy integer array.
IntPair = Union[Tuple[int, int], Sequence[int], Sequence["np.integer[Any]"], "npt.NDArray[np.integer[Any]]"]
CellLike = Union[str, IntPair]
FamilyLike = Union[str, int, "np.integer[Any]", "Family"]
Progress = Callable[[int], Optional[bool]]
# Unions of one-value Literals (equal to Literal["rigid-modes", "ncm", "springs"] for a type
# checker), so that mypy's stubtest sees the Union it expects at runtime too.
Method = Union[Literal["rigid-modes"], Literal["ncm"], Literal["springs"]]
Behaviour = Union[
    Literal["isotropic_auxetic"], Literal["anisotropic_auxetic"], Literal["orthotropic_positive_poisson"]
]
# One facet value, or several: a list, tuple, set, numpy array or pandas Series of them.
FacetValues = Union[str, int, Tuple[int, int], None, Iterable[Union[str, int, Tuple[int, int], None]]]
Ranges = Union[
    Mapping[str, Tuple[Optional[float], Optional[float]]],
    Sequence[Union[Tuple[str, Optional[float], Optional[float]], str]],
    str,
]
InverseProgress = Callable[[Dict[str, Any]], Optional[bool]]
# A graded sheet's optimisation: progress(iteration, cost).
GradedProgress = Callable[[int, float], Optional[bool]]

__all__ = ["FloatArray", "IntArray", "IntPair", "Matrix", "Vector", "DesignLike", "CellLike", "FamilyLike", "Progress", "Method", "Behaviour", "FacetValues", "Ranges", "InverseProgress", "GradedProgress"]
