"""Type stubs of isogami's native module (isogami._isogami), re-exported by ``isogami``."""

from os import PathLike
from pathlib import Path
from typing import final, overload, Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._types import FloatArray, IntArray, IntPair, Matrix, Vector, DesignLike, CellLike, FamilyLike, Progress, Method, Behaviour, FacetValues, Ranges, InverseProgress, GradedProgress

__version__: str
__all__ = [
    "Analysis",
    "COMPARISON_DESIGNS",
    "CancelledError",
    "Cell",
    "CellError",
    "Comparison",
    "ContactError",
    "DEPLOY_SETTINGS",
    "Database",
    "DeployError",
    "DeploySettings",
    "Deployment",
    "Design",
    "DesignError",
    "ExploreError",
    "ExportError",
    "Family",
    "FiniteError",
    "FiniteSheet",
    "GradedRun",
    "InverseError",
    "InverseResult",
    "IsogamiError",
    "KinematicsError",
    "LinkageError",
    "Linkages",
    "MeasureError",
    "MethodResult",
    "MobilityError",
    "Motion",
    "NAMED_DESIGNS",
    "Query",
    "QueryError",
    "Record",
    "SAMPLE_OPENING_DESIGNS",
    "SettingsError",
    "ShapeError",
    "SheetDeployment",
    "SheetPull",
    "StoreError",
    "StoredDesign",
    "TilingError",
    "__version__",
    "_compute_calls",
    "_restore",
    "analyze",
    "area_ratio",
    "cell",
    "compare",
    "deformation_gradient",
    "deploy",
    "deploy_sheet",
    "design",
    "directional_expansion",
    "expansion_profile",
    "export",
    "export_formats",
    "families",
    "family",
    "finite_sheet",
    "graded",
    "load_graded",
    "follow_shape",
    "inverse",
    "linkages",
    "open_database",
    "poisson_ratio",
    "polar",
    "principal_direction",
    "principal_expansions",
    "pull_sheet",
    "param_ranges_of",
    "rank_drop_shape",
    "shape_mobility",
]

NAMED_DESIGNS: List[str]
SAMPLE_OPENING_DESIGNS: List[str]
COMPARISON_DESIGNS: List[str]
DEPLOY_SETTINGS: List[str]


# Exceptions: one class per kind of library error.
class IsogamiError(Exception): ...
class TilingError(IsogamiError): ...
class CellError(IsogamiError): ...
class DesignError(IsogamiError): ...
class KinematicsError(IsogamiError): ...
class MobilityError(IsogamiError): ...
class ContactError(IsogamiError): ...
class DeployError(IsogamiError): ...
class CancelledError(DeployError): ...
class MeasureError(IsogamiError): ...
class LinkageError(IsogamiError): ...
class ExploreError(IsogamiError): ...
class SettingsError(IsogamiError): ...
class StoreError(IsogamiError): ...
class QueryError(StoreError): ...
class ExportError(IsogamiError): ...
class InverseError(IsogamiError): ...
class ShapeError(IsogamiError): ...
class FiniteError(IsogamiError): ...

@final
class Family:
    """One of the 81 realizable isohedral tiling families IH1…IH93."""

    @property
    def name(self) -> str: ...
    @property
    def number(self) -> int: ...
    @property
    def param_count(self) -> int: ...
    @property
    def default_params(self) -> List[float]: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def aspect_count(self) -> int: ...
    @property
    def edges(self) -> List[Dict[str, Any]]: ...
    def param_ranges(self, span: Optional[float] = None) -> FloatArray:
        """(param_count, 2) array of the exploration's sampling box (low, high)."""
    def prototile(self, params: Optional[Sequence[float]] = None) -> FloatArray:
        """(vertex_count, 2) prototile vertices; TilingError for invalid parameters."""
    def check_params(self, params: Sequence[float]) -> None:
        """None when the parameters give a valid tiling, else TilingError."""
    def sample_params(
        self, levels: int = 3, span: Optional[float] = None, max_samples: int = 12
    ) -> List[List[float]]:
        """Well-shaped parameter vectors on the exploration's grid, defaults first."""
    def info(self) -> Dict[str, Any]:
        """The family as ``isogami families --json`` lists it."""

def families() -> List[Family]:
    """All 81 families in Kaplan's order."""

def family(name: FamilyLike) -> Family:
    """The family named (``"IH28"``, ``"28"``) or numbered; TilingError if unknown."""

@final
class Cell:
    """The closed unit cell (or a×b supercell) of a tiling."""

    @property
    def family(self) -> str: ...
    @property
    def params(self) -> List[float]: ...
    @property
    def cell(self) -> Tuple[int, int]: ...
    @property
    def u(self) -> FloatArray: ...
    @property
    def w(self) -> FloatArray: ...
    @property
    def tile_count(self) -> int: ...
    @property
    def edge_count(self) -> int: ...
    @property
    def mean_edge_length(self) -> float: ...
    @property
    def polygons(self) -> List[FloatArray]: ...
    @property
    def centroids(self) -> FloatArray: ...
    @property
    def aspects(self) -> List[int]: ...
    @property
    def edges(self) -> IntArray:
        """(edges, 4): tile_a, edge_a, tile_b, edge_b."""
    @property
    def offsets(self) -> IntArray:
        """(edges, 2): cell offset of each edge's neighbour."""
    @property
    def endpoints(self) -> FloatArray:
        """(edges, 2, 2): endpoints A and B of each edge."""
    def to_dict(self) -> Dict[str, Any]:
        """The cell as ``isogami cell --json`` prints it."""
    def svg(self, joints: Optional[str] = None) -> str: ...

def cell(family: FamilyLike, params: Optional[Sequence[float]] = None, cell: Optional[CellLike] = None) -> Cell:
    """The closed unit cell of a family at shape ``params`` in supercell ``cell``."""

@final
class Design:
    """A kirigami design: family, shape parameters, supercell, a joint per unique edge."""

    def __new__(
        cls,
        family: FamilyLike,
        params: Optional[Sequence[float]] = None,
        cell: Optional[CellLike] = None,
        joints: Union[str, Sequence[str], None] = None,
    ) -> Design: ...
    @staticmethod
    def from_spec(spec: str) -> Design: ...
    @staticmethod
    def from_json(json: Union[str, Mapping[str, Any]]) -> Design: ...
    @staticmethod
    def named(name: str) -> Design: ...
    @property
    def family(self) -> str: ...
    @property
    def params(self) -> List[float]: ...
    @property
    def cell(self) -> Tuple[int, int]: ...
    @property
    def joints(self) -> str: ...
    @property
    def spec(self) -> str: ...
    @property
    def joint_count(self) -> int: ...
    @property
    def edge_count(self) -> int: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def with_params(self, params: Sequence[float]) -> Design: ...
    def with_joints(self, joints: Union[str, Sequence[str]]) -> Design: ...
    def unit_cell(self) -> Cell: ...
    def geometry(self) -> Dict[str, Any]: ...
    def svg(self) -> str: ...
    def __hash__(self) -> int: ...
    def __eq__(self, value: object, /) -> bool: ...

def design(text: str) -> Design:
    """Reads a name, a spec string or design JSON, checked to build."""

@final
class Motion:
    """A first-order motion (unit vector, lengths in units of L, signed to open)."""

    @property
    def tiles(self) -> FloatArray:
        """(tiles, 3): vx, vy, omega."""
    @property
    def u(self) -> FloatArray: ...
    @property
    def w(self) -> FloatArray: ...
    @property
    def area_rate(self) -> float: ...
    @property
    def vector(self) -> FloatArray: ...

@final
class Analysis:
    """Mobility of a design in its closed state."""

    @property
    def design(self) -> str: ...
    @property
    def tiles(self) -> int: ...
    @property
    def edges(self) -> int: ...
    @property
    def joints(self) -> int: ...
    @property
    def length_scale(self) -> float: ...
    @property
    def dof(self) -> int: ...
    @property
    def eigenvalues(self) -> FloatArray: ...
    @property
    def spectrum(self) -> FloatArray: ...
    @property
    def threshold(self) -> float: ...
    @property
    def largest_zero(self) -> Optional[float]: ...
    @property
    def smallest_nonzero(self) -> Optional[float]: ...
    @property
    def gap_decades(self) -> Optional[float]: ...
    @property
    def gap(self) -> FloatArray:
        """[largest_zero, smallest_nonzero], or empty."""
    @property
    def motion(self) -> Optional[Motion]: ...
    @property
    def modes(self) -> List[Motion]: ...
    def to_dict(self) -> Dict[str, Any]:
        """As ``isogami analyze --json`` prints it."""

def _restore(cls: str, tag: str, json: bytes, arrays: List[bytes]) -> Any:
    """Unpickling a computed result from its data (see ``isogami._restore``)."""

def _compute_calls() -> int:
    """How many computations this process has started (unpickling starts none)."""

def analyze(design: DesignLike, tol: Optional[float] = None) -> Analysis:
    """Mobility of a design (relative zero tolerance ``tol``, default 1e-9)."""

@final
class DeploySettings:
    """Every setting of a deployment; keyword-only, library defaults."""

    def __new__(
        cls,
        *,
        method: Method = ...,
        kerf: float = ...,
        dhat: float = ...,
        stiffness: float = ...,
        step_weight: float = ...,
        initial_step: float = ...,
        max_step: float = ...,
        max_halvings: int = ...,
        growth: float = ...,
        max_steps: int = ...,
        step_tolerance: float = ...,
        joint_tolerance: float = ...,
        frame_joint_tolerance: float = ...,
        max_attempts: int = ...,
        max_stretch: float = ...,
        mobility_tol: float = ...,
        mode: Optional[int] = ...,
    ) -> DeploySettings: ...
    def replace(self, **changes: Any) -> DeploySettings: ...
    def validate(self) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...
    @property
    def method(self) -> Method: ...
    @property
    def kerf(self) -> float: ...
    @property
    def dhat(self) -> float: ...
    @property
    def stiffness(self) -> float: ...
    @property
    def step_weight(self) -> float: ...
    @property
    def initial_step(self) -> float: ...
    @property
    def max_step(self) -> float: ...
    @property
    def max_halvings(self) -> int: ...
    @property
    def growth(self) -> float: ...
    @property
    def max_steps(self) -> int: ...
    @property
    def step_tolerance(self) -> float: ...
    @property
    def joint_tolerance(self) -> float: ...
    @property
    def frame_joint_tolerance(self) -> float: ...
    @property
    def max_attempts(self) -> int: ...
    @property
    def max_stretch(self) -> float: ...
    @property
    def mobility_tol(self) -> float: ...
    @property
    def mode(self) -> Optional[int]: ...

@final
class Deployment:
    """A finished deployment: report and per-frame numpy arrays (n frames)."""

    @property
    def design(self) -> str: ...
    @property
    def method(self) -> Method: ...
    @property
    def kerf(self) -> float: ...
    @property
    def length_scale(self) -> float: ...
    @property
    def dof(self) -> int: ...
    @property
    def end_reason(self) -> str: ...
    @property
    def steps(self) -> int: ...
    @property
    def attempts(self) -> int: ...
    @property
    def arc_length(self) -> float: ...
    @property
    def max_joint_residual(self) -> float: ...
    @property
    def min_clearance(self) -> float: ...
    @property
    def behaviour(self) -> Optional[Behaviour]: ...
    @property
    def max_expansion(self) -> float: ...
    @property
    def min_expansion(self) -> float: ...
    @property
    def max_area_ratio(self) -> float: ...
    @property
    def max_tile_rotation(self) -> float: ...
    @property
    def t(self) -> FloatArray:
        """(n,) normalised arc length."""
    @property
    def step(self) -> IntArray: ...
    @property
    def F(self) -> FloatArray:
        """(n, 2, 2) deformation gradient."""
    @property
    def U(self) -> FloatArray:
        """(n, 2, 2) right stretch tensor."""
    @property
    def principal_expansions(self) -> FloatArray:
        """(n, 2): min, max."""
    @property
    def principal_angle(self) -> FloatArray: ...
    @property
    def area_ratio(self) -> FloatArray: ...
    @property
    def lattice_rotation(self) -> FloatArray: ...
    @property
    def tile_rotations(self) -> FloatArray:
        """(n, tiles)."""
    @property
    def tile_poses(self) -> FloatArray:
        """(n, tiles, 3): x, y, theta."""
    @property
    def tiling_vectors(self) -> FloatArray:
        """(n, 2, 2): u, w."""
    @property
    def joint_residual(self) -> FloatArray: ...
    @property
    def clearance(self) -> FloatArray: ...
    @property
    def states(self) -> FloatArray:
        """(n, unknowns) non-dimensional states."""
    def frame_index(self, t: float) -> int: ...
    def profile(
        self, t: Optional[float] = None, frame: Optional[int] = None, samples: int = 180
    ) -> FloatArray:
        """(samples, 2): theta, epsilon(theta) of one frame."""
    def classify(
        self, isotropic: float = 0.05, orthotropic: float = 0.02, absolute: float = 1e-6
    ) -> Optional[Behaviour]: ...
    def report(self) -> Dict[str, Any]:
        """As ``isogami deploy --json`` prints it."""
    def to_json(self) -> str: ...
    def frame_svgs(self, width: float = 480.0) -> List[str]: ...
    def dataframe(self) -> Any:
        """One row per frame as a pandas DataFrame (t, step, area_ratio, expansions, ...)."""
    def __len__(self) -> int: ...

def deploy(
    design: DesignLike,
    settings: Optional[DeploySettings] = None,
    *,
    frames: Union[int, Literal["all"], None] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
    **overrides: Any,
) -> Deployment:
    """Deploys a design to the contact limit (GIL released; Ctrl-C interrupts)."""

@final
class Linkages:
    """The linkage analysis of a design."""

    @property
    def signature(self) -> str: ...
    @property
    def bars(self) -> List[int]: ...
    @property
    def linkages(self) -> List[Dict[str, Any]]: ...
    @property
    def degree_histogram(self) -> Dict[int, int]: ...
    @property
    def other_faces(self) -> List[Dict[str, Any]]: ...
    def tile_linkages(self) -> List[List[int]]: ...
    def to_dict(self) -> Dict[str, Any]:
        """As ``isogami linkages --json`` prints it."""
    def svg(self) -> str: ...
    def __len__(self) -> int: ...

def linkages(design: DesignLike) -> Linkages:
    """The linkage analysis of a design (paper §5.1)."""

@final
class MethodResult:
    """One method's result in a comparison."""

    @property
    def method(self) -> Method: ...
    @property
    def final_t(self) -> float: ...
    @property
    def path_distance(self) -> float: ...
    @property
    def max_area_ratio(self) -> float: ...
    @property
    def max_area_t(self) -> float: ...
    @property
    def final_area_ratio(self) -> float: ...
    @property
    def max_expansion(self) -> float: ...
    @property
    def min_expansion(self) -> float: ...
    @property
    def max_tile_rotation(self) -> float: ...
    @property
    def reached_peak_area(self) -> bool: ...
    @property
    def end_reason(self) -> str: ...
    @property
    def steps(self) -> int: ...
    @property
    def attempts(self) -> int: ...
    @property
    def millis(self) -> float: ...
    def to_dict(self) -> Dict[str, Any]: ...

@final
class Comparison:
    """Rigid modes, NCM and springs on one design."""

    @property
    def design(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def results(self) -> List[MethodResult]: ...
    def result(self, method: Method) -> MethodResult: ...
    def to_dict(self) -> Dict[str, Any]:
        """One element of ``isogami compare --json``."""
    def __len__(self) -> int: ...

def compare(
    design: DesignLike,
    settings: Optional[DeploySettings] = None,
    *,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
    **overrides: Any,
) -> Comparison:
    """The baseline comparison of paper §5 / Fig. 4 on one design."""

# Measures (paper §4.3); matrices as rows.
def deformation_gradient(u0: Vector, w0: Vector, u: Vector, w: Vector) -> FloatArray: ...
# The measures take one 2x2 matrix (a float or a pair of floats back) or a stack of them,
# an array of shape (..., 2, 2) such as ``Deployment.F`` (arrays of the stack's shape back).
@overload
def polar(f: Sequence[Sequence[float]]) -> Tuple[FloatArray, FloatArray]: ...
@overload
def polar(f: npt.ArrayLike) -> Tuple[FloatArray, FloatArray]: ...
@overload
def principal_expansions(u: Sequence[Sequence[float]]) -> Tuple[float, float]: ...
@overload
def principal_expansions(u: npt.ArrayLike) -> Union[Tuple[float, float], FloatArray]: ...
@overload
def principal_direction(u: Sequence[Sequence[float]]) -> float: ...
@overload
def principal_direction(u: npt.ArrayLike) -> Union[float, FloatArray]: ...
@overload
def directional_expansion(u: Sequence[Sequence[float]], theta: float) -> float: ...
@overload
def directional_expansion(u: npt.ArrayLike, theta: float) -> Union[float, FloatArray]: ...
def expansion_profile(u: Matrix, samples: int = 180) -> FloatArray: ...
@overload
def area_ratio(f: Sequence[Sequence[float]]) -> float: ...
@overload
def area_ratio(f: npt.ArrayLike) -> Union[float, FloatArray]: ...
def poisson_ratio(min_expansion: float, max_expansion: float) -> Optional[float]: ...


@final
class Query:
    """The browser's catalogue filters as the store's query type."""

    def __new__(
        cls,
        *,
        family: FacetValues = ...,
        cell: FacetValues = ...,
        tiles: FacetValues = ...,
        behaviour: FacetValues = ...,
        linkage: FacetValues = ...,
        end: FacetValues = ...,
        origin: FacetValues = ...,
        range: Ranges = ...,
        sort: Optional[str] = ...,
        limit: Optional[int] = ...,
        offset: int = ...,
    ) -> Query: ...
    def where(self, **filters: Any) -> Query: ...
    def to_dict(self) -> Dict[str, Any]: ...

@final
class Record:
    """One design of a catalogue (the browser's columns)."""

    @property
    def spec(self) -> str: ...
    @property
    def origin(self) -> Literal["explored", "user"]: ...
    @property
    def family(self) -> str: ...
    @property
    def cell(self) -> Tuple[int, int]: ...
    @property
    def tile_count(self) -> int: ...
    @property
    def joints(self) -> str: ...
    @property
    def topology(self) -> str: ...
    @property
    def params(self) -> List[float]: ...
    @property
    def behaviour(self) -> Optional[Behaviour]: ...
    @property
    def linkage_signature(self) -> Optional[str]: ...
    @property
    def end_reason(self) -> str: ...
    @property
    def method(self) -> Method: ...
    @property
    def dof(self) -> int: ...
    @property
    def kerf(self) -> float: ...
    @property
    def max_expansion(self) -> float: ...
    @property
    def min_expansion(self) -> float: ...
    @property
    def max_area_ratio(self) -> float: ...
    @property
    def max_tile_rotation(self) -> float: ...
    @property
    def poisson_min(self) -> Optional[float]: ...
    @property
    def poisson_max(self) -> Optional[float]: ...
    @property
    def steps(self) -> int: ...
    @property
    def finite_raw_dof(self) -> Optional[int]: ...
    @property
    def finite_covered(self) -> Optional[float]: ...
    @property
    def open_t(self) -> Optional[float]: ...
    @property
    def end_area_ratio(self) -> Optional[float]: ...
    @property
    def shape_tolerance(self) -> Optional[float]: ...
    @property
    def fabrication_kept(self) -> Optional[float]: ...
    @property
    def buildable(self) -> bool: ...
    def design(self) -> Design: ...
    def to_dict(self) -> Dict[str, Any]: ...

@final
class StoredDesign:
    """A stored design read back whole."""

    @property
    def record(self) -> Record: ...
    def report(self) -> Dict[str, Any]: ...
    def linkages(self) -> Optional[Dict[str, Any]]: ...
    @property
    def other_cells(self) -> List[str]: ...

@final
class Database:
    """A design database opened read-only."""

    def __new__(cls, path: Union[str, PathLike[str]], check: Literal["quick", "full"] = "quick") -> Database: ...
    @property
    def path(self) -> Path: ...
    def designs(self, query: Optional[Query] = None, **filters: Any) -> List[Record]: ...
    def dataframe(self, query: Optional[Query] = None, **filters: Any) -> Any:
        """A pandas DataFrame of the matching designs (shape parameters also as param_0, ...)."""
    def count(self, query: Optional[Query] = None, **filters: Any) -> int: ...
    def facet_counts(self, facet: str, query: Optional[Query] = None, **filters: Any) -> List[Tuple[Any, int]]: ...
    def scatter(
        self, x: str, y: str, query: Optional[Query] = None, limit: int = 100000, **filters: Any
    ) -> Dict[str, Any]: ...
    def design(self, spec: Union[str, Design]) -> Optional[StoredDesign]: ...
    def stats(self) -> Dict[str, Any]:
        """As ``isogami db stats --json`` prints it."""
    @property
    def settings(self) -> Optional[Dict[str, Any]]: ...
    @property
    def tool_version(self) -> Optional[str]: ...
    def close(self) -> None: ...
    def __len__(self) -> int: ...
    def __enter__(self) -> Database: ...
    def __exit__(self, *args: Any) -> bool: ...

def open_database(path: Union[str, PathLike[str]], check: Literal["quick", "full"] = "quick") -> Database:
    """Opens a design database for reading."""

@overload
def export(
    design: DesignLike,
    format: Literal["svg", "dxf", "fold", "obj", "tiles-csv", "tiles-json", "stl", "3mf"],
    *,
    patch: Union[str, Tuple[int, int], Sequence[int], npt.NDArray[np.integer[Any]], None] = None,
    region: Optional[str] = None,
    edge_mm: Optional[float] = None,
    width_mm: Optional[float] = None,
    t: Union[float, Literal["open", "limit"], None] = None,
    kerf: Optional[float] = None,
    frames: Optional[int] = None,
    complete: bool = True,
    material: Optional[Literal["card", "felt", "pla"]] = None,
    hinge_mm: Optional[float] = None,
    kerf_mm: Optional[float] = None,
    thickness_mm: Optional[float] = None,
    margin_mm: Optional[float] = None,
    stroke_mm: Optional[float] = None,
    cut_colour: Optional[str] = None,
    score_colour: Optional[str] = None,
    engrave_colour: Optional[str] = None,
    labels: bool = False,
    gap_mm: Optional[float] = None,
    lamella_mm: Optional[float] = None,
    nozzle_mm: Optional[float] = None,
    creator: Optional[str] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
) -> bytes: ...
@overload
def export(
    design: DesignLike,
    format: Literal["kirigami-sim"],
    *,
    patch: Union[str, Tuple[int, int], Sequence[int], npt.NDArray[np.integer[Any]], None] = None,
    region: Optional[str] = None,
    edge_mm: Optional[float] = None,
    width_mm: Optional[float] = None,
    t: Union[float, Literal["open", "limit"], None] = None,
    kerf: Optional[float] = None,
    frames: Optional[int] = None,
    complete: bool = True,
    material: Optional[Literal["card", "felt", "pla"]] = None,
    hinge_mm: Optional[float] = None,
    kerf_mm: Optional[float] = None,
    thickness_mm: Optional[float] = None,
    margin_mm: Optional[float] = None,
    stroke_mm: Optional[float] = None,
    cut_colour: Optional[str] = None,
    score_colour: Optional[str] = None,
    engrave_colour: Optional[str] = None,
    labels: bool = False,
    gap_mm: Optional[float] = None,
    lamella_mm: Optional[float] = None,
    nozzle_mm: Optional[float] = None,
    creator: Optional[str] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
) -> Dict[str, bytes]: ...
@overload
def export(
    design: DesignLike,
    format: str,
    *,
    patch: Union[str, Tuple[int, int], Sequence[int], npt.NDArray[np.integer[Any]], None] = None,
    region: Optional[str] = None,
    edge_mm: Optional[float] = None,
    width_mm: Optional[float] = None,
    t: Union[float, Literal["open", "limit"], None] = None,
    kerf: Optional[float] = None,
    frames: Optional[int] = None,
    complete: bool = True,
    material: Optional[Literal["card", "felt", "pla"]] = None,
    hinge_mm: Optional[float] = None,
    kerf_mm: Optional[float] = None,
    thickness_mm: Optional[float] = None,
    margin_mm: Optional[float] = None,
    stroke_mm: Optional[float] = None,
    cut_colour: Optional[str] = None,
    score_colour: Optional[str] = None,
    engrave_colour: Optional[str] = None,
    labels: bool = False,
    gap_mm: Optional[float] = None,
    lamella_mm: Optional[float] = None,
    nozzle_mm: Optional[float] = None,
    creator: Optional[str] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
) -> Union[bytes, Dict[str, bytes]]:
    """A patch of a design in mm in one export format (bytes, or {name: bytes} for a folder).

    By default the one-DOF completion of the ``patch`` rectangle is written (the sheet that
    opens with the design's one motion; ``FiniteError`` when there is none);
    ``complete=False`` writes the rectangle as it is (the CLI's ``--raw``)."""

def export_formats() -> List[Dict[str, Optional[str]]]:
    """The export formats: name, description, extension, media_type, settings group."""


@final
class InverseResult:
    """An inverse-design run's result: per topology the screened and the refined design."""

    @property
    def target(self) -> str: ...
    @property
    def designs(self) -> List[Design]: ...
    @property
    def best(self) -> Optional[Design]: ...
    @property
    def objectives(self) -> List[float]: ...
    @property
    def seconds(self) -> float: ...
    @property
    def met(self) -> Optional[bool]:
        """Every goal naming a value within its tolerance (None: all ask for the most)."""
    @property
    def verdict(self) -> str:
        """The best design's verdict in one line."""
    def to_dict(self) -> Dict[str, Any]:
        """As ``isogami inverse --json`` prints it."""
    def __len__(self) -> int: ...

def inverse(
    target: Union[str, Mapping[str, Any]],
    database: Union[Database, str, PathLike[str]],
    *,
    top: int = 3,
    budget: int = 80,
    confirm: Optional[int] = None,
    triage: Optional[int] = None,
    samples: int = 0,
    kerf: Optional[float] = None,
    refine_kerf: bool = False,
    save: bool = False,
    progress: Optional[InverseProgress] = None,
    timeout: Optional[float] = None,
) -> InverseResult:
    """Designs with a target behaviour from a database, their tile shapes refined."""

def shape_mobility(design: DesignLike) -> Dict[str, Any]:
    """Generic or special: does one DOF survive shape changes; constraints and pinned parameters."""

def follow_shape(design: DesignLike, index: int, value: float) -> Design:
    """Parameter ``index`` moved to ``value``, the others adjusted to keep one DOF."""

def rank_drop_shape(design: DesignLike) -> Optional[Design]:
    """A shape of a rigid design's topology with exactly one DOF, or None."""

def param_ranges_of(design: DesignLike, kerf: float = 0.01) -> Optional[List[Dict[str, Any]]]:
    """Each shape parameter's valid interval, the others fixed (index, value, lo, hi,
    lo_open, hi_open, well_shaped, tol); None when the design does not build at that kerf."""

@final
class FiniteSheet:
    """A finite region of a design, its DOF with a free boundary, and its completion."""

    @property
    def design(self) -> str: ...
    @property
    def region(self) -> str: ...
    @property
    def t(self) -> float: ...
    @property
    def completed(self) -> bool: ...
    @property
    def tiles(self) -> IntArray: ...
    @property
    def joints(self) -> IntArray: ...
    @property
    def dof(self) -> int: ...
    @property
    def closed_dof(self) -> int: ...
    @property
    def raw_tiles(self) -> IntArray: ...
    @property
    def raw_dof(self) -> int: ...
    @property
    def raw_closed_dof(self) -> int: ...
    @property
    def floppy_tiles(self) -> List[IntArray]: ...
    @property
    def loose_tiles(self) -> IntArray: ...
    @property
    def covered_fraction(self) -> float: ...
    @property
    def removed(self) -> IntArray: ...
    @property
    def added(self) -> IntArray: ...
    def report(self) -> Dict[str, Any]: ...

@final
class SheetDeployment:
    """A finite sheet deployed with contact among its own tiles, beside the periodic sheet."""

    @property
    def sheet(self) -> FiniteSheet: ...
    @property
    def end_reason(self) -> str: ...
    @property
    def steps(self) -> int: ...
    @property
    def max_hull_area_ratio(self) -> float: ...
    @property
    def periodic_hull_area_ratio(self) -> float: ...
    @property
    def max_position_deviation(self) -> float: ...
    @property
    def max_angle_deviation(self) -> float: ...
    @property
    def one_dof_throughout(self) -> bool: ...
    @property
    def t(self) -> FloatArray: ...
    @property
    def step(self) -> IntArray: ...
    @property
    def hull_area_ratio(self) -> FloatArray: ...
    @property
    def stretches(self) -> FloatArray: ...
    @property
    def clearance(self) -> FloatArray: ...
    @property
    def poses(self) -> FloatArray: ...
    def report(self) -> Dict[str, Any]: ...

@final
class SheetPull:
    """A finite sheet pulled apart by two of its tiles, as a tester would."""

    @property
    def sheet(self) -> FiniteSheet: ...
    @property
    def dof(self) -> int: ...
    @property
    def grips(self) -> Tuple[int, int]: ...
    @property
    def end_reason(self) -> str: ...
    @property
    def steps(self) -> int: ...
    @property
    def final_extension(self) -> float: ...
    @property
    def max_hull_area_ratio(self) -> float: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def leaving(self) -> IntArray: ...
    @property
    def leaves(self) -> Optional[Dict[str, Any]]: ...
    @property
    def extension(self) -> FloatArray: ...
    @property
    def deviation(self) -> FloatArray: ...
    @property
    def periodic_t(self) -> FloatArray: ...
    @property
    def hull_area_ratio(self) -> FloatArray: ...
    @property
    def poses(self) -> FloatArray: ...
    def report(self) -> Dict[str, Any]: ...

def pull_sheet(
    design: DesignLike,
    region: str = "6x6",
    *,
    edge_mm: float = 20.0,
    t: float = 0.3,
    complete: bool = True,
    min_cover: float = 0.5,
    grips: Optional[IntPair] = None,
    frames: int = 24,
    settings: Optional[DeploySettings] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
    **overrides: Any,
) -> SheetPull:
    """The finite sheet (``complete=False``: the raw region) held by one tile and pulled apart by another."""

def finite_sheet(
    design: DesignLike,
    region: str = "6x6",
    *,
    edge_mm: float = 20.0,
    t: float = 0.3,
    complete: bool = True,
    min_cover: float = 0.5,
    settings: Optional[DeploySettings] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
    **overrides: Any,
) -> FiniteSheet:
    """A region of a design, its DOF with a free boundary and its completion to one DOF."""

def deploy_sheet(
    design: DesignLike,
    region: str = "6x6",
    *,
    edge_mm: float = 20.0,
    t: float = 0.3,
    complete: bool = True,
    min_cover: float = 0.5,
    frames: int = 24,
    settings: Optional[DeploySettings] = None,
    progress: Optional[Progress] = None,
    timeout: Optional[float] = None,
    **overrides: Any,
) -> SheetDeployment:
    """The (completed) finite sheet deployed with contact among its own tiles."""

@final
class GradedRun:
    """A graded sheet, how its optimisation went and whether it opens along one motion."""

    @property
    def design(self) -> str: ...
    @property
    def length_scale(self) -> float: ...
    @property
    def nodes(self) -> FloatArray: ...
    @property
    def tiles(self) -> IntArray: ...
    @property
    def tile_nodes(self) -> List[IntArray]: ...
    @property
    def joints(self) -> IntArray: ...
    @property
    def poses(self) -> FloatArray: ...
    @property
    def states(self) -> FloatArray: ...
    @property
    def closed(self) -> List[FloatArray]: ...
    @property
    def opened(self) -> List[FloatArray]: ...
    @property
    def target(self) -> FloatArray: ...
    @property
    def reached(self) -> bool: ...
    @property
    def max_outline_error(self) -> float: ...
    @property
    def joint_gap(self) -> float: ...
    @property
    def field_targets(self) -> FloatArray: ...
    @property
    def field_ratios(self) -> FloatArray: ...
    @property
    def field_cells(self) -> FloatArray: ...
    @property
    def max_field_error(self) -> Optional[float]: ...
    @property
    def passed(self) -> bool: ...
    def report(self) -> Dict[str, Any]: ...
    def path_check(self) -> Dict[str, Any]: ...
    def verdict(self) -> Optional[Dict[str, Any]]: ...
    def fit(self) -> Optional[Dict[str, Any]]: ...
    def to_json(self) -> str: ...
    def save(self, path: Union[str, PathLike[str]]) -> None: ...
    @overload
    def export(
        self,
        format: Literal["svg", "dxf", "fold", "obj", "tiles-csv", "tiles-json", "stl", "3mf"],
        *,
        edge_mm: Optional[float] = None,
        width_mm: Optional[float] = None,
        t: Union[float, Literal["open", "limit"], None] = None,
        frames: Optional[int] = None,
        material: Optional[Literal["card", "felt", "pla"]] = None,
        hinge_mm: Optional[float] = None,
        kerf_mm: Optional[float] = None,
        thickness_mm: Optional[float] = None,
        margin_mm: Optional[float] = None,
        stroke_mm: Optional[float] = None,
        cut_colour: Optional[str] = None,
        score_colour: Optional[str] = None,
        engrave_colour: Optional[str] = None,
        labels: bool = False,
        gap_mm: Optional[float] = None,
        lamella_mm: Optional[float] = None,
        nozzle_mm: Optional[float] = None,
        creator: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> bytes: ...
    @overload
    def export(
        self,
        format: Literal["kirigami-sim"],
        *,
        edge_mm: Optional[float] = None,
        width_mm: Optional[float] = None,
        t: Union[float, Literal["open", "limit"], None] = None,
        frames: Optional[int] = None,
        material: Optional[Literal["card", "felt", "pla"]] = None,
        hinge_mm: Optional[float] = None,
        kerf_mm: Optional[float] = None,
        thickness_mm: Optional[float] = None,
        margin_mm: Optional[float] = None,
        stroke_mm: Optional[float] = None,
        cut_colour: Optional[str] = None,
        score_colour: Optional[str] = None,
        engrave_colour: Optional[str] = None,
        labels: bool = False,
        gap_mm: Optional[float] = None,
        lamella_mm: Optional[float] = None,
        nozzle_mm: Optional[float] = None,
        creator: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Dict[str, bytes]: ...
    @overload
    def export(
        self,
        format: str,
        *,
        edge_mm: Optional[float] = None,
        width_mm: Optional[float] = None,
        t: Union[float, Literal["open", "limit"], None] = None,
        frames: Optional[int] = None,
        material: Optional[Literal["card", "felt", "pla"]] = None,
        hinge_mm: Optional[float] = None,
        kerf_mm: Optional[float] = None,
        thickness_mm: Optional[float] = None,
        margin_mm: Optional[float] = None,
        stroke_mm: Optional[float] = None,
        cut_colour: Optional[str] = None,
        score_colour: Optional[str] = None,
        engrave_colour: Optional[str] = None,
        labels: bool = False,
        gap_mm: Optional[float] = None,
        lamella_mm: Optional[float] = None,
        nozzle_mm: Optional[float] = None,
        creator: Optional[str] = None,
        timeout: Optional[float] = None,
    ) -> Union[bytes, Dict[str, bytes]]: ...

def graded(
    design: DesignLike,
    region: Union[IntPair, str] = (3, 3),
    target: str = "disc",
    t: Optional[float] = None,
    states: int = 8,
    iterations: int = 200,
    *,
    field: Union[Tuple[float, float], Tuple[float, float, float], Sequence[float], None] = None,
    tolerance: Optional[float] = None,
    fall_back: bool = True,
    progress: Optional[GradedProgress] = None,
    timeout: Optional[float] = None,
) -> GradedRun:
    """A design's finite sheet graded so that it opens into ``target`` (disc, ellipse:A,B,
    polygon:x,y;..., or @file.svg) or meets a field of area ratio (``target="field:FROM,TO[,DEGREES]"``
    or ``field=(from, to[, degrees])``), and the check that it opens along one motion. When
    that sheet does not open, the nearest sheet found that does (``fall_back``); the run's
    ``verdict()`` says whether it opens and meets the target within ``tolerance``."""

def load_graded(path: Union[str, PathLike[str]]) -> GradedRun:
    """The graded run ``GradedRun.save`` or ``isogami graded --out`` wrote."""
