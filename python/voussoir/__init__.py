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
import os
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
    "RetrofitResult",
    "AssessResult",
    "DynamicResult",
    "IdaResult",
    "PulseCurveResult",
    "HandInReport",
    "FragilityResult",
    "analyze",
    "roll",
    "RollResult",
    "min_thickness",
    "retrofit",
    "dem",
    "assess",
    "report",
    "fragility",
    "dem_dynamic",
    "dem_ida",
    "dem_pulse_curve",
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
    (a deep copy: the same dict ``voussoir ... --json`` prints, parsed). Results that have a
    picture show it inline in Jupyter (``_repr_svg_``): the library draws it again from the
    same scene and options on first display (a report rebuilt from a pickle has none)."""

    __slots__ = ("_data", "_drawer", "_svg")

    def __init__(self, data: Dict[str, Any], drawer: Optional[Any] = None):
        object.__setattr__(self, "_data", data)
        object.__setattr__(self, "_drawer", drawer)
        object.__setattr__(self, "_svg", None)

    def _repr_svg_(self) -> Optional[str]:
        """The result's drawing as SVG text (Jupyter's inline picture), None without one."""
        drawer = object.__getattribute__(self, "_drawer") if _has_slot(self, "_drawer") else None
        if drawer is None:
            return None
        if object.__getattribute__(self, "_svg") is None:
            object.__setattr__(self, "_svg", drawer())
        return object.__getattribute__(self, "_svg")

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
        object.__setattr__(self, "_drawer", None)
        object.__setattr__(self, "_svg", None)

    def __repr__(self) -> str:
        shown = ", ".join(
            f"{k}={self._data[k]!r}"
            for k in ("status", "outcome", "lambda_lower", "lambda_non_associative",
                      "lambda_upper", "min_thickness",
                      "lambda_dem", "governing", "passes", "verdict", "scale_collapses",
                      "friction_exact")
            if k in self._data
        )
        # Exact in a wall: a collapse state of real joints, not proved the lowest.
        if self._data.get("friction_lower_states_possible"):
            shown += ", friction_lower_states_possible=True"
        # With joints that slip at collapse, lambda_lower is the associative multiplier, an
        # upper bound of the real collapse multiplier: say so in words (docs/friction.md).
        note = self._data.get("friction_note")
        if note:
            shown += f", friction_note={note!r}"
        return f"{type(self).__name__}({shown})"


def _has_slot(obj: Any, name: str) -> bool:
    try:
        object.__getattribute__(obj, name)
        return True
    except AttributeError:
        return False


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

    With finite friction ``friction_exact`` says whether ``lambda_lower`` is exact: when joints
    slip in the static mechanism it is False, and ``lambda_lower`` (= ``lambda_associative``) is
    the multiplier of associative friction, an upper bound of the real (non-associative)
    collapse multiplier, not a safe lower bound; ``friction_note`` says so in words, and so
    does ``repr(result)``. ``friction_lower_states_possible`` is True when it is exact in an
    assembly that is not a chain (a wall), where real joints may still collapse lower: the
    non-associative iteration then runs by default (docs/friction.md).
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


class RetrofitResult(Report):
    """The result of :func:`retrofit`: the fields of ``voussoir retrofit --json``
    (``target_lambda``, ``feasible``, ``ties`` with each designed tie's ``capacity_required``,
    ``needed`` and ``bar``, ``not_needed``, ``reinforcements`` with each designed strip's
    ``capacity_required`` (its debonding force at each joint it crosses), ``needed``,
    ``reinforcements_not_needed``, ``lambda_lower``, ``best_reachable_lambda``, ``analyses``:
    the retrofitted structure analysed in each direction; ``site``: the verdict of a design
    for a site, None for a target multiplier)."""

    __slots__ = ()


def retrofit(
    scene: Scene,
    target_lambda: Optional[float] = None,
    *,
    site: Optional[Mapping[str, Any]] = None,
) -> RetrofitResult:
    """The smallest capacities of the scene's ties marked ``capacity = "design"`` and strips
    (``[[reinforcements]]``) marked ``tensile_capacity = "design"`` for which the structure
    carries ``target_lambda`` (both directions of a seismic action), the smallest standard
    steel bar for each tie, and the structure analysed again with them, as ``voussoir
    retrofit --target-lambda L --json`` (docs/retrofit.md). An unreachable target gives
    ``feasible = False`` and ``best_reachable_lambda``.

    Without ``target_lambda``, the least capacities whose structure passes the NTC 2018 check
    of :func:`assess` at the scene's ``[site]``, as ``voussoir retrofit --site KEY=VALUE
    --json``; ``site``: keys of the ``[site]`` table to set over the scene's own, as in
    :func:`assess` (``{"ag": 0.25, "soil": "B", "F0": 2.4, "Tc_star": 0.3}``). The result's
    ``site`` holds the verdict (``passes``, ``lambda_needed``, ``assessment``). Giving both
    ``target_lambda`` and ``site`` raises :class:`ValueError`, as the command line refuses
    both flags; a site design of a scene with strips raises :class:`AnalysisError` (the
    assessment does not follow strips)."""
    if target_lambda is not None and site:
        raise ValueError(
            "retrofit: give target_lambda or site, not both (a design reaches a multiplier, "
            "or passes at a site)"
        )
    if site:
        scene = scene.with_values({f"site.{k}": v for k, v in site.items()})
    return RetrofitResult(json.loads(_voussoir.retrofit_json(scene, target_lambda)))


class DemResult(Report):
    """The result of :func:`dem`: the fields of ``voussoir dem --json`` (``status``,
    ``lambda_stands``, ``lambda_collapses``, ``lambda_dem``, ``lambda_lower``,
    ``bracket_width``, ``runs``, ...)."""

    __slots__ = ()


def analyze(
    scene: Scene,
    direction: Optional[str] = None,
    continuous: bool = False,
    *,
    kinematic: str = "certified",
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
    friction: str = "auto",
) -> Result:
    """The collapse multiplier of ``scene``: the static lower bound with its thrust line,
    hinges and mechanism, the kinematic upper bound, and with ``continuous=True`` the
    continuous model, as ``voussoir analyze --json`` reports them.

    ``direction``: ``"right"`` (+x, the default) or ``"left"``; a scene whose ``[action]``
    is ``"live"`` (lambda the adequacy factor of its live loads) has no direction, and giving
    one raises :class:`AnalysisError` (``kind = "not_for_action"``), as ``--direction`` does.
    ``kinematic``: ``"certified"`` (the
    mechanism of the static hinges, falling back to a search), ``"exhaustive"`` or
    ``"general"`` (the general kinematic program, which assemblies that are not chains always
    get: ``docs/kinematic.md``);
    ``kinematic_max_joints`` bounds the exhaustive search (0 turns the kinematic analysis
    off). ``friction``: ``"auto"`` (the non-associative multiplier, ``lambda_non_associative``,
    whenever joints slide in the static mechanism), ``"associative"`` (the static program's
    alone) or ``"non-associative"`` (always), as ``--friction`` (docs/friction.md);
    ``lambda_governing`` is the one that governs. The GIL is released while the library
    solves. Raises :class:`SceneError` for a scene that cannot be built and
    :class:`AnalysisError` for a solver failure or an unknown ``friction`` (physical answers
    such as ``cannot_stand`` are statuses, not errors).
    """
    args = (scene, direction, continuous, kinematic, kinematic_max_joints, friction)
    text = _voussoir.analyze_json(*args)
    return Result(json.loads(text), lambda: _voussoir.analysis_svg(*args))


class RollResult(Result):
    """The result of :func:`roll`: the fields of ``voussoir analyze --roll ... --json``, the
    analysis at the critical position (``lambda_lower``, ``hinges``, ``mechanism``, ...), and
    ``roll``: ``target``, ``positions``, ``status``, ``lambda_lower``, ``lambda_upper`` (one per
    position), ``critical_position`` (refined by golden section) and
    ``critical_grid_position``. ``chart_svg`` is the chart of ``--roll-svg`` (both bounds
    against the position)."""

    __slots__ = ("chart_svg",)

    def __init__(self, data: dict, svg, chart_svg: str) -> None:
        super().__init__(data, svg)
        object.__setattr__(self, "chart_svg", chart_svg)


def roll(
    scene: Scene,
    target: str,
    start: float,
    stop: float,
    step: float,
    direction: Optional[str] = None,
    *,
    kinematic: str = "certified",
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
    friction: str = "auto",
) -> RollResult:
    """A moving load, as ``voussoir analyze SCENE --roll TARGET --from START --to STOP --step
    STEP``: ``target`` is ``"loads[K]"`` (a point load standing on the top at each position,
    or a line load by its ``from_x``) or ``"vehicles[K]"`` (by its first axle); both bounds
    at every position, the critical position refined and analysed again (docs/geometry.md,
    "Moving loads"). The other arguments are :func:`analyze`'s. Raises :class:`AnalysisError`
    for a bad range or target and :class:`SceneError` for a load off the structure."""
    text, drawing, chart = _voussoir.roll_json(
        scene, target, start, stop, step, direction, kinematic, kinematic_max_joints, friction
    )
    return RollResult(json.loads(text), lambda: drawing, chart)


def min_thickness(
    scene: Scene,
    continuous: bool = False,
    *,
    kinematic_max_joints: int = KINEMATIC_DEFAULT_MAX_JOINTS,
    friction: str = "auto",
) -> MinThicknessResult:
    """The smallest arch thickness that stands under the permanent loads (lambda = 0), all
    else fixed, by the static program (bisection to 1e-9) and beside it the kinematic (and
    with ``continuous=True`` the continuous) minimum, as ``voussoir min-thickness --json``;
    ``friction="non-associative"`` adds ``min_thickness_non_associative`` (joints that slide
    without opening, docs/friction.md)."""
    text = _voussoir.min_thickness_json(scene, continuous, kinematic_max_joints, friction)
    return MinThicknessResult(json.loads(text))


def dem(scene: Scene, tolerance: float = 0.01, *, from_static: bool = False) -> DemResult:
    """The collapse multiplier bracketed by discrete element runs (rigid blocks in time,
    no-tension Coulomb contacts) to a relative width ``tolerance``, as ``voussoir dem --json``
    (``from_static=True``: ``--from-static``, the search starts at the static bound). About a
    second per bundled scene. Ctrl-C raises ``KeyboardInterrupt`` at once."""
    return DemResult(json.loads(_voussoir.dem_json(scene, tolerance, from_static)))


class AssessResult(Report):
    """The result of :func:`assess`: the fields of ``voussoir assess --json``. The top-level
    fields (``passes``, ``verdict``, ``alpha0``, ``a0_star``, ``du_star``, ``linear_check``,
    ``nonlinear_check``, ``ag_max``, ``capacity_curve``, ...) are the governing direction's
    (``governing``: ``"right"`` or ``"left"``); ``directions["right"]`` and
    ``directions["left"]`` hold each direction in full. ``passes`` applies the code's rule
    (either check satisfied, ``rule``), over every direction assessed.

    - ``curve``: (points, 5) array of the governing capacity curve, columns ``rotation``
      (rad), ``d_k`` (m), ``alpha``, ``d_star`` (m), ``a_star`` (m/s^2);
      ``curve_of("left")`` the same for one direction;
    - ``svg("capacity")`` / ``svg("adrs")``: the charts of ``--svg`` / ``--adrs-svg``; in
      Jupyter the ADRS plot shows inline.
    """

    __slots__ = ()

    _COLUMNS = ("rotation", "d_k", "alpha", "d_star", "a_star")

    @staticmethod
    def _curve(points: List[Dict[str, float]]) -> np.ndarray:
        return np.array(
            [[p[c] for c in AssessResult._COLUMNS] for p in points], dtype=float
        ).reshape(-1, len(AssessResult._COLUMNS))

    @property
    def curve(self) -> np.ndarray:
        return self._curve(self._data["capacity_curve"])

    def curve_of(self, direction: str) -> np.ndarray:
        """The capacity curve of ``direction`` (``"right"`` or ``"left"``), if assessed."""
        try:
            return self._curve(self._data["directions"][direction]["capacity_curve"])
        except KeyError:
            raise KeyError(
                f"direction {direction!r} was not assessed (assessed: "
                f"{', '.join(self._data['directions'])})"
            ) from None

    def svg(self, which: str = "adrs") -> str:
        """A chart as SVG text: ``"capacity"`` (the capacity curves) or ``"adrs"``."""
        drawer = object.__getattribute__(self, "_drawer") if _has_slot(self, "_drawer") else None
        if drawer is None:
            raise ValueError("this result has no scene to draw (rebuilt from a pickle?)")
        return drawer(which)

    def _repr_svg_(self) -> Optional[str]:
        drawer = object.__getattribute__(self, "_drawer") if _has_slot(self, "_drawer") else None
        if drawer is None:
            return None
        if object.__getattribute__(self, "_svg") is None:
            object.__setattr__(self, "_svg", drawer("adrs"))
        return object.__getattribute__(self, "_svg")


def assess(
    scene: Scene,
    site: Optional[Mapping[str, Any]] = None,
    direction: Optional[str] = None,
    *,
    points: int = 200,
    control_block: Optional[int] = None,
    incremental: bool = False,
) -> AssessResult:
    """The seismic assessment of the governing mechanism (NTC 2018 / Circolare 2019 C8.7.1,
    docs/assessment.md), as ``voussoir assess --json``: both directions of the load, the worse
    governing, or only ``direction`` (``"right"`` or ``"left"``, as ``--direction``).

    ``site``: keys of the ``[site]`` table to set (``{"ag": 0.25, "soil": "B", "F0": 2.4,
    "Tc_star": 0.3}``, or ``{"latitude": 42.35, "longitude": 13.4, "soil": "B"}`` for the
    values of the national hazard grid there, as ``--site KEY=VALUE``) over the scene's own.
    ``points``, ``control_block`` and ``incremental`` as ``--points``, ``--control-block`` and
    ``--incremental``. Raises :class:`AnalysisError`
    when a direction has no mechanism with a capacity curve (the message says why)."""
    if site:
        scene = scene.with_values({f"site.{k}": v for k, v in site.items()})
    text = _voussoir.assess_json(scene, direction, points, control_block, incremental)
    return AssessResult(
        json.loads(text),
        lambda which: _voussoir.assess_svg(
            scene, which, direction, points, control_block, incremental
        ),
    )


class FragilityResult(Report):
    """The result of :func:`fragility`: the fields of ``voussoir fragility --json``
    (``median`` and ``beta`` of the lognormal fit with ``median_bounds``, ``beta_bounds`` at
    ``confidence``, ``samples``: one row per sample with its ``values``, ``outcome`` and
    ``ag_capacity``, ...), ``capacities``, the samples' capacities (g) as an array (NaN where
    a sample has none), and ``svg``, the chart of ``--svg`` (the fitted curve over the
    samples), which Jupyter shows inline."""

    __slots__ = ("svg",)

    def __init__(self, data: Dict[str, Any], svg: str):
        super().__init__(data)
        object.__setattr__(self, "svg", svg)

    @property
    def capacities(self) -> np.ndarray:
        return np.array([_float(s["ag_capacity"]) for s in self._data["samples"]], dtype=float)

    def _repr_svg_(self) -> Optional[str]:
        return object.__getattribute__(self, "svg") if _has_slot(self, "svg") else None


def fragility(
    scene: Scene,
    samples: int = 100,
    site: Optional[Mapping[str, Any]] = None,
    *,
    seed: int = 1,
    records: Optional[Union[str, os.PathLike[str]]] = None,
    stripes: Optional[Sequence[float]] = None,
    client: Any = None,
    progress: bool = True,
    chunk: Optional[int] = None,
) -> FragilityResult:
    """The fragility curve of ``scene`` by the capacity route, as ``voussoir fragility
    --json`` (docs/fragility.md): ``samples`` Latin hypercube samples of its ``[uncertain]``
    inputs from ``seed`` (the same seed, the same samples and curve), each sample's capacity
    the largest ``ag`` its NTC 2018 nonlinear kinematic check passes (the worse direction,
    the site's other parameters held), and a lognormal fitted by maximum likelihood with
    confidence bounds. ``site``: keys of the ``[site]`` table to set, as in :func:`assess`.
    ``records`` (a directory of ``.AT2`` records) and ``stripes`` (peak ground accelerations
    in g) run the dynamic route instead, as ``--records DIR --stripes ...``: each sample in
    the DEM under each record scaled to each stripe, the lognormal fitted to the counts of
    collapse. Raises :class:`AnalysisError` for a sample outside a key's range (samples are
    refused, not truncated), a capacity route without a site, or only one of ``records``
    and ``stripes``.

    With ``client`` (a ``dask.distributed.Client``) the work runs on its cluster in chunks,
    as :func:`sweep`'s cases do (the first ones locally to measure their cost, the rest in
    chunks sized so the per-task overhead stays under 10 %, or of ``chunk`` cases; a
    progress bar unless ``progress=False``), and the fit is made here from all of them: the
    same samples, curve and fit as the local run. A case is a sample in the capacity route
    and one DEM run (a sample under one record at one stripe) in the dynamic route, whose
    samples cost tens of runs each and would balance poorly over the workers; there the
    client runs no pilot, a chunk is one run, and ``chunk`` counts runs, not samples (it
    counted samples before issue 30's run chunks). Every sample's scene is checked on the
    client first. ``records`` must then be a directory the workers can read at the same
    path."""
    if site:
        scene = scene.with_values({f"site.{k}": v for k, v in site.items()})
    records_dir = None if records is None else str(records)
    pgas = None if stripes is None else [float(x) for x in stripes]
    chunks = None
    if client is not None:
        from . import _dask

        done, _ = _dask.fragility(
            client, scene, samples, seed, records_dir, pgas, progress=progress, chunk=chunk
        )
        chunks = [json.dumps(done)]
    text, svg = _voussoir.fragility_json_svg(scene, samples, seed, records_dir, pgas, chunks)
    return FragilityResult(json.loads(text), svg)


class HandInReport(Report):
    """The result of :func:`report`: ``html``, the hand-in report as one self-contained HTML
    page (what ``voussoir report -o FILE`` writes), and the fields of ``voussoir report
    --json`` (``analysis``, ``min_thickness``, ``assessment``, ``sensitivity``,
    ``scene_sha256``, ``voussoir_version``, ...). ``save(path)`` writes the page; Jupyter shows
    it inline."""

    __slots__ = ("html",)

    def __init__(self, data: Dict[str, Any], html: str):
        super().__init__(data)
        object.__setattr__(self, "html", html)

    def save(self, path: Union[str, os.PathLike[str]]) -> None:
        """Write the page (UTF-8) to ``path``; print it to PDF with a browser, or with
        ``voussoir report --pdf``."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.html)

    def _repr_html_(self) -> str:
        return self.html

    def __getstate__(self) -> Dict[str, Any]:
        return {"data": self._data, "html": self.html}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        super().__setstate__(state["data"])
        object.__setattr__(self, "html", state["html"])


def report(
    scene: Scene,
    site: Optional[Mapping[str, Any]] = None,
    *,
    dem: bool = False,
) -> HandInReport:
    """The hand-in report of ``scene`` (docs/report.md), as ``voussoir report``: the
    structure, the method, both bounds, the minimum thickness, the seismic check when the
    scene has a ``[site]`` (``site``: keys to set over it, as ``--site KEY=VALUE``), the
    sensitivity to the thickness and the friction (-10 % / +10 %) and what reproduces it.
    ``dem=True`` adds the DEM's bracket (``--dem``). The page quotes and hashes the scene as
    ``scene.to_toml()`` writes it. Raises :class:`SceneError` or :class:`AnalysisError` as
    :func:`analyze` does; what cannot be computed for a scene (an assessment of a structure
    that cannot stand) is said in the page and in ``assessment_note``."""
    if site:
        scene = scene.with_values({f"site.{k}": v for k, v in site.items()})
    html, text = _voussoir.report_html_json(scene, dem)
    return HandInReport(json.loads(text), html)


class DynamicResult(Report):
    """The result of :func:`dem_dynamic`: the fields of ``voussoir dem --record/--pulse
    --json`` (``status``, ``excitation``, ``pga``, ``collapse_time``, ``peak_displacement``,
    ``peak_rotation``, ``residual_displacement``, ...) and ``history``, the control block's
    time history (``--history``) as numpy arrays: ``time`` (s), ``ground_acceleration``
    (m/s^2), ``displacement`` (m), ``rotation`` (rad), ``ground_acceleration_vertical``."""

    __slots__ = ("history",)

    def __init__(self, data: Dict[str, Any], history: Optional[Dict[str, np.ndarray]] = None):
        super().__init__(data)
        object.__setattr__(self, "history", history or {})

    def __getstate__(self) -> Dict[str, Any]:
        return {"data": self._data, "history": self.history}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        super().__setstate__(state["data"])
        object.__setattr__(self, "history", state["history"])


class IdaResult(Report):
    """The result of :func:`dem_ida`: the fields of ``voussoir dem --ida --json``
    (``scale_survives``, ``scale_collapses``, ``collapse_pga``, ``runs``, ...)."""

    __slots__ = ()


class PulseCurveResult(Report):
    """The result of :func:`dem_pulse_curve`: the fields of ``voussoir dem --pulse-curve
    --json`` (``points``: ``shape``, ``period``, ``amplitude_survives``,
    ``amplitude_collapses``, ``runs``)."""

    __slots__ = ()


_HISTORY = ("time", "ground_acceleration", "displacement", "rotation",
            "ground_acceleration_vertical")


def _ground_args(record, pulse, amplitude, period, units, dt, scale, component, record_vertical):
    return (
        None if record is None else str(record),
        pulse,
        None if amplitude is None else float(amplitude),
        None if period is None else float(period),
        units,
        None if dt is None else float(dt),
        float(scale),
        component,
        None if record_vertical is None else str(record_vertical),
    )


def dem_dynamic(
    scene: Scene,
    record: Optional[Any] = None,
    pulse: Optional[str] = None,
    amplitude: Optional[float] = None,
    period: Optional[float] = None,
    *,
    units: str = "g",
    dt: Optional[float] = None,
    scale: float = 1.0,
    component: str = "x",
    record_vertical: Optional[Any] = None,
    tail: float = 2.0,
) -> DynamicResult:
    """Run the scene's blocks under a ground motion, as ``voussoir dem --json`` with
    ``--record FILE`` (PEER NGA .AT2 in g, or one/two-column text or CSV in ``units``; ``dt``
    for one column) or ``--pulse sine|rect --amplitude A --period T`` (``amplitude`` in
    ``units``: ``"g"``, ``"m/s2"`` or ``"cm/s2"``). ``scale`` multiplies the motion,
    ``component`` is ``"x"`` (horizontal) or ``"y"`` (vertical), ``record_vertical`` a vertical
    record acting together with the horizontal one, ``tail`` the free motion after the ground
    stops (s). Ctrl-C raises ``KeyboardInterrupt`` at once."""
    text, columns = _voussoir.dem_dynamic_json(
        scene,
        *_ground_args(record, pulse, amplitude, period, units, dt, scale, component,
                      record_vertical),
        float(tail),
        False,
        0.01,
    )
    history = {k: np.asarray(c, dtype=float) for k, c in zip(_HISTORY, columns or [])}
    return DynamicResult(json.loads(text), history)


def dem_ida(
    scene: Scene,
    record: Optional[Any] = None,
    pulse: Optional[str] = None,
    amplitude: Optional[float] = None,
    period: Optional[float] = None,
    *,
    tolerance: float = 0.01,
    units: str = "g",
    dt: Optional[float] = None,
    scale: float = 1.0,
    component: str = "x",
    record_vertical: Optional[Any] = None,
    tail: float = 2.0,
) -> IdaResult:
    """Scale a ground motion (as :func:`dem_dynamic`) up until the blocks collapse, to a
    relative ``tolerance``, as ``voussoir dem --ida --json``."""
    text, _ = _voussoir.dem_dynamic_json(
        scene,
        *_ground_args(record, pulse, amplitude, period, units, dt, scale, component,
                      record_vertical),
        float(tail),
        True,
        float(tolerance),
    )
    return IdaResult(json.loads(text))


def dem_pulse_curve(
    scene: Scene,
    periods: Optional[Sequence[float]] = None,
    shapes: Optional[Sequence[str]] = None,
    *,
    tail: float = 2.0,
    tolerance: float = 0.01,
) -> PulseCurveResult:
    """The minimum amplitude of one-cycle pulses (``shapes``: ``"sine"``, ``"rect"``) that
    brings the blocks down, at each of ``periods`` (s), as ``voussoir dem --pulse-curve
    --json`` (the CLI's defaults when None)."""
    text = _voussoir.dem_pulse_curve_json(
        scene,
        [float(t) for t in (periods or [])],
        list(shapes or []),
        float(tail),
        float(tolerance),
    )
    return PulseCurveResult(json.loads(text))


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
    client: Any = None,
    progress: bool = True,
    chunk: Optional[int] = None,
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

    With ``client`` (a ``dask.distributed.Client``) the cases run on its cluster: the first
    ones locally to measure a case's cost, the rest in chunks sized so that the scheduler's
    per-task overhead, measured on the client, stays under 10 % of a chunk's time (or of
    ``chunk`` cases when given); the rows stream back with a progress bar (tqdm's when
    installed; ``progress=False`` hides it) and are returned in the local sweep's order, the
    same rows (docs/python.md, "Scaling a study out with Dask").
    """
    options = (continuous, dem, kinematic, kinematic_max_joints)
    if client is not None:
        from . import _dask

        rows, _ = _dask.sweep(client, scene, dict(vary), options, progress=progress, chunk=chunk)
    else:
        rows = _voussoir.sweep_rows(scene, dict(vary), *options)
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
