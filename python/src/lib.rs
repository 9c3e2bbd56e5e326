//! `voussoir._voussoir`: the native half of the Python package `voussoir` (distribution
//! `voussoir-arch`). It is a thin binding of the library: every analysis goes through
//! `voussoir::analysis` (and `thickness`, `sweep`) exactly as the CLI's commands do, and every
//! report is the library's JSON contract (`voussoir::report`), so Python and the CLI give the
//! same numbers. What lives here is only translation: Python values to TOML values and back,
//! library errors to Python exceptions (with the same messages), and releasing the GIL while
//! the library solves. The pure-Python half (`python/voussoir/__init__.py`) turns the JSON
//! reports into result objects with numpy arrays and sweeps into pandas frames.

// No unsafe code of ours: PyO3's macros expand to code that passes this lint.
#![forbid(unsafe_code)]

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString};
use toml::{Table, Value};
use voussoir::analysis::{self, DemOptions, KinematicMode, Options};
use voussoir::error::{AnalysisError as LibAnalysisError, SceneError as LibSceneError};
use voussoir::lp::StaticSettings;
use voussoir::outcome::Direction;
use voussoir::report;
use voussoir::scene::Scene as LibScene;
use voussoir::sweep::{self, SweepRow, Variation};

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
/// through `__index__` / `__float__`.
fn to_toml(key: &str, ob: &Bound<'_, PyAny>) -> PyResult<Value> {
    let py = ob.py();
    if ob.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(ob.extract::<bool>()?));
    }
    if ob.is_instance_of::<PyString>() {
        return Ok(Value::String(ob.extract::<String>()?));
    }
    if ob.is_instance_of::<PyDict>() {
        return Ok(Value::Table(to_table(key, ob)?));
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
                .map(|(i, item)| to_toml(&format!("{key}[{i}]"), &item?))
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

/// A Python dict (string keys) as a TOML table; `prefix` is its dotted key.
fn to_table(prefix: &str, ob: &Bound<'_, PyAny>) -> PyResult<Table> {
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
        table.insert(k, to_toml(&dotted, &v)?);
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
        let table = to_table("", d)?;
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
            let v = to_toml(&k, &v)?;
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
        other => Err(PyValueError::new_err(format!(
            "kinematic `{other}`: expected \"certified\" or \"exhaustive\""
        ))),
    }
}

fn options(
    dir: &str,
    continuous: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
) -> PyResult<Options> {
    Ok(Options {
        static_settings: StaticSettings::default().direction(direction(dir)?),
        kinematic_max_joints,
        kinematic: kinematic_mode(kinematic)?,
        continuous,
    })
}

fn to_json<T: serde::Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// `analyze --json` of a scene, as JSON text (the GIL is released while it solves).
#[pyfunction]
#[pyo3(signature = (scene, direction = "right", continuous = false, kinematic = "certified", kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS))]
fn analyze_json(
    py: Python<'_>,
    scene: &Scene,
    direction: &str,
    continuous: bool,
    kinematic: &str,
    kinematic_max_joints: usize,
) -> PyResult<String> {
    let options = options(direction, continuous, kinematic, kinematic_max_joints)?;
    let scene = &scene.inner;
    let a = py
        .detach(|| analysis::analyse(scene, &options))
        .map_err(|e| analysis_error(py, &e))?;
    to_json(&report::AnalysisReport::new(scene, &a))
}

/// `min-thickness --json` of a scene, as JSON text (the GIL is released while it solves).
#[pyfunction]
#[pyo3(signature = (scene, continuous = false, kinematic_max_joints = analysis::KINEMATIC_DEFAULT_MAX_JOINTS))]
fn min_thickness_json(
    py: Python<'_>,
    scene: &Scene,
    continuous: bool,
    kinematic_max_joints: usize,
) -> PyResult<String> {
    let scene = &scene.inner;
    let (model, t) = py
        .detach(|| -> Result<_, LibAnalysisError> {
            let model = voussoir::scene::build(scene)?;
            let options = analysis::Options {
                static_settings: StaticSettings::default(),
                kinematic_max_joints,
                kinematic: analysis::KinematicMode::Certified,
                continuous,
            };
            let t = voussoir::thickness::analyse(scene, &options)?;
            Ok((model, t))
        })
        .map_err(|e| analysis_error(py, &e))?;
    to_json(&report::MinThicknessReport::new(scene, &model, &t))
}

/// `dem --json` of a scene, as JSON text (the GIL is released while it runs).
#[pyfunction]
#[pyo3(signature = (scene, tolerance = 0.01))]
fn dem_json(py: Python<'_>, scene: &Scene, tolerance: f64) -> PyResult<String> {
    let scene = &scene.inner;
    let options = DemOptions {
        tolerance,
        ..DemOptions::default()
    };
    let d = py
        .detach(|| analysis::dem(scene, &options, &mut |_| {}))
        .map_err(|e| analysis_error(py, &e))?;
    to_json(&report::DemReport::of(scene, &d))
}

/// One varied key's values: a string in the CLI's syntax (`"0.1,0.2"`, `"0.1:0.2:0.01"`), a
/// sequence (list, tuple, range, numpy array) or a single value.
fn variation(key: &str, values: &Bound<'_, PyAny>) -> PyResult<Variation> {
    let py = values.py();
    if values.is_instance_of::<PyString>() {
        let spec: String = values.extract()?;
        return sweep::parse_variation(&format!("{key}={spec}")).map_err(|e| scene_error(py, &e));
    }
    let values = match to_toml(key, values)? {
        Value::Array(a) => a,
        one => vec![one],
    };
    Ok(Variation {
        key: key.to_string(),
        values,
    })
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
    let options = options("right", continuous, kinematic, kinematic_max_joints)?;
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
    let rows = py.detach(|| plan.run(&options, dem, &|| {}));
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
    m.add_function(wrap_pyfunction!(dem_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_rows, m)?)?;
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
