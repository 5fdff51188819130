//! ENG, the energy-based baseline (paper Sec. VI.C, after Yang & Parasuraman 2020).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::ranked::fill_from_hardest;
use crate::grouping::request::GroupingRequest;

/// ENG: within each kind, sort robots by `energy_pct` descending (ties: lower id first) and
/// fill the tasks from the hardest down, each with its quota for the kind: the highest
/// batteries go to the hardest task. Two tasks: the top `quota[hard]` go hard, the rest easy.
/// `O(n log n)`.
///
/// # Reference
/// Per kind, rank by `(-energy_r, id_r)`; the first `q[t_1]` go to the hardest task `t_1`, the
/// next `q[t_2]` to `t_2`, ...; paper Sec. VI.C "ENG - Energy-based".
#[derive(Debug, Clone, Copy, Default)]
pub struct Eng;

impl GroupingMethod for Eng {
    fn name(&self) -> &str {
        "eng"
    }

    /// `ENG`, the paper's name (Sec. VI.C).
    fn display_name(&self) -> &str {
        "ENG"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        Ok(fill_from_hardest(request, |a, b| {
            b.energy_pct.total_cmp(&a.energy_pct)
        }))
    }
}
