//! `usar.Scenario`: a validated scenario with the RON source it came from, edited by field
//! path (`set`, `update`: the paths and values of `usar sweep --vary` and `usar check --set`),
//! written back as RON (`to_ron`, as `usar check --print`) and summarised as data (`check`).

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use usar_sim::scenario::{self as sc, ScenarioSpec, path_text};

use serde_json::Value;
use usar_sweep::spec_ron::spec_to_ron;
use usar_sweep::vary::{
    FieldPath, Override, Step, apply_overrides, brief, spec_from_json, spec_json,
    validate_overridden,
};

use crate::errors::{ScenarioWarning, chain_value_error, value_error};
use crate::json_value::{from_python, to_python, values_at};
use crate::ron_value::ron_text;

/// A validated scenario: `Scenario.load(path)`, `Scenario.from_ron(text)` or
/// `Scenario.from_dict(data)`; edited by field path into a new one (`s.set("kinds[0].count",
/// 8)`, `s.update({...})`), read by path (`s.get("mission.duration_s")`, `s.to_dict()`),
/// written as RON (`s.to_ron()`) and summarised (`s.check()`). Immutable, compared by value,
/// picklable. A bad file or edit is a `ValueError` naming the file, line and field; what
/// `usar check` warns about is a `usar.ScenarioWarning`. Pass it to `usar.run` and
/// `usar.sweep`. docs/python.md has the whole of it.
#[pyclass(module = "usar", frozen)]
#[derive(Clone)]
pub struct Scenario {
    /// The RON source it was read from (errors point into it).
    text: String,
    /// The file's path as errors name it, or `<string>` for `from_ron`.
    origin: String,
    /// The path it was loaded from (the folder of a `report.targets` file).
    path: PathBuf,
    /// Every `set` so far, in order.
    overrides: Vec<Override>,
    /// The source's spec with the overrides applied.
    spec: ScenarioSpec,
    /// The validated scenario.
    scenario: sc::Scenario,
}

impl Scenario {
    /// The validated scenario.
    pub fn inner(&self) -> &sc::Scenario {
        &self.scenario
    }

    /// The path it was loaded from (`<string>` for one made from text).
    pub fn path(&self) -> &std::path::Path {
        &self.path
    }

    /// Its spec (the source with every `set` applied), unvalidated as a calibration takes it.
    pub fn spec(&self) -> &ScenarioSpec {
        &self.spec
    }

    /// Its file's path as errors name it (`<string>` for one made from text).
    pub fn origin_text(&self) -> &str {
        &self.origin
    }

    fn from_text(text: String, origin: String, path: PathBuf) -> PyResult<Self> {
        let spec = sc::parse_spec(&text, &origin).map_err(value_error)?;
        let scenario = sc::validate_in_source(&spec, &text, &origin).map_err(value_error)?;
        Ok(Self {
            text,
            origin,
            path,
            overrides: Vec::new(),
            spec,
            scenario,
        })
    }

    /// `self`, after warning (a [`ScenarioWarning`] each) about what `usar check` warns
    /// about: `ORIGIN: tasks.west: no kind has a quota for it; the task is never worked`.
    ///
    /// # Errors
    /// A warning the Python warning filters turn into an error.
    fn warned(self, py: Python<'_>) -> PyResult<Self> {
        let category = py.get_type::<ScenarioWarning>();
        for w in usar_sim::mission::scenario_warnings(&self.scenario) {
            let text = format!("{}: {w}", self.origin).replace('\0', " ");
            let message = std::ffi::CString::new(text).map_err(value_error)?;
            PyErr::warn(py, category.as_any(), &message, 1)?;
        }
        Ok(self)
    }

    /// The spec's JSON form (what field paths walk).
    fn json(&self) -> PyResult<Value> {
        spec_json(&self.spec).map_err(value_error)
    }

    /// A copy with `more` overrides applied after the earlier ones, validated once.
    fn with(&self, more: Vec<Override>) -> PyResult<Self> {
        let mut overrides = self.overrides.clone();
        overrides.extend(more);
        let base = sc::parse_spec(&self.text, &self.origin).map_err(value_error)?;
        let spec = apply_overrides(&base, &overrides)
            .map_err(|(i, e)| value_error(format!("set {}: {e}", overrides[i].brief())))?;
        let scenario = validate_overridden(&spec, &self.text, &self.origin, "set", &overrides)
            .map_err(value_error)?;
        Ok(Self {
            text: self.text.clone(),
            origin: self.origin.clone(),
            path: self.path.clone(),
            overrides,
            spec,
            scenario,
        })
    }
}

/// One `FIELD=VALUE` override from a path and a Python value, for the spec whose JSON form is
/// `json`. Where the path names text (a name, the description, a file path, a unit variant
/// such as `Aerial`), a `str` is read as RON when the field takes it so
/// (`Threshold(below_pct: 50.0, factor: 0.6)`, `Aerial`) and else as the text itself (`my
/// paper`), `None` clears an optional field, and a number or bool is refused; elsewhere a `str`
/// is RON text (`"Some(3)"`) and other values are converted ([`ron_text`]).
fn override_of(json: &Value, path: &str, value: &Bound<'_, PyAny>) -> PyResult<Override> {
    let fail = |e: String| value_error(format!("set {path}: {e}"));
    let parse = |ron: &str| {
        let arg = format!("{path}={ron}");
        Override::parse(&arg).map_err(|e| value_error(format!("set {}: {e}", brief(&arg))))
    };
    // A path that names nothing is refused by the override's own message.
    let field = FieldPath::parse(path).ok();
    let current = field.as_ref().and_then(|f| values_at(json, f).ok());
    let text_field = match (&current, &field) {
        (Some(Value::String(_)), _) => true,
        (Some(Value::Array(all)), Some(f)) => {
            has_all(f) && !all.is_empty() && all.iter().all(Value::is_string)
        }
        _ => false,
    };
    if !text_field {
        return parse(&ron_text(value).map_err(fail)?);
    }
    if let Ok(text) = value.extract::<String>() {
        if let Ok(o) = parse(&text)
            && takes(json, &o)
        {
            return Ok(o);
        }
        return parse(&ron::to_string(&text).map_err(|e| fail(e.to_string()))?);
    }
    if value.is_none() {
        return parse("None");
    }
    Err(fail(format!(
        "expected a str (the field holds text), found {}",
        value
            .get_type()
            .name()
            .map_or_else(|_| "?".into(), |n| n.to_string())
    )))
}

/// Whether the spec whose JSON form is `json` still reads as a spec with `o` applied (its
/// value of the field's type; the rules are checked later).
fn takes(json: &Value, o: &Override) -> bool {
    let mut copy = json.clone();
    o.apply(&mut copy).is_ok() && spec_from_json(copy).is_ok()
}

/// Whether `path` has a `[*]` step (its values are a list of every element's).
fn has_all(path: &FieldPath) -> bool {
    path.steps().iter().any(|s| matches!(s, Step::All))
}

#[pymethods]
impl Scenario {
    /// Reads and validates a scenario file (RON).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let text = crate::read_file::read_source_interruptibly(py, &path)?;
        Self::from_text(text, path_text(&path), path)?.warned(py)
    }

    /// Validates a scenario given as RON text; `origin` names it in errors.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_ron(py: Python<'_>, text: String, origin: &str) -> PyResult<Self> {
        Self::from_text(text, origin.to_string(), PathBuf::from(origin))?.warned(py)
    }

    /// A copy with one field set (validated at once): `s.set("kinds[0].count", 8)`,
    /// `s.set("kinds[*].max_speed_m_per_s", 1.2)`, `s.set("name", "my paper")` (a `str` on a
    /// text field is the text; elsewhere RON, `"Some(3)"`), `None` clears an optional field.
    /// A bad path or value is a `ValueError` naming the field (with the nearest name); what
    /// `usar check` warns about is a `usar.ScenarioWarning`.
    fn set(&self, py: Python<'_>, path: &str, value: &Bound<'_, PyAny>) -> PyResult<Self> {
        let json = self.json()?;
        self.with(vec![override_of(&json, path, value)?])?
            .warned(py)
    }

    /// A copy with several fields set in order, validated once at the end.
    fn update(&self, py: Python<'_>, fields: &Bound<'_, PyDict>) -> PyResult<Self> {
        let json = self.json()?;
        let more = fields
            .iter()
            .map(|(k, v)| override_of(&json, &k.extract::<String>()?, &v))
            .collect::<PyResult<Vec<_>>>()?;
        self.with(more)?.warned(py)
    }

    /// The scenario as RON, every field written out (as `usar check --print`).
    fn to_ron(&self) -> PyResult<String> {
        let hash = usar_sweep::fingerprint::scenario_hash(&self.scenario)
            .map_err(|e| chain_value_error(&e))?;
        let mut head = format!("{}, scenario hash {hash}", self.origin);
        if !self.overrides.is_empty() {
            let sets: Vec<String> = self.overrides.iter().map(ToString::to_string).collect();
            head = format!(
                "{} with {}, scenario hash {hash}",
                self.origin,
                sets.join(", ")
            );
        }
        spec_to_ron(&self.spec, &[head]).map_err(|e| chain_value_error(&e))
    }

    /// What `usar check` prints, as a dict of plain values: `name`, `description`, `arena`,
    /// `dt_s`, `duration_s`, `steps`, `seed`, `kinds` (with `quota` by task), `tasks`
    /// (`rank` 0 = the hardest, `quota` by kind, goals and areas in metres), `robots` (`id`,
    /// `kind`, `kind_index`, `start_m`, `distance_to_goal_m`), `rest_stations`, debris,
    /// `radiation_zones`, `hash` (the scenario hash), `needs_len` and `mission` (every
    /// mission parameter, as the scenario file names it). Keys in full: `usar/_usar.pyi`.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::check_data::summary(py, &self.scenario)
    }

    /// The overrides applied so far, as `FIELD=VALUE` texts.
    #[getter]
    fn overrides<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, self.overrides.iter().map(ToString::to_string))
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> String {
        self.scenario.name().to_string()
    }

    /// The origin errors name (the file's path, or `<string>`).
    #[getter]
    fn origin(&self) -> String {
        self.origin.clone()
    }

    /// The task names, in the scenario's order.
    #[getter]
    fn task_names(&self) -> Vec<String> {
        self.scenario.task_names()
    }

    /// The value at a field path (any path `set` takes), as Python data; a `[*]` path gives
    /// the list of every element's value.
    fn get<'py>(&self, py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyAny>> {
        let fail = |e: String| value_error(format!("get {path}: {e}"));
        let field = FieldPath::parse(path).map_err(fail)?;
        to_python(py, &values_at(&self.json()?, &field).map_err(fail)?)
    }

    /// Every field as Python data (dicts, lists, str, numbers, bool, None): the JSON form of
    /// the scenario, an enum variant with data as a one-key dict (`{"Grid": {...}}`), an
    /// optional value as the value or None.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.json()?)
    }

    /// A scenario from the data `to_dict` gives; `origin` names it in errors, which point
    /// into its RON text (`to_ron`); `path` (default `origin`) is the file its relative paths
    /// (`report.targets`) are read beside.
    #[staticmethod]
    #[pyo3(signature = (data, origin = "<dict>", path = None))]
    fn from_dict(
        py: Python<'_>,
        data: &Bound<'_, PyAny>,
        origin: &str,
        path: Option<PathBuf>,
    ) -> PyResult<Self> {
        // A NaN's place, after the origin as every error of the data (a TypeError as it is).
        let json = from_python(data, "").map_err(|e| {
            if e.is_instance_of::<PyValueError>(py) {
                value_error(format!("{origin}: {}", e.value(py)))
            } else {
                e
            }
        })?;
        let spec = spec_from_json(json).map_err(|e| value_error(format!("{origin}: {e}")))?;
        let text = spec_to_ron(&spec, &[origin.to_string()]).map_err(|e| chain_value_error(&e))?;
        let path = path.unwrap_or_else(|| PathBuf::from(origin));
        Self::from_text(text, origin.to_string(), path)?.warned(py)
    }

    /// Equal when every field is (wherever each was read from, however it was edited).
    fn __eq__(&self, other: &Self) -> PyResult<bool> {
        Ok(self.json()? == other.json()?)
    }

    fn __hash__(&self) -> PyResult<u64> {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.json()?.to_string().hash(&mut h);
        Ok(h.finish())
    }

    /// Pickling (and so `copy`, `multiprocessing`, joblib): rebuilt from its source text,
    /// origin, path and overrides.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let restore = py.get_type::<Self>().getattr("_restore")?;
        let sets: Vec<String> = self.overrides.iter().map(ToString::to_string).collect();
        let args = (
            self.text.clone(),
            self.origin.clone(),
            path_text(&self.path),
            sets,
        )
            .into_pyobject(py)?;
        Ok((restore, args))
    }

    /// The inverse of `__reduce__` (not for direct use).
    #[staticmethod]
    fn _restore(text: String, origin: String, path: String, sets: Vec<String>) -> PyResult<Self> {
        let base = Self::from_text(text, origin, PathBuf::from(path))?;
        let overrides = sets
            .iter()
            .map(|a| Override::parse(a).map_err(value_error))
            .collect::<PyResult<Vec<_>>>()?;
        if overrides.is_empty() {
            return Ok(base);
        }
        base.with(overrides)
    }

    /// A table for notebooks: the name, origin and edits, the kinds (role, locomotion,
    /// count) and the tasks, HTML-escaped.
    fn _repr_html_(&self) -> String {
        let esc = |t: &str| {
            t.replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;")
                .replace('"', "&quot;")
        };
        let s = &self.scenario;
        let mut h = format!(
            "<div><b>usar.Scenario</b> {} <small>from {}</small>",
            esc(s.name()),
            esc(&self.origin)
        );
        for o in &self.overrides {
            h += &format!("<br><small>set {}</small>", esc(&o.to_string()));
        }
        h += "<table><tr><th>kind</th><th>role</th><th>locomotion</th><th>robots</th></tr>";
        for k in s.kinds() {
            h += &format!(
                "<tr><td>{}</td><td>{:?}</td><td>{:?}</td><td>{}</td></tr>",
                esc(&k.name),
                k.role,
                k.locomotion,
                k.count
            );
        }
        h += &format!(
            "</table><small>tasks: {}; {} s per trial</small></div>",
            esc(&s.task_names().join(", ")),
            s.mission().duration_s
        );
        h
    }

    fn __repr__(&self) -> String {
        let sets: Vec<String> = self.overrides.iter().map(ToString::to_string).collect();
        let with = if sets.is_empty() {
            String::new()
        } else {
            format!(" with {}", sets.join(", "))
        };
        format!(
            "<usar.Scenario {} from {}{with}>",
            self.scenario.name(),
            self.origin
        )
    }
}
