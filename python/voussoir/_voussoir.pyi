"""Type stubs of the native module ``voussoir._voussoir`` (Rust, PyO3). Use the package
``voussoir``: it wraps these functions into result objects."""

from os import PathLike
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

__version__: str
DERIVED_KEYS: List[str]
KINEMATIC_DEFAULT_MAX_JOINTS: int

class VoussoirError(Exception):
    """Base class of every error voussoir raises."""

class SceneError(VoussoirError):
    """A problem with a scene: its file, a key, a value, or a varied key. The message is the
    command line's."""

    kind: str
    """io, syntax, unknown_key, missing_key, wrong_type, out_of_range, bad_override,
    bad_variation, bad_chart or usage."""
    origin: Optional[str]
    """The scene's file or source (``<dict>``, ``<string>``), when the error has one."""
    key: Optional[str]
    """The dotted scene key (``arch.thickness``) or varied key, when the error has one."""
    value: Optional[str]
    """The offending value as text, when the error has one."""

class AnalysisError(VoussoirError):
    """A failure of an analysis that is not a physical answer."""

    kind: str
    """solver_setup, solver_failed, assembly, record (a ground-motion record) or other."""

class Scene:
    """A validated scene (the TOML format of docs/geometry.md). Immutable; pickles."""

    @staticmethod
    def from_toml(path: Union[str, PathLike[str]]) -> Scene:
        """Read and validate a scene file."""
    @staticmethod
    def from_toml_str(text: str, origin: str = "<string>") -> Scene:
        """Parse and validate a scene from TOML text."""
    @staticmethod
    def from_dict(d: Mapping[str, Any], origin: str = "<dict>") -> Scene:
        """Validate a scene given as a dict of its TOML tables."""
    def with_values(self, values: Mapping[str, Any]) -> Scene:
        """A copy with dotted keys (or the sweep's ratios) set together, validated once."""
    def to_dict(self) -> Dict[str, Any]:
        """The scene as a dict of its TOML tables."""
    def to_toml(self) -> str:
        """The scene as TOML text."""
    @property
    def origin(self) -> str: ...
    @property
    def thickness(self) -> float | None: ...
    @property
    def voussoirs(self) -> int | None: ...
    @property
    def span(self) -> float: ...
    @property
    def rise(self) -> float: ...
    def ratios(self) -> Dict[str, float]:
        """The dimensionless ratios (t/R, t/span, ...); NaN where not defined."""
    def __reduce__(self) -> Tuple[Any, Tuple[str, str]]: ...
    def _repr_svg_(self) -> str:
        """The scene drawn (blocks and loads), as SVG text: Jupyter's inline picture."""

def analyze_json(
    scene: Scene,
    direction: str = "right",
    continuous: bool = False,
    kinematic: str = "certified",
    kinematic_max_joints: int = 200,
    friction: str = "auto",
) -> str:
    """``voussoir analyze --json`` of a scene, as JSON text."""

def min_thickness_json(
    scene: Scene,
    continuous: bool = False,
    kinematic_max_joints: int = 200,
    friction: str = "auto",
) -> str:
    """``voussoir min-thickness --json`` of a scene, as JSON text."""

def retrofit_json(scene: Scene, target_lambda: Optional[float] = None) -> str:
    """``voussoir retrofit --json`` of a scene, as JSON text (for its ``[site]`` without
    ``target_lambda``)."""

def fragility_json_svg(
    scene: Scene,
    samples: int = 100,
    seed: int = 1,
    records: Optional[Union[str, PathLike[str]]] = None,
    stripes: Optional[List[float]] = None,
    chunks: Optional[List[str]] = None,
) -> Tuple[str, str]:
    """``voussoir fragility --json`` of a scene and its chart (``--svg``), as text; with
    ``chunks``, from the samples of :func:`fragility_samples_json` joined in order."""

def fragility_samples_json(
    scene: Scene,
    samples: int,
    seed: int,
    records: Optional[str],
    stripes: Optional[List[float]],
    lo: int,
    hi: int,
) -> str:
    """Samples ``lo..hi`` of a capacity-route fragility with their outcomes, as JSON text (a
    cluster's chunk; the dynamic route's chunks are its runs, :func:`fragility_runs_json`)."""

def fragility_run_count(
    scene: Scene, samples: int, seed: int, records: str, stripes: List[float]
) -> int:
    """The DEM runs of a dynamic-route fragility: samples x stripes x records, after checking
    every sample's scene."""

def fragility_runs_json(
    scene: Scene,
    samples: int,
    seed: int,
    records: str,
    stripes: List[float],
    lo: int,
    hi: int,
) -> str:
    """Runs ``lo..hi`` of a dynamic-route fragility (sample, then stripe, then record),
    whether each collapsed, as JSON text (a cluster's chunk)."""

def fragility_samples_from_runs_json(
    scene: Scene,
    samples: int,
    seed: int,
    records: str,
    stripes: List[float],
    runs: List[bool],
) -> str:
    """The samples of a dynamic-route fragility from all its runs' outcomes, as the JSON text
    of :func:`fragility_samples_json` over every sample."""

def report_html_json(scene: Scene, dem: bool = False) -> Tuple[str, str]:
    """``voussoir report`` of a scene: the report's HTML and its JSON text."""

def dem_json(scene: Scene, tolerance: float = 0.01, from_static: bool = False) -> str:
    """``voussoir dem --json`` of a scene, as JSON text."""

def roll_json(
    scene: Scene,
    target: str,
    start: float,
    stop: float,
    step: float,
    direction: Optional[str] = None,
    kinematic: str = "certified",
    kinematic_max_joints: int = 200,
    friction: str = "auto",
) -> Tuple[str, str, str]:
    """``voussoir analyze --roll ... --json`` of a scene, as JSON text, with the drawing at the
    critical position and the chart of the multiplier against the position (SVG text)."""

def analysis_svg(
    scene: Scene,
    direction: str = "right",
    continuous: bool = False,
    kinematic: str = "certified",
    kinematic_max_joints: int = 200,
    friction: str = "auto",
) -> str:
    """The drawing of ``voussoir analyze --svg``, as SVG text."""

def assess_json(
    scene: Scene,
    direction: Optional[str] = None,
    points: int = 200,
    control_block: Optional[int] = None,
) -> str:
    """``voussoir assess --json`` of a scene, as JSON text (both directions unless one is
    given)."""

def assess_svg(
    scene: Scene,
    which: str = "adrs",
    direction: Optional[str] = None,
    points: int = 200,
    control_block: Optional[int] = None,
) -> str:
    """The chart of ``assess --svg`` (``which="capacity"``) or ``--adrs-svg`` (``"adrs"``)."""

def dem_dynamic_json(
    scene: Scene,
    record: Optional[str] = None,
    pulse: Optional[str] = None,
    amplitude: Optional[float] = None,
    period: Optional[float] = None,
    units: str = "g",
    dt: Optional[float] = None,
    scale: float = 1.0,
    component: str = "x",
    record_vertical: Optional[str] = None,
    tail: float = 2.0,
    ida: bool = False,
    tolerance: float = 0.01,
) -> Tuple[str, Optional[List[List[float]]]]:
    """``voussoir dem --record/--pulse [--ida] --json``, as JSON text, and for a single run
    the control block's time history as five columns."""

def dem_pulse_curve_json(
    scene: Scene,
    periods: List[float] = ...,
    shapes: List[str] = ...,
    tail: float = 2.0,
    tolerance: float = 0.01,
) -> str:
    """``voussoir dem --pulse-curve --json``, as JSON text."""

def sweep_rows(
    scene: Scene,
    vary: Dict[str, Any],
    continuous: bool = False,
    dem: bool = False,
    kinematic: str = "certified",
    kinematic_max_joints: int = 200,
) -> List[Dict[str, Any]]:
    """The rows of a sweep, with the columns of the CLI's CSV."""

def variation_values(key: str, values: Any) -> List[Any]:
    """One varied key's values as a sweep reads them (a CLI string expanded), in order."""
