"""isogami: rigid-deployable kirigami sheets from isohedral tilings.

The Rust library from Python: tiling families and cells, designs (from a name, a spec
string, design JSON or keyword arguments), mobility (DOF, spectrum, first-order motions),
deployment with every method and setting (numpy arrays per frame), expansion measures and
the behaviour class, linkages, the baseline comparison, and design databases queried with
the browser's filters. Long calls release the GIL and can be interrupted with Ctrl-C.

>>> import isogami
>>> run = isogami.deploy("rotating-squares")
>>> round(float(run.area_ratio.max()), 3)     # the squares turn by 45°: (cos + sin)² = 2
2.0
>>> run.behaviour
'isotropic_auxetic'

Main entry points: ``design``, ``families``/``family``, ``cell``, ``analyze``, ``deploy``
(with ``DeploySettings``), ``linkages``, ``compare``, ``open_database`` (with ``Query``),
``export`` (``export_formats``), ``inverse`` (inverse design on a database), ``shape_mobility`` / ``follow_shape`` /
``rank_drop_shape`` / ``param_ranges_of`` (shape-aware mobility, each parameter's valid range), ``finite_sheet`` / ``deploy_sheet`` / ``pull_sheet`` (finite sheets: a region's
degrees of freedom, its completion to one DOF and its deployment), ``graded`` / ``load_graded``
(graded sheets: tiles each shaped so that the sheet opens into a target outline, typed in or
drawn in an SVG file) and the measure functions (``polar``, ``principal_expansions``, ``expansion_profile``, ...).
Every library error is an ``IsogamiError`` subclass carrying the library's message.
"""

from ._isogami import (
    COMPARISON_DESIGNS,
    DEPLOY_SETTINGS,
    NAMED_DESIGNS,
    SAMPLE_OPENING_DESIGNS,
    Analysis,
    CancelledError,
    Cell,
    CellError,
    Comparison,
    ContactError,
    Database,
    DeployError,
    Deployment,
    DeploySettings,
    Design,
    DesignError,
    ExploreError,
    ExportError,
    FiniteError,
    FiniteSheet,
    GradedRun,
    InverseError,
    InverseResult,
    ShapeError,
    Family,
    IsogamiError,
    KinematicsError,
    LinkageError,
    Linkages,
    MeasureError,
    MethodResult,
    MobilityError,
    Motion,
    Query,
    QueryError,
    Record,
    SettingsError,
    SheetDeployment,
    SheetPull,
    StoredDesign,
    StoreError,
    TilingError,
    __version__,
    analyze,
    area_ratio,
    cell,
    compare,
    deformation_gradient,
    deploy,
    deploy_sheet,
    pull_sheet,
    design,
    directional_expansion,
    expansion_profile,
    export,
    export_formats,
    finite_sheet,
    graded,
    load_graded,
    inverse,
    follow_shape,
    param_ranges_of,
    rank_drop_shape,
    shape_mobility,
    families,
    family,
    linkages,
    open_database,
    poisson_ratio,
    polar,
    principal_direction,
    principal_expansions,
)

__all__ = [
    "COMPARISON_DESIGNS",
    "DEPLOY_SETTINGS",
    "NAMED_DESIGNS",
    "SAMPLE_OPENING_DESIGNS",
    "Analysis",
    "CancelledError",
    "Cell",
    "CellError",
    "Comparison",
    "ContactError",
    "Database",
    "DeployError",
    "Deployment",
    "DeploySettings",
    "Design",
    "DesignError",
    "ExploreError",
    "ExportError",
    "FiniteError",
    "FiniteSheet",
    "GradedRun",
    "InverseError",
    "InverseResult",
    "ShapeError",
    "Family",
    "IsogamiError",
    "KinematicsError",
    "LinkageError",
    "Linkages",
    "MeasureError",
    "MethodResult",
    "MobilityError",
    "Motion",
    "Query",
    "QueryError",
    "Record",
    "SettingsError",
    "SheetDeployment",
    "SheetPull",
    "StoredDesign",
    "StoreError",
    "TilingError",
    "__version__",
    "analyze",
    "area_ratio",
    "cell",
    "compare",
    "deformation_gradient",
    "deploy",
    "deploy_sheet",
    "pull_sheet",
    "design",
    "directional_expansion",
    "expansion_profile",
    "export",
    "export_formats",
    "finite_sheet",
    "graded",
    "load_graded",
    "inverse",
    "follow_shape",
    "param_ranges_of",
    "rank_drop_shape",
    "shape_mobility",
    "families",
    "family",
    "linkages",
    "open_database",
    "poisson_ratio",
    "polar",
    "principal_direction",
    "principal_expansions",
]


def _rebuild(name, args, kwargs):
    """Unpickling a value (a design, family, cell, settings, record...): the constructor call
    ``isogami.<name>(*args, **kwargs)`` that makes it, which computes nothing (``name`` may be
    dotted: ``"Record._from_json"``)."""
    target = globals()[name.split(".")[0]]
    for part in name.split(".")[1:]:
        target = getattr(target, part)
    return target(*args, **kwargs)


def _restore(cls, tag, data, arrays):
    """Unpickling a computed result from its pickled data (``tag`` names the layout; another
    layout than this version's raises ``pickle.UnpicklingError``). Computes nothing."""
    from . import _isogami

    return _isogami._restore(cls, tag, data, arrays)
