//! rne-core as Python functions: `usar.trust` (agent-to-agent RNE trust, paper Eq. 7) and
//! the built-in grouping methods applied to one request (`usar.rne`, `dis`, `eng`,
//! `hp_dis`); and usar-sim's seed of a sweep's trial (`usar.gym.trial_seed`).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rne_core::grouping::{GroupingRequest, RobotSnapshot, method_from_name};
use rne_core::{NeedsVector, TrustModel, Weights};

use crate::errors::{chain_value_error, value_error};
use crate::scenario::Scenario;

/// Trust of robot A in robot B, nats (paper Eq. 7, `TrustModel::agent_agent`).
///
/// # Errors
/// `ValueError` for weights or needs that are empty, of different lengths, negative or not
/// finite.
#[pyfunction]
pub fn trust(weights: Vec<f64>, needs_a: Vec<f64>, needs_b: Vec<f64>) -> PyResult<f64> {
    let model = TrustModel::with_weights(Weights::new(weights).map_err(value_error)?);
    let a = NeedsVector::new(needs_a).map_err(value_error)?;
    let b = NeedsVector::new(needs_b).map_err(value_error)?;
    model.agent_agent(&a, &b).map_err(value_error)
}

/// The seed of trial `trial` of a sweep under the base seed `base_seed` (`sim.seed` or
/// `--seed`): `usar_sim::mission::trial_seed`, the splitmix64 output for the state
/// `base_seed + trial` (wrapping), the seed `usar.run(trial=k)` and `usar run --trial K` use.
/// PyO3 refuses a negative or too large argument (`OverflowError`); `usar.gym.trial_seed`
/// checks the arguments first.
#[pyfunction]
pub fn trial_seed(base_seed: u64, trial: u32) -> u64 {
    usar_sim::mission::trial_seed(base_seed, trial)
}

/// Reads `key` of the raw request.
fn item<'py, T>(raw: &Bound<'py, PyDict>, key: &str) -> PyResult<T>
where
    T: for<'a> FromPyObject<'a, 'py>,
    for<'a> <T as FromPyObject<'a, 'py>>::Error: Into<PyErr>,
{
    let v = raw
        .get_item(key)?
        .ok_or_else(|| value_error(format!("request: no {key:?}")))?;
    v.extract::<T>().map_err(|e| {
        let e: PyErr = e.into();
        value_error(format!("request: {key}: {e}"))
    })
}

/// The rne-core request of a raw request dict (the keys `PyMethod` makes).
fn request_of(raw: &Bound<'_, PyDict>) -> PyResult<GroupingRequest> {
    let ids: Vec<usize> = item(raw, "ids")?;
    let kinds: Vec<usize> = item(raw, "kinds")?;
    let needs: Vec<Vec<f64>> = item(raw, "needs")?;
    let energy: Vec<f64> = item(raw, "energy_pct")?;
    let hp: Vec<f64> = item(raw, "hp_pct")?;
    let dist: Vec<Vec<f64>> = item(raw, "distance_to_goal_m")?;
    let n = ids.len();
    if [kinds.len(), needs.len(), energy.len(), hp.len(), dist.len()]
        .iter()
        .any(|&l| l != n)
    {
        return Err(value_error("request: robot fields of different lengths"));
    }
    let robots = (0..n)
        .map(|i| {
            Ok(RobotSnapshot {
                id: ids[i],
                kind: kinds[i],
                needs: NeedsVector::new(needs[i].clone()).map_err(value_error)?,
                energy_pct: energy[i],
                hp_pct: hp[i],
                distance_to_goal_m: dist[i].clone(),
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    GroupingRequest::new(robots, item(raw, "quotas")?, item(raw, "hardest_first")?)
        .map_err(value_error)
}

/// Groups `raw` with the built-in method `name`; RNE's trust model is the scenario's (its
/// `needs_weights`) or the one of `weights`. Returns one sorted list of ids per task.
///
/// # Errors
/// `ValueError` for an unknown name, a bad request or weights, or RNE without either.
#[pyfunction]
#[pyo3(signature = (name, raw, scenario = None, weights = None))]
pub fn builtin_group(
    name: &str,
    raw: &Bound<'_, PyDict>,
    scenario: Option<&Scenario>,
    weights: Option<Vec<f64>>,
) -> PyResult<Vec<Vec<usize>>> {
    let request = request_of(raw)?;
    let model = match (weights, scenario) {
        (Some(w), _) => TrustModel::with_weights(Weights::new(w).map_err(value_error)?),
        (None, Some(s)) => {
            usar_sweep::sweep::trust_model(s.inner()).map_err(|e| chain_value_error(&e))?
        }
        (None, None) => {
            let j = request.robots()[0].needs.len();
            TrustModel::with_weights(Weights::new(vec![1.0; j]).map_err(value_error)?)
        }
    };
    let method = method_from_name(name, &model).map_err(value_error)?;
    Ok(method.group(&request).map_err(value_error)?.groups)
}
