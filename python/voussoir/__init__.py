"""voussoir: the seismic collapse multiplier of masonry arches and portals, from Python.

The horizontal ground acceleration ``lambda * g`` that turns an arch or portal of rigid
voussoirs with no-tension frictional joints into a mechanism: the static lower bound (a conic
program; the thrust line), the kinematic upper bound (mechanisms by virtual work), the
continuous model and a discrete element check. Every number comes from the Rust library
``voussoir`` through the same analysis layer as the command line, and the reports carry the
fields of its JSON contract (README.md of the repository, "JSON contract").

>>> import voussoir
>>> scene = voussoir.Scene.from_toml("data/semicircular.toml")
>>> r = voussoir.analyze(scene.with_values({"arch.thickness": 0.2}))
>>> r.status, r.lambda_lower                                   # doctest: +SKIP
('collapse', 0.2...)

Units are SI (m, N); angles in scene keys ending in ``_deg`` are degrees. The distribution is
``voussoir-arch`` on PyPI (``voussoir`` there is an unrelated project); the import name is
``voussoir``.
"""

from __future__ import annotations

import json
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _voussoir
from ._voussoir import (
    DERIVED_KEYS,
    KINEMATIC_DEFAULT_MAX_JOINTS,
    AnalysisError,
    Scene,
    SceneError,
    VoussoirError,
    __version__,
)

__all__ = [
    "Scene",
    "Report",
    "Result",
    "MinThicknessResult",
    "DemResult",
    "analyze",
    "min_thickness",
    "dem",
    "sweep",
    "sweep_frame",
    "VoussoirError",
    "SceneError",
    "AnalysisError",
    "DERIVED_KEYS",
    "KINEMATIC_DEFAULT_MAX_JOINTS",
    "__version__",
]


class Report:
    """A report of the JSON contract: every field is an attribute (``r.status``,
    ``r.lambda_lower``), ``r["field"]`` works too, and ``to_dict()`` gives the JSON object
    (a deep copy: the same dict ``voussoir ... --json`` prints, parsed)."""

    __slots__ = ("_data",)

    def __init__(self, data: Dict[str, Any]):
        object.__setattr__(self, "_data", data)

    def __getattr__(self, name: str) -> Any:
        try:
            return self._data[name]
        except KeyError:
            raise AttributeError(
                f"{type(self).__name__} has no field {name!r} (fields: {', '.join(self._data)})"
            ) from None

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is read-only")

    def __getitem__(self, name: str) -> Any:
        return self._data[name]

    def __contains__(self, name: object) -> bool:
        return name in self._data

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self._data))

    def keys(self):
        """The field names, in the JSON's order."""
        return self._data.keys()

    def to_dict(self) -> Dict[str, Any]:
        """The report as the JSON object the CLI prints (a fresh copy)."""
        return json.loads(json.dumps(self._data))

    def to_json(self, indent: Optional[int] = 2) -> str:
        """The report as JSON text."""
        return json.dumps(self._data, indent=indent)

    def __getstate__(self) -> Dict[str, Any]:
        return self._data

    def __setstate__(self, data: Dict[str, Any]) -> None:
        object.__setattr__(self, "_data", data)

    def __repr__(self) -> str:
        shown = ", ".join(
            f"{k}={self._data[k]!r}"
            for k in ("status", "outcome", "lambda_lower", "lambda_upper", "min_thickness", "lambda_dem")
            if k in self._data
        )
        return f"{type(self).__name__}({shown})"


def _float(x: Any) -> float:
    return np.nan if x is None else float(x)


class Result(Report):
    """The result of :func:`analyze`: the fields of ``voussoir analyze --json`` as attributes
    (``status``, ``lambda_lower``, ``lambda_upper``, ``gap``, ``hinges``, ``joints``,
    ``mechanism``, ...), and numpy views of the joints:

    - ``p1``, ``p2``: (joints, 2) joint ends (m): p1 the intrados or a pier's inner face;
    - ``thrust``: (joints, 2) thrust-line points (m), NaN without a collapse state;
    - ``forces``: (joints, 3) ``N, V, M`` per joint (N, N, N m), NaN without a collapse state;
    - ``eccentricity``: (joints,) ``e = M / N`` (m);
    - ``mechanism_array``: (blocks, 3) ``vx, vy, omega`` of the static collapse mechanism.
    """

    __slots__ = ()

    @property
    def p1(self) -> np.ndarray:
        return np.array([j["p1"] for j in self._data["joints"]], dtype=float).reshape(-1, 2)

    @property
    def p2(self) -> np.ndarray:
        return np.array([j["p2"] for j in self._data["joints"]], dtype=float).reshape(-1, 2)

    @property
    def thrust(self) -> np.ndarray:
        return np.array(
            [[_float(x) for x in (j["thrust"] or [None, None])] for j in self._data["joints"]],
            dtype=float,
        ).reshape(-1, 2)

    @property
    def forces(self) -> np.ndarray:
        return np.array(
            [[_float(j[k]) for k in ("N", "V", "M")] for j in self._data["joints"]], dtype=float
        ).reshape(-1, 3)

    @property
    def eccentricity(self) -> np.ndarray:
        return np.array([_float(j["e"]) for j in self._data["joints"]], dtype=float)

    @property
    def mechanism_array(self) -> np.ndarray:
        return np.array(self._data["mechanism"], dtype=float).reshape(-1, 3)


class MinThicknessResult(Report):
    """The result of :func:`min_thickness`: the fields of ``voussoir min-thickness --json``
    (``outcome``, ``min_thickness``, ``min_thickness_ratio``, ``hinges``, ``safety_factor``,
    ``min_thickness_kinematic``, ...)."""

    __slots__ = ()


class DemResult(Report):
    """The result of :func:`dem`: the fields of ``voussoir dem --json`` (``status``,
    ``lambda_stands``, ``lambda_collapses``, ``lambda_dem``, ``lambda_lower``,
    ``bracket_width``, ``runs``, ...)."""

    __slots__ = ()


def analyze(
    scene: Scene,
    direction: str = "right",
    continuous: bool = False,
    *,
    kinematic: str = "certified",
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
) -> Result:
    """The collapse multiplier of ``scene``: the static lower bound with its thrust line,
    hinges and mechanism, the kinematic upper bound, and with ``continuous=True`` the
    continuous model, as ``voussoir analyze --json`` reports them.

    ``direction``: ``"right"`` (+x) or ``"left"``. ``kinematic``: ``"certified"`` (the
    mechanism of the static hinges, falling back to a search) or ``"exhaustive"``;
    ``kinematic_max_joints`` bounds the exhaustive search (0 turns the kinematic analysis
    off). The GIL is released while the library solves. Raises :class:`SceneError` for a
    scene that cannot be built and :class:`AnalysisError` for a solver failure (physical
    answers such as ``cannot_stand`` are statuses, not errors).
    """
    text = _voussoir.analyze_json(
        scene, direction, continuous, kinematic, kinematic_max_joints
    )
    return Result(json.loads(text))


def min_thickness(
    scene: Scene,
    continuous: bool = False,
    *,
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
) -> MinThicknessResult:
    """The smallest arch thickness that stands under the permanent loads (lambda = 0), all
    else fixed, by the static program (bisection to 1e-9) and beside it the kinematic (and
    with ``continuous=True`` the continuous) minimum, as ``voussoir min-thickness --json``."""
    text = _voussoir.min_thickness_json(scene, continuous, kinematic_max_joints)
    return MinThicknessResult(json.loads(text))


def dem(scene: Scene, tolerance: float = 0.01) -> DemResult:
    """The collapse multiplier bracketed by discrete element runs (rigid blocks in time,
    no-tension Coulomb contacts) to a relative width ``tolerance``, starting from the static
    bound, as ``voussoir dem --json``. About a second per bundled scene."""
    return DemResult(json.loads(_voussoir.dem_json(scene, tolerance)))


VaryValues = Union[str, Sequence[Any], Any]


def sweep(
    scene: Scene,
    vary: Mapping[str, VaryValues],
    *,
    continuous: bool = False,
    dem: bool = False,
    kinematic: str = "certified",
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
    as_frame: bool = False,
):
    """A parametric sweep: every combination of the values in ``vary`` (dict order: the
    first key changes slowest), solved in parallel with the GIL released, as
    ``voussoir sweep`` does.

    Keys are scene keys (``"arch.thickness"``) or the ratios ``t/R``, ``e/R``, ``h/R``,
    ``b/R``, ``t/span``, ``rise/span``, ``e/span``. Values are a list, tuple, range or numpy
    array, a single value, or a string in the CLI's syntax (``"0.1,0.15"`` or
    ``"0.1:0.2:0.01"``, STOP included).

    Returns a list of dicts, one per case, with the columns of the CLI's CSV: the varied
    keys, ``status, lambda_lower, lambda_upper, gap, hinges, solve_time_s`` (plus
    ``lambda_continuous`` with ``continuous``, ``lambda_dem, dem_time_s`` with ``dem``), the
    ratios not varied, and ``error`` (missing numbers are None). Invalid cases stay as rows
    with status ``"error"``; unknown keys and values of the wrong type raise
    :class:`SceneError` before anything is solved. With ``as_frame=True``, a
    ``pandas.DataFrame`` (pandas must be installed).
    """
    rows = _voussoir.sweep_rows(
        scene, dict(vary), continuous, dem, kinematic, kinematic_max_joints
    )
    if as_frame:
        return _frame(rows)
    return rows


def sweep_frame(scene: Scene, vary: Mapping[str, VaryValues], **options: Any):
    """:func:`sweep` as a ``pandas.DataFrame`` (needs pandas)."""
    return sweep(scene, vary, as_frame=True, **options)


def _frame(rows: List[Dict[str, Any]]):
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "as_frame=True needs pandas: pip install pandas (or voussoir-arch[pandas])"
        ) from e
    return pd.DataFrame.from_records(rows)
