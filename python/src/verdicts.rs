//! `usar.verdicts` and `usar.compare`: claims checked on a sweep's trials known only by their
//! values (the columns of a DataFrame of `usar.sweep`), by the library's
//! [`check_claim_on`], the check `report.md` runs on the same trials; one row per claim and
//! rival, as Python dicts that `python/usar/_verdicts.py` turns into a DataFrame.

use std::collections::HashMap;
use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use usar_report::calibration::ReportOptions;
use usar_report::claims::{
    Claim, ClaimCheck, Claims, Correction, Direction, Observation, Rivals, Test, check_claim,
    check_claim_on,
};
use usar_report::targets::metric_ref::MetricRef;

use crate::errors::value_error;
use crate::methods::claims_of;
use crate::scenario::Scenario;

/// A sweep's trials as columns, one entry per trial in the sweep's order (`trials.csv`'s
/// rows): the method as the sweep spells it, the trial index and the seed.
struct Trials<'a> {
    method: &'a [String],
    trial: &'a [u32],
    seed: &'a [u64],
}

impl Trials<'_> {
    /// The defined values of `column` (NaN is undefined), as observations.
    fn observations<'v>(&'v self, column: &[f64]) -> Vec<Observation<'v>> {
        (0..self.method.len())
            .filter(|&i| !column[i].is_nan())
            .map(|i| Observation {
                method: &self.method[i],
                trial: self.trial[i],
                seed: self.seed[i],
                value: column[i],
            })
            .collect()
    }
}

/// The test named by its claims-file variant (`PairedT`, `Wilcoxon`, `Welch`, `MannWhitney`).
fn test_named(name: &str) -> PyResult<Test> {
    match name {
        "PairedT" => Ok(Test::PairedT),
        "Wilcoxon" => Ok(Test::Wilcoxon),
        "Welch" => Ok(Test::Welch),
        "MannWhitney" => Ok(Test::MannWhitney),
        _ => Err(PyValueError::new_err(format!(
            "test: unknown test {name:?} (PairedT, Wilcoxon, Welch, MannWhitney)"
        ))),
    }
}

/// `claim` checked on `trials` whose metric columns are `columns` (`trials.csv` names; NaN
/// where undefined), for a sweep of `methods` (in its order) and tasks `tasks`.
///
/// # Errors
/// `ValueError` naming `trials` when the claim's metric has no column.
fn check(
    claim: &Claim,
    trials: &Trials<'_>,
    columns: &HashMap<String, Vec<f64>>,
    methods: &[String],
    tasks: &[String],
) -> PyResult<ClaimCheck> {
    let Ok(metric) = claim.metric.resolve(tasks) else {
        // Not tested, saying why, as report.md says it.
        return Ok(check_claim(claim, &[], methods, tasks));
    };
    let name = metric.name(tasks);
    let Some(column) = columns
        .get(&name)
        .filter(|c| c.len() == trials.method.len())
    else {
        return Err(PyValueError::new_err(format!(
            "trials: no column {name} (the metric of claim {})",
            claim.id
        )));
    };
    Ok(check_claim_on(
        claim,
        metric,
        &trials.observations(column),
        methods,
    ))
}

/// The rows of a checked claim: one per rival compared (one with no rival when none was),
/// each a dict of the columns `usar.verdicts` documents. `id` is the claim column (`None`
/// for an ad-hoc comparison).
fn rows<'py>(
    py: Python<'py>,
    c: &ClaimCheck,
    id: Option<&str>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let claim = &c.claim;
    let paired = claim.test.is_paired();
    // report.md's words for the test that ran (`one-sided paired t-test over 10 pairs of
    // trials, alpha 0.05`).
    let ran = if paired && c.reason.is_none() {
        claim.test_words_naming(&c.test_run_words())
    } else {
        claim.test_words()
    };
    let common = |d: &Bound<'py, PyDict>| -> PyResult<()> {
        d.set_item("claim", id)?;
        d.set_item("sentence", &claim.sentence)?;
        d.set_item("method", &c.subject)?;
        d.set_item("metric", &claim.metric.0)?;
        d.set_item("direction", claim.direction.words())?;
        d.set_item("test", claim.test.words())?;
        d.set_item("test_words", &ran)?;
        d.set_item("paired", paired)?;
        d.set_item("alpha", claim.alpha)?;
        d.set_item(
            "correction",
            match claim.correction {
                Correction::None => "none",
                Correction::Holm => "Holm",
            },
        )?;
        d.set_item("n_method", c.subject_summary.n)?;
        d.set_item("mean_method", c.subject_summary.mean)?;
        d.set_item("verdict", c.verdict.words())?;
        d.set_item("reason", c.reason.as_deref())?;
        Ok(())
    };
    if c.comparisons.is_empty() {
        let d = PyDict::new(py);
        common(&d)?;
        return Ok(vec![d]);
    }
    c.comparisons
        .iter()
        .map(|cmp| {
            let d = PyDict::new(py);
            common(&d)?;
            let result = match claim.test {
                Test::PairedT => cmp.paired_t,
                Test::Wilcoxon => cmp.wilcoxon,
                Test::Welch => cmp.welch,
                Test::MannWhitney => cmp.mann_whitney,
            };
            let (n, difference) = if paired {
                (cmp.pairs, cmp.paired_diff)
            } else {
                (
                    c.subject_summary.n + cmp.other_summary.n,
                    c.subject_summary.mean - cmp.other_summary.mean,
                )
            };
            d.set_item("rival", &cmp.other)?;
            let counts = [
                ("n", n),
                ("n_rival", cmp.other_summary.n),
                ("unpaired", cmp.unpaired),
            ];
            for (key, count) in counts {
                d.set_item(key, count)?;
            }
            let numbers = [
                ("mean_rival", cmp.other_summary.mean),
                ("difference", difference),
                ("statistic", result.statistic),
                ("dof", result.dof),
                ("p_raw", result.p),
                ("p_value", cmp.p_adjusted),
                ("p_reverse", cmp.reverse.p),
                ("effect_size", c.effect_size(cmp)),
            ];
            for (key, x) in numbers {
                d.set_item(key, x)?;
            }
            d.set_item("significant", cmp.p_adjusted < claim.alpha)?;
            Ok(d)
        })
        .collect()
}

/// The claims to check: a claims file's path, a list of claims as dicts, or else those the
/// scenario's `report` section names (resolved as a sweep's report resolves them).
///
/// # Errors
/// `ValueError` for a claims file that does not read or check, or naming `scenario` when
/// neither claims nor a scenario naming a claims file is given.
fn claims_to_check(
    claims: Option<&Bound<'_, PyAny>>,
    scenario: Option<&Scenario>,
    methods: &[String],
    tasks: &[String],
) -> PyResult<Claims> {
    if let Some(list) = claims {
        if let Ok(path) = list.extract::<PathBuf>() {
            let c = Claims::load(&path).map_err(value_error)?;
            c.check_tasks(tasks).map_err(value_error)?;
            c.check_methods(methods).map_err(value_error)?;
            return Ok(c);
        }
        return claims_of(list, tasks, methods);
    }
    let Some(s) = scenario else {
        return Err(PyValueError::new_err(
            "scenario: give the sweep's scenario (whose report.claims names its claims) or claims=",
        ));
    };
    let report =
        ReportOptions::resolve(None, None, s.inner(), s.path(), methods).map_err(value_error)?;
    report.claims.ok_or_else(|| {
        PyValueError::new_err(format!(
            "scenario: {} names no claims file that exists (its report.claims); give claims=",
            s.path().display()
        ))
    })
}

/// Checks the claims (`claims`: a claims file's path or a list of claims as dicts; `None`:
/// those `scenario`'s `report.claims` names) on a sweep's trials given as columns: `method`,
/// `trial`, `seed` (one entry per trial, the sweep's order) and `columns` (`trials.csv`'s
/// metric columns by name, NaN where undefined), for the sweep's `methods` (in its order)
/// and `tasks`. `test` (`PairedT`, `Wilcoxon`, `Welch`, `MannWhitney`) replaces every
/// claim's own test. Returns the claims' origin and one dict per claim and rival
/// ([`rows`]), in the claims' order, rivals in sweep order.
///
/// # Errors
/// `ValueError` for bad claims, an unknown test, columns of unequal lengths or a missing
/// metric column.
#[pyfunction]
#[pyo3(signature = (claims, scenario, methods, tasks, method, trial, seed, columns, test = None))]
#[allow(clippy::too_many_arguments)]
pub fn claim_verdicts<'py>(
    py: Python<'py>,
    claims: Option<&Bound<'py, PyAny>>,
    scenario: Option<&Scenario>,
    methods: Vec<String>,
    tasks: Vec<String>,
    method: Vec<String>,
    trial: Vec<u32>,
    seed: Vec<u64>,
    columns: HashMap<String, Vec<f64>>,
    test: Option<String>,
) -> PyResult<(String, Vec<Bound<'py, PyDict>>)> {
    let trials = trials_of(&method, &trial, &seed)?;
    let test = test.as_deref().map(test_named).transpose()?;
    let claims = claims_to_check(claims, scenario, &methods, &tasks)?;
    let mut out = Vec::new();
    for claim in claims.claims() {
        let mut claim = claim.clone();
        if let Some(t) = test {
            claim.test = t;
        }
        let c = check(&claim, &trials, &columns, &methods, &tasks)?;
        out.extend(rows(py, &c, Some(&claim.id))?);
    }
    Ok((claims.origin().to_owned(), out))
}

/// The trial columns, checked for equal lengths.
fn trials_of<'a>(method: &'a [String], trial: &'a [u32], seed: &'a [u64]) -> PyResult<Trials<'a>> {
    if trial.len() != method.len() || seed.len() != method.len() {
        return Err(PyValueError::new_err(
            "trials: the method, trial and seed columns differ in length",
        ));
    }
    Ok(Trials {
        method,
        trial,
        seed,
    })
}

/// An ad-hoc comparison: `subject` against each of `rivals` on `metric` (a `trials.csv`
/// column name; `values` its column, NaN where undefined), `direction` `More` or `Less`
/// being better, by `test` (as [`claim_verdicts`]) at one-sided level `alpha`, each rival a
/// claim of its own (no correction). Trials as [`claim_verdicts`]. Returns one dict per
/// rival ([`rows`], the claim column `None`).
///
/// # Errors
/// `ValueError` for an unknown test or direction, a metric that is no `trials.csv` column
/// for `tasks`, or columns of unequal lengths.
#[pyfunction]
#[pyo3(signature = (subject, rivals, metric, direction, test, alpha, methods, tasks, method, trial, seed, values))]
#[allow(clippy::too_many_arguments)]
pub fn compare_values<'py>(
    py: Python<'py>,
    subject: String,
    rivals: Vec<String>,
    metric: String,
    direction: &str,
    test: &str,
    alpha: f64,
    methods: Vec<String>,
    tasks: Vec<String>,
    method: Vec<String>,
    trial: Vec<u32>,
    seed: Vec<u64>,
    values: Vec<f64>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let trials = trials_of(&method, &trial, &seed)?;
    let direction = match direction {
        "More" => Direction::More,
        "Less" => Direction::Less,
        _ => {
            return Err(PyValueError::new_err(format!(
                "direction: {direction:?} is neither More nor Less"
            )));
        }
    };
    let test = test_named(test)?;
    let metric_ref = MetricRef(metric);
    metric_ref
        .resolve(&tasks)
        .map_err(|e| PyValueError::new_err(format!("metric: {e}")))?;
    let columns = HashMap::from([(metric_ref.0.clone(), values)]);
    let mut out = Vec::new();
    for rival in rivals {
        let claim = Claim {
            id: "compare".into(),
            sentence: format!("{subject} against {rival}"),
            subject: subject.clone(),
            rivals: Rivals::Only(vec![rival]),
            metric: metric_ref.clone(),
            direction,
            test,
            alpha,
            correction: Correction::None,
        };
        let c = check(&claim, &trials, &columns, &methods, &tasks)?;
        out.extend(rows(py, &c, None)?);
    }
    Ok(out)
}
