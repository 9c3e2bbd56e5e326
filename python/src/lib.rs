//! `voussoir._voussoir`: the native half of the Python package `voussoir` (distribution
//! `voussoir-arch`). It is a thin binding of the library: every analysis goes through
//! `voussoir::analysis` (and `thickness`, `sweep`) exactly as the CLI's commands do, and every
//! report is the library's JSON contract (`voussoir::report`), so Python and the CLI give the
//! same numbers. What lives here is only translation: Python values to TOML values and back,
//! library errors to Python exceptions (with the same messages), and running the library's
//! work on a worker thread with the GIL released while this thread keeps answering Ctrl-C
//! ([`interruptible`]). The pure-Python half (`python/voussoir/__init__.py`) turns the JSON
//! reports into result objects with numpy arrays and sweeps into pandas frames.

// No unsafe code of ours: PyO3's macros expand to code that passes this lint.
#![forbid(unsafe_code)]

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString};
use toml::{Table, Value};
use voussoir::analysis::{self, DemOptions, KinematicMode, Options};
use voussoir::error::{AnalysisError as LibAnalysisError, SceneError as LibSceneError};
use voussoir::outcome::Direction;
use voussoir::report;
use voussoir::scene::Scene as LibScene;
use voussoir::statics::StaticSettings;
use voussoir::sweep::{self, SweepRow, Variation};

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// How often a waiting call checks for Ctrl-C (and any other signal with a Python handler).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Stack of the worker threads (the library's analyses run on the CLI's 8 MiB main stack).
const WORKER_STACK: usize = 16 << 20;

/// Run `work` on a worker thread with the GIL released, and wait for it while checking for
/// signals every [`SIGNAL_POLL`]: Ctrl-C raises `KeyboardInterrupt` at once instead of after
/// the work (a sweep or a DEM run can take minutes). On a signal `cancel` is set, which the
/// work may poll to stop early (a sweep skips its remaining cases); work that cannot stop
/// (a single DEM run) finishes on its thread and its result is dropped.
fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    cancel: Arc<AtomicBool>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .name("voussoir-work".into())
        .stack_size(WORKER_STACK)
        .spawn(move || {
            // The receiver is gone when the caller was interrupted: nothing to deliver to.
            let _ = tx.send(work());
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    let mut rx = rx;
    loop {
        // The receiver moves into the GIL-free closure and back (it is Send, not Sync).
        let (back, received) = py.detach(move || {
            let r = rx.recv_timeout(SIGNAL_POLL);
            (rx, r)
        });
        rx = back;
        match received {
            Ok(value) => return Ok(value),
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    cancel.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the library's worker thread stopped without a result (an internal error: please report it with the scene)",
                ))
            }
        }
    }
}

/// Deepest nesting of dicts and lists accepted from Python: a scene is a few tables deep, and
/// the conversion recurses (a dict nested 10,000 deep overflowed the stack).
const MAX_DEPTH: usize = 32;

create_exception!(
    _voussoir,
    VoussoirError,
    PyException,
    "Base class of every error voussoir raises."
);
create_exception!(
    _voussoir,
    SceneError,
    VoussoirError,
    "A problem with a scene: its file, a key in it, a value, or a varied key. Attributes: \
`kind` (io, syntax, unknown_key, missing_key, wrong_type, out_of_range, bad_override, \
bad_variation, bad_chart, usage), `origin` (file or source, or None), `key` (the dotted \
scene key, or None) and `value` (the offending value as text, or None)."
);
create_exception!(
    _voussoir,
    AnalysisError,
    VoussoirError,
    "A failure of an analysis that is not a physical answer (a solver that could not be set \
up or did not converge, an invalid assembly). Attribute `kind`."
);

/// A library scene error as a Python `SceneError` with the library's message and the
/// fields a script needs (kind, origin, key, value).
fn scene_error(py: Python<'_>, e: &LibSceneError) -> PyErr {
    let split = |text: &str| -> (Option<String>, Option<String>) {
        match text.split_once('=') {
            Some((k, v)) => (Some(k.trim().to_string()), Some(v.trim().to_string())),
            None => (Some(text.trim().to_string()), None),
        }
    };
    let (kind, origin, key, value): (&str, Option<String>, Option<String>, Option<String>) = match e
    {
        LibSceneError::Io { path, .. } => ("io", Some(path.display().to_string()), None, None),
        LibSceneError::Syntax { origin, .. } => ("syntax", Some(origin.clone()), None, None),
        LibSceneError::UnknownKey { origin, key, .. } => {
            ("unknown_key", Some(origin.clone()), Some(key.clone()), None)
        }
        LibSceneError::MissingKey { origin, key, .. } => {
            ("missing_key", Some(origin.clone()), Some(key.clone()), None)
        }
        LibSceneError::WrongType {
            origin, key, value, ..
        } => (
            "wrong_type",
            Some(origin.clone()),
            Some(key.clone()),
            Some(value.clone()),
        ),
        LibSceneError::OutOfRange {
            origin, key, value, ..
        } => (
            "out_of_range",
            Some(origin.clone()),
            Some(key.clone()),
            Some(value.clone()),
        ),
        LibSceneError::BadOverride { text, .. } => {
            let (k, v) = split(text);
            ("bad_override", None, k, v)
        }
        LibSceneError::BadVariation { text, .. } => {
            let (k, v) = split(text);
            ("bad_variation", None, k, v)
        }
        LibSceneError::BadChart { key, .. } => ("bad_chart", None, Some(key.clone()), None),
        LibSceneError::BadBlocks { origin, key, .. } => {
            ("bad_blocks", Some(origin.clone()), Some(key.clone()), None)
        }
        LibSceneError::Hazard { origin, key, .. } => {
            ("hazard", Some(origin.clone()), Some(key.clone()), None)
        }
        LibSceneError::Usage(_) => ("usage", None, None, None),
    };
    let err = SceneError::new_err(e.to_string());
    let instance = err.value(py);
    let set = || -> PyResult<()> {
        instance.setattr("kind", kind)?;
        instance.setattr("origin", origin)?;
        instance.setattr("key", key)?;
        instance.setattr("value", value)?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// A library analysis error as a Python exception (a scene error stays a `SceneError`).
fn analysis_error(py: Python<'_>, e: &LibAnalysisError) -> PyErr {
    let kind = match e {
        LibAnalysisError::Scene(s) => return scene_error(py, s),
        LibAnalysisError::SolverSetup(_) => "solver_setup",
        LibAnalysisError::SolverFailed { .. } => "solver_failed",
        LibAnalysisError::Assembly(_) => "assembly",
        LibAnalysisError::Record(_) => "record",
        LibAnalysisError::Settings { .. } => "settings",
        LibAnalysisError::NotForAction { .. } => "not_for_action",
        LibAnalysisError::Other(_) => "other",
    };
    let err = AnalysisError::new_err(e.to_string());
    match err.value(py).setattr("kind", kind) {
        Ok(()) => err,
        Err(e) => e,
    }
}

/// A Python value as a TOML value (`key` names it in errors): bool, int, float, str, lists
/// (any sequence, e.g. a numpy array) and dicts with string keys. numpy scalars convert
/// through `__index__` / `__float__`. `depth` counts the enclosing dicts and lists; beyond
/// [`MAX_DEPTH`] the value is refused with a `ValueError`.
fn to_toml(key: &str, ob: &Bound<'_, PyAny>, depth: usize) -> PyResult<Value> {
    let py = ob.py();
    if depth > MAX_DEPTH {
        return Err(PyValueError::new_err(format!(
            "`{}`: nested more than {MAX_DEPTH} levels deep (a scene is a few tables deep; is a dict or list inside itself?)",
            shorten(key)
        )));
    }
    if ob.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(ob.extract::<bool>()?));
    }
    if ob.is_instance_of::<PyString>() {
        return Ok(Value::String(ob.extract::<String>()?));
    }
    if ob.is_instance_of::<PyDict>() {
        return Ok(Value::Table(to_table(key, ob, depth + 1)?));
    }
    if !ob.is_instance_of::<PyFloat>() {
        if let Ok(i) = ob.extract::<i64>() {
            return Ok(Value::Integer(i));
        }
    }
    if let Ok(x) = ob.extract::<f64>() {
        // numpy.bool_ is no int: it arrives here as 0.0 or 1.0, so ask it first.
        let name = ob.get_type().name()?.to_string();
        if name == "bool" || name == "bool_" {
            return Ok(Value::Boolean(x != 0.0));
        }
        return Ok(Value::Float(x));
    }
    if !ob.is_none() {
        if let Ok(iter) = ob.try_iter() {
            let items = iter
                .enumerate()
                .map(|(i, item)| to_toml(&format!("{key}[{i}]"), &item?, depth + 1))
                .collect::<PyResult<Vec<_>>>()?;
            return Ok(Value::Array(items));
        }
    }
    let shown = ob
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "?".to_string());
    Err(scene_error(
        py,
        &LibSceneError::WrongType {
            origin: "<dict>".to_string(),
            key: key.to_string(),
            value: shown,
            expected: "a TOML value (bool, int, float, str, list or dict)".to_string(),
        },
    ))
}

/// A long dotted key, its middle elided (a key built 32 levels deep is long).
fn shorten(key: &str) -> String {
    if key.chars().count() <= 80 {
        return key.to_string();
    }
    let head: String = key.chars().take(36).collect();
    let tail: String = key
        .chars()
        .rev()
        .take(36)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    format!("{head}...{tail}")
}

/// A Python dict (string keys) as a TOML table; `prefix` is its dotted key, `depth` as in
/// [`to_toml`].
fn to_table(prefix: &str, ob: &Bound<'_, PyAny>, depth: usize) -> PyResult<Table> {
    let dict = ob
        .cast::<PyDict>()
        .map_err(|_| PyValueError::new_err(format!("`{prefix}`: expected a dict of scene keys")))?;
    let mut table = Table::new();
    for (k, v) in dict.iter() {
        let k: String = k
            .extract()
            .map_err(|_| PyValueError::new_err(format!("`{prefix}`: scene keys are strings")))?;
        let dotted = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        table.insert(k, to_toml(&dotted, &v, depth)?);
    }
    Ok(table)
}

/// A TOML value as a Python value.
fn from_toml<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        Value::Float(x) => x.into_pyobject(py)?.into_any(),
        Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        Value::Array(a) => PyList::new(
            py,
            a.iter()
                .map(|x| from_toml(py, x))
                .collect::<PyResult<Vec<_>>>()?,
        )?
        .into_any(),
        Value::Table(t) => {
            let d = PyDict::new(py);
            for (k, x) in t {
                d.set_item(k, from_toml(py, x)?)?;
            }
            d.into_any()
        }
    })
}

/// A validated scene (the TOML scene format of docs/geometry.md). Immutable: `with_values`
/// returns a new scene. Scenes pickle (as their TOML), so they travel to Dask workers.
#[pyclass(frozen, name = "Scene", module = "voussoir")]
struct Scene {
    inner: LibScene,
}

#[pymethods]
impl Scene {
    /// Read and validate a scene file (TOML).
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Scene> {
        LibScene::from_file(&path)
            .map(|inner| Scene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// Parse and validate a scene from TOML text; `origin` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_toml_str(py: Python<'_>, text: &str, origin: &str) -> PyResult<Scene> {
        LibScene::from_toml_str(text, origin)
            .map(|inner| Scene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// Validate a scene given as a dict of the TOML tables, e.g.
    /// `{"arch": {"shape": "circular", "radius": 1.0, "embrace_deg": 180.0,
    /// "thickness": 0.15, "voussoirs": 32}}`.
    #[staticmethod]
    #[pyo3(signature = (d, origin = "<dict>"))]
    fn from_dict(py: Python<'_>, d: &Bound<'_, PyAny>, origin: &str) -> PyResult<Scene> {
        let table = to_table("", d, 0)?;
        LibScene::from_table(table, origin)
            .map(|inner| Scene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// A copy with the given dotted keys set together and validated once, e.g.
    /// `{"arch.thickness": 0.2}`; the sweep's ratios (`t/R`, `e/R`, `h/R`, `b/R`, `t/span`,
    /// `rise/span`, `e/span`) are accepted too.
    fn with_values(&self, py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Scene> {
        let mut pairs: Vec<(String, Value)> = Vec::new();
        for (k, v) in values.iter() {
            let k: String = k.extract()?;
            let v = to_toml(&k, &v, 0)?;
            pairs.push((k, v));
        }
        let refs: Vec<(&str, &Value)> = pairs.iter().map(|(k, v)| (k.as_str(), v)).collect();
        sweep::apply(&self.inner, &refs)
            .map(|inner| Scene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// The scene as a dict of its TOML tables (overrides applied).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_toml(py, &Value::Table(self.inner.table().clone()))
    }

    /// The scene as TOML text (overrides applied).
    fn to_toml(&self) -> PyResult<String> {
        toml::to_string(self.inner.table()).map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Where the scene came from (its file, or `<dict>` / `<string>`).
    #[getter]
    fn origin(&self) -> String {
        self.inner.origin.clone()
    }

    /// Radial thickness t of the arch (m); None for a scene of the user's own blocks.
    #[getter]
    fn thickness(&self) -> Option<f64> {
        self.inner.arch.as_ref().map(|a| a.thickness)
    }

    /// Number of voussoirs n; None for a scene of the user's own blocks.
    #[getter]
    fn voussoirs(&self) -> Option<usize> {
        self.inner.arch.as_ref().map(|a| a.voussoirs)
    }

    /// Centreline span of the arch (m).
    #[getter]
    fn span(&self) -> f64 {
        sweep::span(&self.inner)
    }

    /// Centreline rise of the arch (m).
    #[getter]
    fn rise(&self) -> f64 {
        sweep::rise(&self.inner)
    }

    /// The dimensionless ratios (`t/R`, `t/span`, ...); NaN where not defined.
    fn ratios<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in sweep::ratios(&self.inner) {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// Pickled as its TOML text and origin.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let rebuild = slf.get_type().getattr("from_toml_str")?;
        let text = slf.get().to_toml()?;
        Ok((rebuild, (text, slf.get().inner.origin.clone())))
    }

    /// The scene drawn (its blocks and loads, the horizontal load toward +x), as SVG text:
    /// Jupyter shows it inline. A scene whose blocks cannot be built raises the library's
    /// error.
    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<String> {
        let model = voussoir::scene::build(&self.inner).map_err(|e| scene_error(py, &e))?;
        report::figures::scene(&self.inner, &model)
            .map(|f| f.svg)
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    fn __repr__(&self) -> String {
        match &self.inner.arch {
            Some(a) => format!(
                "Scene({}, t = {} m, {} voussoirs, from {})",
                report::shape_title(&self.inner),
                a.thickness,
                a.voussoirs,
                self.inner.origin
            ),
            None => format!(
                "Scene({}, from {})",
                report::shape_title(&self.inner),
                self.inner.origin
            ),
        }
    }
}

fn direction(d: &str) -> PyResult<Direction> {
    match d {
        "right" => Ok(Direction::Right),
        "left" => Ok(Direction::Left),
        other => Err(PyValueError::new_err(format!(
            "direction `{other}`: expected \"right\" or \"left\""
        ))),
    }
}

fn kinematic_mode(k: &str) -> PyResult<KinematicMode> {
    match k {
        "certified" => Ok(KinematicMode::Certified),
        "exhaustive" => Ok(KinematicMode::Exhaustive),
        "general" => Ok(KinematicMode::General),
        other => Err(PyValueError::new_err(format!(
            "kinematic `{other}`: expected \"certified\", \"exhaustive\" or \"general\""
        ))),
    }
}

/// The analysis options; `dir` is the caller's direction, None for the default (toward +x).
/// A live action has no direction: one asked for is refused, as the CLI's `--direction`
/// (`analysis::direction_for`).
fn options(
    py: Python<'_>,
    scene: &LibScene,
    dir: Option<&str>,
    continuous: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
    friction: &str,
) -> PyResult<Options> {
    let asked = dir.map(direction).transpose()?;
    let d = analysis::direction_for(scene, asked).map_err(|e| analysis_error(py, &e))?;
    Ok(Options {
        static_settings: StaticSettings::default().direction(d),
        kinematic_max_joints,
        kinematic: kinematic_mode(kinematic)?,
        continuous,
        friction: friction_mode(py, friction)?,
        ..Options::default()
    })
}

/// The friction law named `friction` (`--friction`'s words: "auto", "associative",
/// "non-associative"), refused by the library's words otherwise.
fn friction_mode(py: Python<'_>, friction: &str) -> PyResult<analysis::FrictionMode> {
    analysis::FrictionMode::parse(friction).map_err(|e| analysis_error(py, &e))
}

fn to_json<T: serde::Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// `analyze --json` of a scene, as JSON text (solved on a worker thread, Ctrl-C answered).
#[pyfunction]
#[pyo3(signature = (scene, direction = None, continuous = false, kinematic = "certified", kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS, friction = "auto"))]
fn analyze_json(
    py: Python<'_>,
    scene: &Scene,
    direction: Option<&str>,
    continuous: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
    friction: &str,
) -> PyResult<String> {
    let options = options(
        py,
        &scene.inner,
        direction,
        continuous,
        kinematic,
        kinematic_max_joints,
        friction,
    )?;
    let lib_scene = scene.inner.clone();
    let (lib_scene, a) = interruptible(py, Arc::default(), move || {
        let a = analysis::analyse(&lib_scene, &options);
        (lib_scene, a)
    })?;
    let a = a.map_err(|e| analysis_error(py, &e))?;
    to_json(&report::AnalysisReport::new(&lib_scene, &a))
}

/// `analyze --roll TARGET --from --to --step --json` of a scene, as JSON text, with the
/// drawing of the structure at the critical position (`--svg`) and the chart of the
/// multiplier against the position (`--roll-svg`), both as SVG text (empty when the structure
/// stands nowhere). Solved on a worker thread, Ctrl-C answered.
#[pyfunction]
#[pyo3(signature = (scene, target, start, stop, step, direction = None, kinematic = "certified", kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS, friction = "auto"))]
#[allow(clippy::too_many_arguments)]
fn roll_json(
    py: Python<'_>,
    scene: &Scene,
    target: &str,
    start: f64,
    stop: f64,
    step: f64,
    direction: Option<&str>,
    kinematic: &str,
    kinematic_max_joints: usize,
    friction: &str,
) -> PyResult<(String, String, String)> {
    let options = options(
        py,
        &scene.inner,
        direction,
        false,
        kinematic,
        kinematic_max_joints,
        friction,
    )?;
    let side = options.direction();
    let spec = voussoir::roll::RollSpec {
        target: target.parse().map_err(|e| analysis_error(py, &e))?,
        from: start,
        to: stop,
        step,
        refine: true,
    };
    let lib_scene = scene.inner.clone();
    let (lib_scene, r) = interruptible(py, Arc::default(), move || {
        let r = voussoir::roll::roll(&lib_scene, &spec, &options);
        (lib_scene, r)
    })?;
    let r = r.map_err(|e| analysis_error(py, &e))?;
    let doc = report::documents::roll(&lib_scene, &r);
    let Some(report::Data::Analysis(data)) = &doc.data else {
        // No position stands: the roll object alone.
        let json = serde_json::json!({ "roll": report::RollReport::new(&r) });
        return Ok((json.to_string(), String::new(), String::new()));
    };
    let svg_err = |e: voussoir::drawing::svg::SvgError| PyValueError::new_err(e.to_string());
    let chart = report::figures::roll_chart(&lib_scene, &r).map_err(svg_err)?;
    let c = r
        .critical
        .as_ref()
        .expect("an analysis has a critical position");
    let drawing = report::analysis_svg(&c.scene, &c.analysis, side).map_err(svg_err)?;
    Ok((to_json(data)?, drawing, chart.svg))
}

/// The drawing `analyze --svg` writes (blocks, thrust line, hinges, mechanism, loads), as SVG
/// text: `report::analysis_svg` of the same analysis as `analyze_json`.
#[pyfunction]
#[pyo3(signature = (scene, direction = None, continuous = false, kinematic = "certified", kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS, friction = "auto"))]
fn analysis_svg(
    py: Python<'_>,
    scene: &Scene,
    direction: Option<&str>,
    continuous: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
    friction: &str,
) -> PyResult<String> {
    let options = options(
        py,
        &scene.inner,
        direction,
        continuous,
        kinematic,
        kinematic_max_joints,
        friction,
    )?;
    let dir = options.direction();
    let lib_scene = scene.inner.clone();
    let out = interruptible(py, Arc::default(), move || {
        analysis::analyse(&lib_scene, &options)
            .map(|a| report::analysis_svg(&lib_scene, &a, dir).map_err(|e| e.to_string()))
    })?;
    out.map_err(|e| analysis_error(py, &e))?
        .map_err(PyValueError::new_err)
}

/// `min-thickness --json` of a scene, as JSON text (solved on a worker thread, Ctrl-C
/// answered).
#[pyfunction]
#[pyo3(signature = (scene, continuous = false, kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS, friction = "auto"))]
fn min_thickness_json(
    py: Python<'_>,
    scene: &Scene,
    continuous: bool,
    kinematic_max_joints: usize,
    friction: &str,
) -> PyResult<String> {
    let friction = friction_mode(py, friction)?;
    let lib_scene = scene.inner.clone();
    let (lib_scene, out) = interruptible(py, Arc::default(), move || {
        let out = (|| -> Result<_, LibAnalysisError> {
            let model = voussoir::scene::build(&lib_scene)?;
            let options = analysis::Options {
                static_settings: StaticSettings::default(),
                kinematic_max_joints,
                kinematic: analysis::KinematicMode::Certified,
                continuous,
                friction,
                ..analysis::Options::default()
            };
            let t = voussoir::thickness::analyse(&lib_scene, &options)?;
            Ok((model, t))
        })();
        (lib_scene, out)
    })?;
    let (model, t) = out.map_err(|e| analysis_error(py, &e))?;
    to_json(&report::MinThicknessReport::new(&lib_scene, &model, &t))
}

/// `retrofit --json` of a scene, as JSON text: the least capacities of the ties and strips
/// marked `"design"` that give lambda >= `target_lambda`, the structure analysed again; without
/// `target_lambda`, the least that pass the NTC 2018 check at the scene's `[site]`
/// (`retrofit --site`, its `site` object).
#[pyfunction]
#[pyo3(signature = (scene, target_lambda = None))]
fn retrofit_json(py: Python<'_>, scene: &Scene, target_lambda: Option<f64>) -> PyResult<String> {
    if target_lambda.is_none() && scene.inner.site.is_none() {
        return Err(PyValueError::new_err(format!(
            "{}: what should the retrofit reach? Give target_lambda, or a site (site={{\"ag\": 0.25, \"soil\": \"B\", \"F0\": 2.4, \"Tc_star\": 0.3}}, or a [site] table in the scene)",
            scene.inner.origin
        )));
    }
    let lib_scene = scene.inner.clone();
    let (lib_scene, r) = interruptible(py, Arc::default(), move || {
        let options = Options::default();
        let r = match target_lambda {
            Some(target) => voussoir::retrofit::design(&lib_scene, target, &options)
                .map(|r| report::retrofit::RetrofitReport::new(&lib_scene, &r)),
            None => voussoir::retrofit::design_for_site(
                &lib_scene,
                &options,
                &analysis::AssessOptions::default(),
            )
            .map(|r| report::retrofit::RetrofitReport::for_site(&lib_scene, &r)),
        };
        (lib_scene, r)
    })?;
    drop(lib_scene);
    to_json(&r.map_err(|e| analysis_error(py, &e))?)
}

/// `fragility --json` of a scene and its chart (`--svg`), as JSON and SVG text: `samples`
/// Latin hypercube samples of its `[uncertain]` inputs from `seed`; without `records`, each
/// sample's capacity by the NTC nonlinear kinematic check at its `[site]` (the capacity
/// route), with `records` (a directory of .AT2 files) and `stripes` (PGAs in g) the DEM
/// under each record scaled to each stripe (the dynamic route); the lognormal fit
/// (docs/fragility.md). `chunks`: the samples already computed, in order, as the JSON texts
/// of [`fragility_samples_json`] (a cluster's chunks); the fit is then made from them.
#[pyfunction]
#[pyo3(signature = (scene, samples = 100, seed = 1, records = None, stripes = None, chunks = None))]
fn fragility_json_svg(
    py: Python<'_>,
    scene: &Scene,
    samples: usize,
    seed: u64,
    records: Option<std::path::PathBuf>,
    stripes: Option<Vec<f64>>,
    chunks: Option<Vec<String>>,
) -> PyResult<(String, String)> {
    use voussoir::fragility as fr;
    let lib_scene = scene.inner.clone();
    let settings = fragility_settings(samples, seed);
    let out = interruptible(py, Arc::default(), move || {
        let out = match (records, stripes) {
            (None, None) => {
                let all = match &chunks {
                    Some(c) => joined(c),
                    None => fr::capacity_samples(&lib_scene, &settings, 0..settings.samples),
                };
                all.and_then(|all| fr::capacity_fragility(&lib_scene, &settings, all))
                    .and_then(|f| {
                        let svg = report::figures::fragility(&lib_scene, &f)
                            .map_err(|e| LibAnalysisError::Other(e.to_string()))?
                            .svg;
                        Ok((report::fragility::FragilityReport::new(&lib_scene, &f), svg))
                    })
            }
            (Some(dir), Some(stripes)) => fr::read_records(&dir).and_then(|records| {
                let f = match &chunks {
                    Some(c) => fr::dynamic_fragility(
                        &lib_scene,
                        &settings,
                        &records,
                        &stripes,
                        joined(c)?,
                    )?,
                    None => fr::dynamic_route(
                        &lib_scene,
                        &settings,
                        &records,
                        &stripes,
                        &voussoir::dem::dynamic::DynamicSettings::default(),
                    )?,
                };
                let svg = report::figures::dynamic_fragility(&lib_scene, &f)
                    .map_err(|e| LibAnalysisError::Other(e.to_string()))?
                    .svg;
                Ok((
                    report::fragility::FragilityReport::dynamic(&lib_scene, &f),
                    svg,
                ))
            }),
            _ => Err(LibAnalysisError::Other(
                "records and stripes go together: the dynamic route needs both".into(),
            )),
        };
        (lib_scene, out)
    })?;
    let (report, svg) = out.1.map_err(|e| analysis_error(py, &e))?;
    Ok((to_json(&report)?, svg))
}

/// A fragility's settings from Python's arguments (the rest at their defaults).
fn fragility_settings(samples: usize, seed: u64) -> voussoir::fragility::Settings {
    voussoir::fragility::Settings {
        samples,
        seed,
        ..voussoir::fragility::Settings::default()
    }
}

/// A chunk's results as JSON text (a library error if they do not serialise).
fn json_text<T: serde::Serialize>(x: &T) -> Result<String, LibAnalysisError> {
    serde_json::to_string(x).map_err(|e| LibAnalysisError::Other(e.to_string()))
}

/// The samples of chunks (JSON texts of [`fragility_samples_json`]) joined in order.
fn joined<T: serde::de::DeserializeOwned>(chunks: &[String]) -> Result<Vec<T>, LibAnalysisError> {
    let mut all = Vec::new();
    for c in chunks {
        let part: Vec<T> = serde_json::from_str(c).map_err(|e| {
            LibAnalysisError::Other(format!("a chunk of fragility samples is not one: {e}"))
        })?;
        all.extend(part);
    }
    Ok(all)
}

/// Samples `lo..hi` of a fragility (the same samples, values and outcomes as those of
/// [`fragility_json_svg`] with the same `samples`, `seed`, `records` and `stripes`), as JSON
/// text: the chunk a cluster's worker computes for Python's `fragility(..., client=)`.
#[pyfunction]
#[pyo3(signature = (scene, samples, seed, records, stripes, lo, hi))]
#[allow(clippy::too_many_arguments)]
fn fragility_samples_json(
    py: Python<'_>,
    scene: &Scene,
    samples: usize,
    seed: u64,
    records: Option<std::path::PathBuf>,
    stripes: Option<Vec<f64>>,
    lo: usize,
    hi: usize,
) -> PyResult<String> {
    use voussoir::fragility as fr;
    let lib_scene = scene.inner.clone();
    let settings = fragility_settings(samples, seed);
    let out = interruptible(py, Arc::default(), move || {
        let out = match (records, stripes) {
            (None, None) => {
                fr::capacity_samples(&lib_scene, &settings, lo..hi).and_then(|s| json_text(&s))
            }
            // The dynamic route's chunks are its runs (`fragility_runs_json`).
            (Some(_), Some(_)) => Err(LibAnalysisError::Other(
                "the dynamic route is mapped by its runs: fragility_runs_json".into(),
            )),
            _ => Err(LibAnalysisError::Other(
                "records and stripes go together: the dynamic route needs both".into(),
            )),
        };
        (lib_scene, out)
    })?;
    out.1.map_err(|e| analysis_error(py, &e))
}

/// The number of DEM runs of a dynamic-route fragility (samples x stripes x the records of
/// the directory `records`), after the same checks as [`fragility_runs_json`] and a check of
/// every sample's scene (`seed` draws them), so a refused sample is said before any run.
#[pyfunction]
fn fragility_run_count(
    py: Python<'_>,
    scene: &Scene,
    samples: usize,
    seed: u64,
    records: std::path::PathBuf,
    stripes: Vec<f64>,
) -> PyResult<usize> {
    use voussoir::fragility as fr;
    let settings = fragility_settings(samples, seed);
    fr::read_records(&records)
        .and_then(|r| fr::dynamic_run_count(&scene.inner, &settings, &r, &stripes))
        .and_then(|n| fr::check_samples(&scene.inner, &settings).map(|()| n))
        .map_err(|e| analysis_error(py, &e))
}

/// Runs `lo..hi` of a dynamic-route fragility (numbered sample, then stripe, then record:
/// `voussoir::fragility::dynamic_runs`), whether each collapsed, as JSON text: the chunk a
/// cluster's worker computes for Python's `fragility(..., records=, client=)`.
#[pyfunction]
#[pyo3(signature = (scene, samples, seed, records, stripes, lo, hi))]
#[allow(clippy::too_many_arguments)]
fn fragility_runs_json(
    py: Python<'_>,
    scene: &Scene,
    samples: usize,
    seed: u64,
    records: std::path::PathBuf,
    stripes: Vec<f64>,
    lo: usize,
    hi: usize,
) -> PyResult<String> {
    use voussoir::fragility as fr;
    let lib_scene = scene.inner.clone();
    let settings = fragility_settings(samples, seed);
    let out = interruptible(py, Arc::default(), move || {
        let out = fr::read_records(&records).and_then(|records| {
            fr::dynamic_runs(
                &lib_scene,
                &settings,
                &records,
                &stripes,
                &voussoir::dem::dynamic::DynamicSettings::default(),
                lo..hi,
            )
            .and_then(|f| json_text(&f))
        });
        (lib_scene, out)
    })?;
    out.1.map_err(|e| analysis_error(py, &e))
}

/// The samples of a dynamic-route fragility from the outcomes of all its runs (those of
/// [`fragility_runs_json`] joined in order), as the JSON text of [`fragility_samples_json`]
/// over all samples: a chunk for [`fragility_json_svg`].
#[pyfunction]
fn fragility_samples_from_runs_json(
    py: Python<'_>,
    scene: &Scene,
    samples: usize,
    seed: u64,
    records: std::path::PathBuf,
    stripes: Vec<f64>,
    runs: Vec<bool>,
) -> PyResult<String> {
    use voussoir::fragility as fr;
    let settings = fragility_settings(samples, seed);
    let r = fr::read_records(&records)
        .and_then(|r| fr::dynamic_samples_from_runs(&scene.inner, &settings, &r, &stripes, &runs))
        .and_then(|s| json_text(&s));
    r.map_err(|e| analysis_error(py, &e))
}

/// `voussoir report` of a scene: the hand-in report's HTML and its JSON (docs/report.md).
/// The report's input text (quoted in full, hashed) is the scene as `Scene.to_toml()` writes
/// it, which reproduces it; `dem` adds the DEM's bracket as `--dem`.
#[pyfunction]
#[pyo3(signature = (scene, dem = false))]
fn report_html_json(py: Python<'_>, scene: &Scene, dem: bool) -> PyResult<(String, String)> {
    let text =
        toml::to_string(scene.inner.table()).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let lib_scene = scene.inner.clone();
    let (lib_scene, d) = interruptible(py, Arc::default(), move || {
        let d = voussoir::dossier::run(&lib_scene, &voussoir::dossier::DossierOptions { dem });
        (lib_scene, d)
    })?;
    let d = d.map_err(|e| analysis_error(py, &e))?;
    let source = report::dossier::Source {
        text,
        overrides: Vec::new(),
    };
    let r = report::dossier::hand_in(&lib_scene, &source, &d);
    Ok((r.html(), r.json()))
}

/// `dem --json` of a scene, as JSON text. The bracket search runs on a worker thread: Ctrl-C
/// raises `KeyboardInterrupt` at once, and the run in progress finishes on its thread (the
/// library's DEM has no stop flag yet) with its result dropped.
#[pyfunction]
#[pyo3(signature = (scene, tolerance = 0.01, from_static = false))]
fn dem_json(py: Python<'_>, scene: &Scene, tolerance: f64, from_static: bool) -> PyResult<String> {
    let lib_scene = scene.inner.clone();
    let options = DemOptions {
        tolerance,
        from_static,
        ..DemOptions::default()
    };
    let (lib_scene, d) = interruptible(py, Arc::default(), move || {
        let d = analysis::dem(&lib_scene, &options, &mut |_| {});
        (lib_scene, d)
    })?;
    let d = d.map_err(|e| analysis_error(py, &e))?;
    to_json(&report::DemReport::of(&lib_scene, &d))
}

/// `assess --json` of a scene at its `[site]`, as JSON text: both directions of the load, the
/// worse governing, or only `direction` ("right" or "left") when given; `points` of the
/// capacity curve, its `control_block` and `incremental` as the CLI's flags.
#[pyfunction]
#[pyo3(signature = (scene, direction = None, points = 200, control_block = None, incremental = false))]
fn assess_json(
    py: Python<'_>,
    scene: &Scene,
    direction: Option<&str>,
    points: usize,
    control_block: Option<usize>,
    incremental: bool,
) -> PyResult<String> {
    let only = direction.map(self::direction).transpose()?;
    let lib_scene = scene.inner.clone();
    let (lib_scene, all) = interruptible(py, Arc::default(), move || {
        let all = voussoir::analysis::assess_directions(
            &lib_scene,
            &Options::default(),
            &analysis::AssessOptions {
                points,
                control_block,
                incremental,
            },
            only,
        );
        (lib_scene, all)
    })?;
    let all = all.map_err(|e| analysis_error(py, &e))?;
    to_json(&report::assessment::AssessmentReport::new(&lib_scene, &all))
}

/// The charts of `assess` as SVG text: `which` is "capacity" (the capacity curves of every
/// direction, `--svg`) or "adrs" (the governing direction's ADRS plot, `--adrs-svg`).
#[pyfunction]
#[pyo3(signature = (scene, which = "adrs", direction = None, points = 200, control_block = None, incremental = false))]
fn assess_svg(
    py: Python<'_>,
    scene: &Scene,
    which: &str,
    direction: Option<&str>,
    points: usize,
    control_block: Option<usize>,
    incremental: bool,
) -> PyResult<String> {
    if which != "capacity" && which != "adrs" {
        return Err(PyValueError::new_err(format!(
            "which = `{which}`: expected \"capacity\" or \"adrs\""
        )));
    }
    let only = direction.map(self::direction).transpose()?;
    let lib_scene = scene.inner.clone();
    let which = which.to_string();
    let out = interruptible(py, Arc::default(), move || {
        let all = voussoir::analysis::assess_directions(
            &lib_scene,
            &Options::default(),
            &analysis::AssessOptions {
                points,
                control_block,
                incremental,
            },
            only,
        )?;
        let title = report::shape_title(&lib_scene);
        // The same figures as `voussoir assess --svg` and `--adrs-svg` draw.
        let figure = if which == "capacity" {
            report::figures::assessment_capacity(&all, &title)
        } else {
            report::figures::assessment_adrs(&all, &title)
        };
        Ok(figure.map(|f| f.svg).map_err(|e| e.to_string()))
    })?;
    out.map_err(|e: LibAnalysisError| analysis_error(py, &e))?
        .map_err(PyValueError::new_err)
}

/// The ground motion of a dynamic run from the arguments of `dem_dynamic_json` (the CLI's
/// `--record`, `--pulse`, `--amplitude`, `--period`, `--units`, `--dt`, `--scale`,
/// `--component`, `--record-vertical`).
#[allow(clippy::too_many_arguments)]
fn ground_input(
    record: Option<std::path::PathBuf>,
    pulse: Option<&str>,
    amplitude: Option<f64>,
    period: Option<f64>,
    units: &str,
    dt: Option<f64>,
    scale: f64,
    component: &str,
    record_vertical: Option<std::path::PathBuf>,
) -> Result<voussoir::dem::record::GroundInput, voussoir::error::RecordError> {
    use voussoir::dem::record::{
        self as rec, AccelUnit, Component, Excitation, GroundInput, Pulse, PulseShape,
    };
    use voussoir::error::RecordError;
    let flag = |flag: &str, value: String, message: &str| RecordError::Flag {
        flag: flag.to_string(),
        value,
        message: message.to_string(),
    };
    let unit = match units {
        "g" => AccelUnit::G,
        "m/s2" => AccelUnit::MetersPerSecondSquared,
        "cm/s2" => AccelUnit::CentimetersPerSecondSquared,
        other => {
            return Err(flag(
                "units",
                other.to_string(),
                "expected \"g\", \"m/s2\" or \"cm/s2\"",
            ))
        }
    };
    let main = match (record, pulse) {
        (Some(_), Some(_)) => {
            return Err(flag(
                "pulse",
                pulse.unwrap_or("").to_string(),
                "give a record or a pulse, not both",
            ))
        }
        (Some(path), None) => Excitation::Record(rec::read(&path, unit, dt)?),
        (None, Some(shape)) => {
            let shape = match shape {
                "sine" => PulseShape::Sine,
                "rect" => PulseShape::Rect,
                other => {
                    return Err(flag(
                        "pulse",
                        other.to_string(),
                        "expected \"sine\" or \"rect\"",
                    ))
                }
            };
            let (Some(a), Some(t)) = (amplitude, period) else {
                return Err(flag(
                    "pulse",
                    format!("{shape:?}").to_lowercase(),
                    "needs an amplitude and a period",
                ));
            };
            Excitation::Pulse(Pulse::new(shape, a * unit.factor(), t)?)
        }
        (None, None) => {
            return Err(flag(
                "record",
                String::new(),
                "give a record (a file) or a pulse (\"sine\" or \"rect\")",
            ))
        }
    };
    if !(scale.is_finite() && scale >= 0.0) {
        return Err(flag(
            "scale",
            scale.to_string(),
            "must be a finite number >= 0",
        ));
    }
    let component = match component {
        "x" => Component::X,
        "y" => Component::Y,
        other => {
            return Err(flag(
                "component",
                other.to_string(),
                "expected \"x\" or \"y\"",
            ))
        }
    };
    let vertical = match record_vertical {
        Some(path) => Some(Excitation::Record(rec::read(&path, unit, dt)?)),
        None => None,
    };
    Ok(GroundInput::new(main, component, vertical)?.scaled(scale))
}

/// A dynamic DEM run of a scene under a ground-acceleration record or an analytic pulse
/// (`dem --record/--pulse --json`), or with `ida` the scale that brings it down
/// (`--ida --json`): returns the JSON text and, for a single run, the control block's time
/// history as columns `(time, ground_acceleration, displacement, rotation,
/// ground_acceleration_vertical)` (`--history`). Runs on a worker thread: Ctrl-C raises
/// `KeyboardInterrupt` at once (the run in progress finishes on its thread, its result
/// dropped).
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
#[pyfunction]
#[pyo3(signature = (scene, record = None, pulse = None, amplitude = None, period = None, units = "g", dt = None, scale = 1.0, component = "x", record_vertical = None, tail = 2.0, ida = false, tolerance = 0.01))]
fn dem_dynamic_json(
    py: Python<'_>,
    scene: &Scene,
    record: Option<std::path::PathBuf>,
    pulse: Option<&str>,
    amplitude: Option<f64>,
    period: Option<f64>,
    units: &str,
    dt: Option<f64>,
    scale: f64,
    component: &str,
    record_vertical: Option<std::path::PathBuf>,
    tail: f64,
    ida: bool,
    tolerance: f64,
) -> PyResult<(String, Option<[Vec<f64>; 5]>)> {
    let record_error =
        |e: voussoir::error::RecordError| analysis_error(py, &LibAnalysisError::Record(e));
    let ground = ground_input(
        record,
        pulse,
        amplitude,
        period,
        units,
        dt,
        scale,
        component,
        record_vertical,
    )
    .map_err(record_error)?;
    if !(tail.is_finite() && tail >= 0.0) {
        return Err(record_error(voussoir::error::RecordError::Flag {
            flag: "tail".to_string(),
            value: tail.to_string(),
            message: "must be a finite number of seconds >= 0".to_string(),
        }));
    }
    let settings = voussoir::dem::dynamic::DynamicSettings {
        tail,
        ..Default::default()
    };
    let lib_scene = scene.inner.clone();
    if ida {
        let out = interruptible(py, Arc::default(), move || {
            analysis::dem_ida(&lib_scene, &ground, &settings, tolerance)
                .map(|(_, r)| report::IdaReport::new(&ground, &r, tolerance))
        })?;
        let rep = out.map_err(|e| analysis_error(py, &e))?;
        return Ok((to_json(&rep)?, None));
    }
    let (lib_scene, out) = interruptible(py, Arc::default(), move || {
        let d = analysis::dem_dynamic(&lib_scene, &ground, &settings);
        (lib_scene, d)
    })?;
    let d = out.map_err(|e| analysis_error(py, &e))?;
    let h = &d.result.history;
    let column = |f: fn(&voussoir::dem::dynamic::Sample) -> f64| h.iter().map(f).collect();
    let history = [
        column(|s| s.time),
        column(|s| s.ground_acceleration),
        column(|s| s.displacement),
        column(|s| s.rotation),
        column(|s| s.ground_acceleration_vertical),
    ];
    Ok((
        to_json(&report::DynamicReport::new(&lib_scene, &d))?,
        Some(history),
    ))
}

/// The minimum collapse amplitude of one-cycle pulses against their period
/// (`dem --pulse-curve --json`), as JSON text: `shapes` among "sine" and "rect", `periods` in
/// s (the CLI's defaults when empty). Each amplitude search runs on a worker thread; Ctrl-C
/// stops after the point in progress.
#[pyfunction]
#[pyo3(signature = (scene, periods = Vec::new(), shapes = Vec::new(), tail = 2.0, tolerance = 0.01))]
fn dem_pulse_curve_json(
    py: Python<'_>,
    scene: &Scene,
    periods: Vec<f64>,
    shapes: Vec<String>,
    tail: f64,
    tolerance: f64,
) -> PyResult<String> {
    use voussoir::dem::record::PulseShape;
    let record_error =
        |e: voussoir::error::RecordError| analysis_error(py, &LibAnalysisError::Record(e));
    let shapes: Vec<PulseShape> = if shapes.is_empty() {
        vec![PulseShape::Sine, PulseShape::Rect]
    } else {
        shapes
            .iter()
            .map(|s| match s.as_str() {
                "sine" => Ok(PulseShape::Sine),
                "rect" => Ok(PulseShape::Rect),
                other => Err(record_error(voussoir::error::RecordError::Flag {
                    flag: "shapes".to_string(),
                    value: other.to_string(),
                    message: "expected \"sine\" or \"rect\"".to_string(),
                })),
            })
            .collect::<PyResult<_>>()?
    };
    let periods = if periods.is_empty() {
        analysis::PULSE_CURVE_PERIODS.to_vec()
    } else {
        periods
    };
    if !(tail.is_finite() && tail >= 0.0) {
        return Err(record_error(voussoir::error::RecordError::Flag {
            flag: "tail".to_string(),
            value: tail.to_string(),
            message: "must be a finite number of seconds >= 0".to_string(),
        }));
    }
    let settings = voussoir::dem::dynamic::DynamicSettings {
        tail,
        ..Default::default()
    };
    let lib_scene = scene.inner.clone();
    let out = interruptible(py, Arc::default(), move || {
        analysis::dem_pulse_curve(
            &lib_scene,
            &shapes,
            &periods,
            &settings,
            tolerance,
            &mut |_| {},
        )
        .map(|c| report::PulseCurveReport::new(&c))
    })?;
    let rep = out.map_err(|e| analysis_error(py, &e))?;
    to_json(&rep)
}

/// One varied key's values: a string in the CLI's syntax (`"0.1,0.2"`, `"0.1:0.2:0.01"`), a
/// sequence (list, tuple, range, numpy array) or a single value.
fn variation(key: &str, values: &Bound<'_, PyAny>) -> PyResult<Variation> {
    let py = values.py();
    if values.is_instance_of::<PyString>() {
        let spec: String = values.extract()?;
        return sweep::parse_variation(&format!("{key}={spec}")).map_err(|e| scene_error(py, &e));
    }
    let values = match to_toml(key, values, 0)? {
        Value::Array(a) => a,
        one => vec![one],
    };
    Ok(Variation {
        key: key.to_string(),
        values,
    })
}

/// The values of one varied key as a sweep reads them (a string in the CLI's syntax
/// expanded), in order: what `voussoir._dask` splits a sweep's cases by.
#[pyfunction]
fn variation_values<'py>(
    py: Python<'py>,
    key: &str,
    values: &Bound<'py, PyAny>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    variation(key, values)?
        .values
        .iter()
        .map(|v| from_toml(py, v))
        .collect()
}

/// A sweep row as a dict with the columns of the CLI's CSV: the varied keys, `status,
/// lambda_lower, lambda_upper, gap, hinges, solve_time_s`, the extra columns, the ratios not
/// varied, and `error`. Missing numbers (and undefined ratios) are None.
fn row_dict<'py>(
    py: Python<'py>,
    variations: &[Variation],
    ratio_names: &[&str],
    row: &SweepRow,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (v, x) in variations.iter().zip(&row.values) {
        d.set_item(&v.key, from_toml(py, x)?)?;
    }
    let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
    d.set_item("status", &row.status)?;
    d.set_item("lambda_lower", finite(row.lambda_lower))?;
    d.set_item("lambda_upper", finite(row.lambda_upper))?;
    d.set_item("gap", finite(row.gap()))?;
    d.set_item("hinges", sweep::hinge_string(&row.hinges))?;
    d.set_item("solve_time_s", row.solve_time_s)?;
    for (name, x) in &row.extra {
        d.set_item(*name, finite(*x))?;
    }
    for name in ratio_names {
        let x = row.ratios.iter().find(|(n, _)| n == name).map(|(_, v)| *v);
        d.set_item(*name, finite(x))?;
    }
    d.set_item("error", &row.error)?;
    Ok(d)
}

/// The rows of a sweep over the cartesian product of `vary` (dict order: the first key
/// changes slowest), solved in parallel with the GIL released.
#[pyfunction]
#[pyo3(signature = (scene, vary, continuous = false, dem = false, kinematic = "certified", kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS))]
fn sweep_rows<'py>(
    py: Python<'py>,
    scene: &Scene,
    vary: &Bound<'py, PyDict>,
    continuous: bool,
    dem: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
) -> PyResult<Bound<'py, PyList>> {
    let options = options(
        py,
        &scene.inner,
        None,
        continuous,
        kinematic,
        kinematic_max_joints,
        // A sweep's rows are the static multiplier's, as the CLI's `sweep`.
        "associative",
    )?;
    let mut variations = Vec::new();
    for (k, v) in vary.iter() {
        let k: String = k.extract()?;
        variations.push(variation(&k, &v)?);
    }
    if variations.is_empty() {
        return Err(scene_error(
            py,
            &LibSceneError::Usage("sweep: `vary` names no key".to_string()),
        ));
    }
    let base = &scene.inner;
    let plan = py
        .detach(|| sweep::Sweep::new(base, variations))
        .map_err(|e| scene_error(py, &e))?;
    // Solved on a worker thread; on Ctrl-C the cases not yet started are skipped (the cases
    // in progress finish on their threads) and KeyboardInterrupt is raised at once.
    let cancel = Arc::new(AtomicBool::new(false));
    let stop = Arc::clone(&cancel);
    let (plan, rows) = interruptible(py, cancel, move || {
        let rows = plan.run_with(
            |values, scene| {
                (!stop.load(Ordering::Relaxed)).then(|| sweep::case(values, scene, &options, dem))
            },
            &|| {},
        );
        (plan, rows)
    })?;
    let rows: Vec<SweepRow> = rows.into_iter().flatten().collect();
    let ratio_names: Vec<&str> = sweep::DERIVED_KEYS
        .iter()
        .copied()
        .filter(|k| !plan.variations().iter().any(|v| v.key == *k))
        .collect();
    let list = PyList::empty(py);
    for row in &rows {
        list.append(row_dict(py, plan.variations(), &ratio_names, row)?)?;
    }
    Ok(list)
}

/// The native module.
#[pymodule]
fn _voussoir(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(analyze_json, m)?)?;
    m.add_function(wrap_pyfunction!(min_thickness_json, m)?)?;
    m.add_function(wrap_pyfunction!(retrofit_json, m)?)?;
    m.add_function(wrap_pyfunction!(fragility_json_svg, m)?)?;
    m.add_function(wrap_pyfunction!(fragility_samples_json, m)?)?;
    m.add_function(wrap_pyfunction!(fragility_run_count, m)?)?;
    m.add_function(wrap_pyfunction!(fragility_runs_json, m)?)?;
    m.add_function(wrap_pyfunction!(fragility_samples_from_runs_json, m)?)?;
    m.add_function(wrap_pyfunction!(dem_json, m)?)?;
    m.add_function(wrap_pyfunction!(report_html_json, m)?)?;
    m.add_function(wrap_pyfunction!(analysis_svg, m)?)?;
    m.add_function(wrap_pyfunction!(roll_json, m)?)?;
    m.add_function(wrap_pyfunction!(assess_json, m)?)?;
    m.add_function(wrap_pyfunction!(assess_svg, m)?)?;
    m.add_function(wrap_pyfunction!(dem_dynamic_json, m)?)?;
    m.add_function(wrap_pyfunction!(dem_pulse_curve_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_rows, m)?)?;
    m.add_function(wrap_pyfunction!(variation_values, m)?)?;
    m.add("VoussoirError", py.get_type::<VoussoirError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("AnalysisError", py.get_type::<AnalysisError>())?;
    m.add("DERIVED_KEYS", sweep::DERIVED_KEYS.to_vec())?;
    m.add(
        "KINEMATIC_DEFAULT_MAX_JOINTS",
        analysis::KINEMATIC_DEFAULT_MAX_JOINTS,
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
