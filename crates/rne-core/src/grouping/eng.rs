//! ENG, the energy-based baseline (paper Sec. VI.C, after Yang & Parasuraman 2020).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::ranked::top_ranked_to_hard;
use crate::grouping::request::GroupingRequest;

/// ENG: within each kind, sort robots by `energy_pct` descending (ties: lower id first) and
/// send the top `quota.hard` to the hard task, the rest to the easy task.
///
/// # Reference
/// `hard_k = argmax_{S ⊆ kind k, |S| = h_k} min_{r ∈ S} energy_r` (the `h_k` highest
/// batteries); paper Sec. VI.C "ENG - Energy-based".
#[derive(Debug, Clone, Copy, Default)]
pub struct Eng;

impl GroupingMethod for Eng {
    fn name(&self) -> &str {
        "eng"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        Ok(top_ranked_to_hard(request, |a, b| {
            b.energy_pct.total_cmp(&a.energy_pct)
        }))
    }
}
