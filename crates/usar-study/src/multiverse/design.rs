//! A design shared by the universes' calibrations (`usar multiverse --design N`): `N`
//! evaluations spread over the universes and the free ranges, run before any universe, whose
//! statistics the emulator ([`super::emulator`]) is fitted to.
//!
//! Point `j` of the design takes the universe at position `j mod U` of the universes the
//! multiverse runs (`U` of them, in universe order), so every universe gets `N / U` points
//! or one more, and free values from a Latin hypercube of `N` points in `[0, 1]^d`
//! (McKay, Beckman & Conover 1979: in each dimension one point per `1/N` slice, the slices
//! paired by independent random permutations, the point uniform in its slice; ChaCha8 seeded
//! by the calibration seed), mapped onto each free range (log ranges on the log scale) and
//! rounded as a calibration rounds them. It is evaluated as a calibration evaluates a point
//! (`--methods` x `--calibration-trials` trials from `--calibration-seed`, no check on unseen
//! trials) and kept as `design/d<j>.json`, one checksummed line
//! (`{"design":{...},"sum":"..."}`, as a universe's record), so a killed design continues
//! where it stopped and shards (point `j` to shard `j mod N`) share the folder.
//!
//! Reference: M. D. McKay, R. J. Beckman and W. J. Conover (1979), "A comparison of three
//! methods for selecting values of input variables in the analysis of output from a
//! computer code", Technometrics 21(2):239-245.

use std::path::{Path, PathBuf};

use rand::RngExt;
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use usar_sim::scenario::path_text;

use super::error::MultiverseError;
use super::setup::MultiverseSetup;
use super::universe::Universe;
use crate::calibrate::{Evaluator, FreeField};
use usar_report::targets::float_text;
use usar_sweep::atomic::{FileError, write_atomic};
use usar_sweep::bounded_file::{MAX_MULTIVERSE_PLAN_BYTES, read_small};
use usar_sweep::checked_log::{record_line, verified_record};
use usar_sweep::vary::apply_overrides;

/// What the functions of this module return.
type Result<T, E = MultiverseError> = std::result::Result<T, E>;

/// The design's folder under the output folder.
pub const DESIGN_DIR: &str = "design";

/// One evaluated point of the design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignPoint {
    /// Position in the design, from 0.
    pub index: usize,
    /// The universe's index in the full factorial.
    pub universe: u64,
    /// The free values (rounded), in `--free` order: exactly what ran.
    pub values: Vec<f64>,
    /// Each target's statistic, in target order (NaN when undefined, or when nothing ran).
    #[serde(with = "float_text::vec")]
    pub statistics: Vec<f64>,
    /// Why nothing ran (the universe breaks a rule) or trials failed; `None` when all ran.
    pub message: Option<String>,
}

/// The design's points before they run: for point `j`, the position of its universe among
/// `universes` and its free values (rounded to `digits`), as the module documentation says.
/// Empty for `n = 0` or no universe.
pub fn design_plan(
    n: usize,
    universes: usize,
    free: &[FreeField],
    digits: u32,
    seed: u64,
) -> Vec<(usize, Vec<f64>)> {
    if n == 0 || universes == 0 {
        return Vec::new();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let columns: Vec<Vec<f64>> = free
        .iter()
        .map(|f| {
            let mut slices: Vec<usize> = (0..n).collect();
            slices.shuffle(&mut rng);
            slices
                .into_iter()
                .map(|s| f.from_unit((s as f64 + rng.random::<f64>()) / n as f64, digits))
                .collect()
        })
        .collect();
    (0..n)
        .map(|j| (j % universes, columns.iter().map(|c| c[j]).collect()))
        .collect()
}

/// The file of design point `index` in the output folder `root` (`design/d0007.json`: at
/// least four digits, as many as the design's last index has).
pub fn point_path(root: &Path, index: usize, design: usize) -> PathBuf {
    let width = design.saturating_sub(1).to_string().len().max(4);
    root.join(DESIGN_DIR).join(format!("d{index:0width$}.json"))
}

impl DesignPoint {
    /// Writes the point into its file under `root`, atomically, checksummed with the
    /// multiverse's `identity_sum`.
    ///
    /// # Errors
    /// An I/O error.
    pub fn write(&self, root: &Path, design: usize, identity_sum: &str) -> Result<()> {
        let json = serde_json::to_string(self).map_err(|source| MultiverseError::Serialise {
            what: "a design point",
            source,
        })?;
        let line = record_line("design", &json, identity_sum);
        let path = point_path(root, self.index, design);
        let folder = path.parent().unwrap_or(root);
        std::fs::create_dir_all(folder).map_err(FileError::io(format!(
            "creating folder {}",
            path_text(folder)
        )))?;
        Ok(write_atomic(&path, line.as_bytes())?)
    }

    /// Reads design point `index` under `root` for the multiverse with `identity_sum`, `free`
    /// free fields and `targets` targets: `None` when it is missing, or does not verify
    /// (edited, damaged, another multiverse's, or not of that many values; it runs again).
    pub fn read(
        root: &Path,
        index: usize,
        design: usize,
        identity_sum: &str,
        (free, targets): (usize, usize),
    ) -> Option<Self> {
        // Bounded, and a FIFO or device is refused, not waited on (issue 70).
        let bytes = read_small(&point_path(root, index, design), MAX_MULTIVERSE_PLAN_BYTES);
        let text = String::from_utf8(bytes.ok()?).ok()?;
        let json = verified_record(&text, "design", identity_sum)?;
        let point: Self = serde_json::from_str(json).ok()?;
        (point.index == index && point.values.len() == free && point.statistics.len() == targets)
            .then_some(point)
    }
}

/// Evaluates design point `index` (universe `u`, free `values`) of `setup`'s multiverse,
/// as a calibration of that universe evaluates a point (no check on unseen trials). A
/// universe that breaks a rule, or targets its axes cannot flag, give a point with only a
/// message.
///
/// # Errors
/// The thread pool cannot be started.
pub fn evaluate_point(
    setup: &MultiverseSetup,
    index: usize,
    u: &Universe,
    values: &[f64],
) -> Result<DesignPoint> {
    let n = setup.targets.targets().len();
    let mut point = DesignPoint {
        index,
        universe: u.index,
        values: values.to_vec(),
        statistics: vec![f64::NAN; n],
        message: None,
    };
    let overrides = setup.axes.universe_overrides(&u.choices);
    let spec = match apply_overrides(&setup.base, &overrides) {
        Ok(s) => s,
        Err((i, e)) => {
            point.message = Some(format!("set {}: {e}", overrides[i].brief()));
            return Ok(point);
        }
    };
    let targets = match setup.axes.universe_targets(&u.choices, &setup.targets) {
        Ok(t) => t,
        Err(e) => {
            point.message = Some(format!("targets: {}", e.0.message));
            return Ok(point);
        }
    };
    let mut calibration =
        setup.calibration_setup(spec, targets, setup.origin.clone(), String::new());
    calibration.check_trials = 0;
    let checked = match calibration.check() {
        Ok(c) => c,
        Err(e) => {
            point.message = Some(e.to_string());
            return Ok(point);
        }
    };
    let e = Evaluator::new(&calibration, &checked)?.evaluate(values);
    point.statistics = e.statistics;
    point.message = e.message;
    Ok(point)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn free() -> Vec<FreeField> {
        vec![
            FreeField::parse("mission.pickup_s=0.5..2").unwrap(),
            FreeField::parse("mission.hp_pct_per_step_in_radiation=0.001..0.1:log").unwrap(),
        ]
    }

    #[test]
    fn the_design_is_a_latin_hypercube_dealt_round_the_universes() {
        let f = free();
        let plan = design_plan(20, 3, &f, 17, 5);
        assert_eq!(plan.len(), 20);
        assert_eq!(
            plan.iter().map(|p| p.0).collect::<Vec<_>>(),
            (0..20).map(|j| j % 3).collect::<Vec<_>>()
        );
        for (d, field) in f.iter().enumerate() {
            let mut slices: Vec<usize> = plan
                .iter()
                .map(|p| (field.to_unit(p.1[d]) * 20.0 - 1e-9).floor() as usize)
                .collect();
            slices.sort_unstable();
            assert_eq!(slices, (0..20).collect::<Vec<_>>(), "one point per slice");
        }
        assert_eq!(plan, design_plan(20, 3, &f, 17, 5), "seeded");
        assert_ne!(plan, design_plan(20, 3, &f, 17, 6));
        assert!(design_plan(0, 3, &f, 4, 5).is_empty());
    }

    #[test]
    fn a_point_reads_back_only_for_its_multiverse_and_index() {
        let dir = tempfile::tempdir().unwrap();
        let p = DesignPoint {
            index: 7,
            universe: 12,
            values: vec![1.5, 0.01],
            statistics: vec![3.0, f64::NAN],
            message: None,
        };
        p.write(dir.path(), 100, "abc").unwrap();
        assert!(point_path(dir.path(), 7, 100).ends_with("design/d0007.json"));
        let back = DesignPoint::read(dir.path(), 7, 100, "abc", (2, 2)).unwrap();
        assert_eq!(back.values, p.values);
        assert!(back.statistics[1].is_nan());
        assert!(DesignPoint::read(dir.path(), 7, 100, "abd", (2, 2)).is_none());
        assert!(DesignPoint::read(dir.path(), 8, 100, "abc", (2, 2)).is_none());
        assert!(DesignPoint::read(dir.path(), 7, 100, "abc", (3, 2)).is_none());
        assert!(DesignPoint::read(dir.path(), 7, 100, "abc", (2, 1)).is_none());
    }
}
