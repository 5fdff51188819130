//! Grouping methods by name: the [`MethodFactory`] a sweep builds each trial's method with
//! (the extension point for methods of your own), the [`TrialContext`] it builds them for
//! (trial, seed and a seeded random stream for the method), and the trust model.

use std::sync::Arc;

use rand::SeedableRng;
use rne_core::TrustModel;
use rne_core::grouping::{GroupingMethod, method_from_name};
use usar_sim::mission::trial_seed;
use usar_sim::scenario::Scenario;

/// The random number generator of [`TrialContext::rng`]: ChaCha with 8 rounds from
/// `rand_chacha` 0.10, whose output for a given seed and stream is documented as portable
/// and reproducible (the same on every platform and thread count). Use it with the traits of
/// [`rand`] (`rand::RngExt` for `random_range`, `rand::seq::SliceRandom` for `shuffle`).
pub use rand_chacha::ChaCha8Rng;

/// The `rand` crate (0.10) that [`ChaCha8Rng`] works with, so that a method of your own can
/// draw from it without a `rand` dependency of its own at a matching version
/// (`use usar_sweep::sweep::rand::seq::SliceRandom;`).
pub use rand;

/// The ChaCha stream [`TrialContext::rng`] draws from. The trial's starting team is drawn
/// from stream 0 of the same seed ([`usar_sim::mission::draw_initial_levels`]), so a method's
/// draws are independent of it and never change the simulation's own random numbers.
pub const METHOD_RNG_STREAM: u64 = 1;

/// The trial a [`MethodFactory`] builds a method for.
///
/// Trial `k` of a sweep has the same context for every method and every grid cell (common
/// random numbers: the same starting team, and the same method stream). It depends only on
/// the sweep's base seed and `k`, never on the thread count or the order trials finish in,
/// so a method that draws its random numbers from [`rng`](Self::rng) is reproducible.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct TrialContext {
    /// Trial index from 0, as in the `trial` column of `trials.csv`.
    pub trial: u32,
    /// The trial's seed, `trial_seed(base_seed, trial)`
    /// ([`usar_sim::mission::trial_seed`]); its starting team is drawn from it.
    pub seed: u64,
}

impl TrialContext {
    /// The context of trial `trial` whose seed is `seed` (as given; see
    /// [`for_trial`](Self::for_trial) for a sweep's).
    pub fn new(trial: u32, seed: u64) -> Self {
        Self { trial, seed }
    }

    /// Trial `trial` of a sweep with base seed `base_seed`: seed
    /// `trial_seed(base_seed, trial)`, as the sweep derives it.
    pub fn for_trial(base_seed: u64, trial: u32) -> Self {
        Self::new(trial, trial_seed(base_seed, trial))
    }

    /// A generator for the method, at the start of its stream: ChaCha8 seeded with
    /// [`seed`](Self::seed) (`seed_from_u64`) on stream [`METHOD_RNG_STREAM`]. Every call
    /// returns the same stream, so take it once and keep it in the method (e.g. in a
    /// `RefCell`, see `GroupingMethod`'s docs); different trials get different streams.
    pub fn rng(&self) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(METHOD_RNG_STREAM);
        rng
    }
}

/// Builds a grouping method from its name and the trial it is for. [`MethodFactory::builtin`]
/// knows `rne`, `dis`, `eng` and `hp_dis`; wrap it to add methods of your own without
/// touching the sweep (a factory that needs no context ignores it):
///
/// ```
/// use usar_sweep::sweep::{MethodFactory, TrialContext};
/// use rne_core::grouping::{Eng, GroupingMethod};
///
/// // `my_eng` is ENG under another name; anything else falls back to the built-ins.
/// let factory = MethodFactory::new(|name, model, ctx| match name {
///     "my_eng" => Ok(Box::new(Eng) as Box<dyn GroupingMethod>),
///     other => MethodFactory::builtin().build(other, model, ctx),
/// });
/// let model = rne_core::TrustModel::with_weights(rne_core::Weights::uniform(7)?);
/// let ctx = TrialContext::for_trial(2021, 0);
/// assert_eq!(factory.build("my_eng", &model, &ctx)?.name(), "eng");
/// assert_eq!(factory.build("dis", &model, &ctx)?.display_name(), "DIS");
/// # Ok::<(), rne_core::RneError>(())
/// ```
///
/// A stochastic method takes its generator from the context:
/// `crates/usar-sweep/examples/random_method.rs`.
///
/// # How often it is called
/// A sweep ([`run_sweep`](crate::sweep::run_sweep)) calls it once per method when it starts,
/// with trial 0's context, to check the name and learn the method's display name
/// ([`canonical_method`]; that method is dropped unused), then once per trial it runs, with
/// that trial's context, on the worker thread that runs the trial: `M + M x T` calls for `M`
/// methods and `T` trials in one grid cell (`M + M x T x C` with `C` cells), and only the `M`
/// name checks on a resume of a finished sweep. A calibration checks the names once and
/// builds a method per trial of each evaluation; a multiverse does both for each universe.
/// Replays of a sweep's trials (`usar_report::replay::SweepReplays`) call it again to match names
/// and to build a trial they run once more. The factory is shared by the worker threads,
/// hence `Send + Sync`; the methods it builds are not shared (see `GroupingMethod`).
#[derive(Clone)]
pub struct MethodFactory(Arc<MethodBuilder>);

/// The function behind a [`MethodFactory`].
type MethodBuilder = dyn Fn(&str, &TrustModel, &TrialContext) -> rne_core::Result<Box<dyn GroupingMethod>>
    + Send
    + Sync;

impl MethodFactory {
    /// A factory from a function `(name, RNE trust model of the scenario, trial) -> method`.
    pub fn new(
        f: impl Fn(&str, &TrustModel, &TrialContext) -> rne_core::Result<Box<dyn GroupingMethod>>
        + Send
        + Sync
        + 'static,
    ) -> Self {
        Self(Arc::new(f))
    }

    /// The built-in methods, by [`method_from_name`] (the trial is not used: they are
    /// deterministic).
    pub fn builtin() -> Self {
        Self::new(|name, model, _| method_from_name(name, model))
    }

    /// Builds the method called `name` for the trial `ctx`.
    ///
    /// # Errors
    /// Whatever the factory reports for an unknown name (the built-ins list the valid names).
    pub fn build(
        &self,
        name: &str,
        model: &TrustModel,
        ctx: &TrialContext,
    ) -> rne_core::Result<Box<dyn GroupingMethod>> {
        (self.0)(name, model, ctx)
    }
}

impl Default for MethodFactory {
    fn default() -> Self {
        Self::builtin()
    }
}

impl std::fmt::Debug for MethodFactory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MethodFactory")
    }
}

/// Why a sweep's method cannot be used, or its trust model built.
#[derive(Debug, thiserror::Error)]
pub enum MethodError {
    /// The factory does not build a method of this name (or the method refused the trial's
    /// context).
    #[error("method {name:?}")]
    Unknown {
        /// The name, as given.
        name: String,
        /// The factory's error.
        #[source]
        source: rne_core::RneError,
    },
    /// The method's display name is empty.
    #[error("method {name:?}: its display name is empty")]
    EmptyName {
        /// The name, as given.
        name: String,
    },
    /// The method's display name holds a control character (a line break would break the
    /// tables of trials.csv and report.md).
    #[error(
        "method {name:?}: its display name {shown:?} has a control character (a line break \
         would break the tables of trials.csv and report.md)"
    )]
    ControlCharacter {
        /// The name, as given.
        name: String,
        /// The display name.
        shown: String,
    },
    /// The scenario's `needs_weights` that rne-core rejects.
    #[error("scenario needs_weights")]
    NeedsWeights(#[source] usar_sim::mission::MissionError),
}

/// The display name of the method called `name` (its `GroupingMethod::display_name`, kept as
/// its author wrote it: `hp_sort` stays `hp_sort`; the built-ins give `RNE`, `DIS`, `ENG`,
/// `HP_DIS`), as `TrialResult::method`, the journal and the outputs spell it. Builds the
/// method once with trial 0's context of `base_seed` and drops it.
///
/// # Errors
/// An unknown method name, or a display name that is empty or holds a control character.
pub fn canonical_method(
    name: &str,
    factory: &MethodFactory,
    model: &TrustModel,
    base_seed: u64,
) -> Result<String, MethodError> {
    let m = factory
        .build(name, model, &TrialContext::for_trial(base_seed, 0))
        .map_err(|source| MethodError::Unknown {
            name: name.to_owned(),
            source,
        })?;
    let shown = m.display_name();
    if shown.trim().is_empty() {
        return Err(MethodError::EmptyName {
            name: name.to_owned(),
        });
    }
    if shown.chars().any(char::is_control) {
        return Err(MethodError::ControlCharacter {
            name: name.to_owned(),
            shown: shown.to_owned(),
        });
    }
    Ok(shown.to_string())
}

/// The RNE trust model of `scenario` (its `needs_weights`; see
/// [`usar_sim::mission::trust_model`]).
///
/// # Errors
/// Weights rne-core rejects.
pub fn trust_model(scenario: &Scenario) -> Result<TrustModel, MethodError> {
    usar_sim::mission::trust_model(scenario).map_err(MethodError::NeedsWeights)
}

#[cfg(test)]
mod tests {
    use rand::Rng;

    use super::*;

    #[test]
    fn a_trial_context_gives_a_pinned_stream_apart_from_the_starting_team() {
        let ctx = TrialContext::for_trial(2021, 0);
        assert_eq!(ctx.seed, trial_seed(2021, 0));
        // Pinned: a change of generator, seeding or stream would change every stochastic
        // method's draws.
        let first: Vec<u64> = {
            let mut rng = ctx.rng();
            (0..2).map(|_| rng.next_u64()).collect()
        };
        assert_eq!(
            first,
            [16_724_851_754_553_929_695, 3_390_821_875_263_122_250]
        );
        // The same stream on every call; not stream 0, the starting team's.
        assert_eq!(ctx.rng().next_u64(), first[0]);
        assert_ne!(ChaCha8Rng::seed_from_u64(ctx.seed).next_u64(), first[0]);
        // Another trial, another stream.
        assert_ne!(TrialContext::for_trial(2021, 1).rng().next_u64(), first[0]);
    }

    /// A method named `self.0`.
    struct Named(&'static str);

    impl rne_core::grouping::GroupingMethod for Named {
        fn name(&self) -> &str {
            self.0
        }
        fn assign(
            &self,
            request: &rne_core::grouping::GroupingRequest,
        ) -> rne_core::Result<rne_core::grouping::Assignment> {
            rne_core::grouping::Eng.assign(request)
        }
    }

    /// A line break in a display name broke report.md's tables; it is refused by name.
    #[test]
    fn a_display_name_with_a_control_character_is_refused() {
        let factory = MethodFactory::new(|name, _, _| {
            Ok(
                Box::new(Named(if name == "nl" { "my\nmethod" } else { "mine" }))
                    as Box<dyn rne_core::grouping::GroupingMethod>,
            )
        });
        let model = TrustModel::with_weights(rne_core::Weights::uniform(7).unwrap());
        assert_eq!(canonical_method("ok", &factory, &model, 1).unwrap(), "mine");
        let e = canonical_method("nl", &factory, &model, 1)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("display name \"my\\nmethod\" has a control character") && !e.contains('\n'),
            "{e}"
        );
    }
}
