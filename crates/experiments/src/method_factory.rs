//! Grouping methods by name: the [`MethodFactory`] a sweep builds each trial's method with
//! (the extension point for methods of your own), and the trust model they are built for.

use std::sync::Arc;

use anyhow::{Context, Result};
use rne_core::TrustModel;
use rne_core::grouping::{GroupingMethod, method_from_name};
use usar_sim::scenario::Scenario;

/// Builds a grouping method from its name, once per trial (methods need not be `Clone` and
/// are never shared between threads). [`MethodFactory::builtin`] knows `rne`, `dis`, `eng` and
/// `hp_dis`; wrap it to add methods of your own without touching the sweep:
///
/// ```
/// use experiments::sweep::MethodFactory;
/// use rne_core::grouping::{Eng, GroupingMethod};
///
/// // `my_eng` is ENG under another name; anything else falls back to the built-ins.
/// let factory = MethodFactory::new(|name, model| match name {
///     "my_eng" => Ok(Box::new(Eng) as Box<dyn GroupingMethod>),
///     other => MethodFactory::builtin().build(other, model),
/// });
/// let model = rne_core::TrustModel::with_weights(rne_core::Weights::uniform(7)?);
/// assert_eq!(factory.build("my_eng", &model)?.name(), "eng");
/// assert_eq!(factory.build("dis", &model)?.name(), "dis");
/// # Ok::<(), rne_core::RneError>(())
/// ```
#[derive(Clone)]
pub struct MethodFactory(Arc<MethodBuilder>);

/// The function behind a [`MethodFactory`].
type MethodBuilder =
    dyn Fn(&str, &TrustModel) -> rne_core::Result<Box<dyn GroupingMethod>> + Send + Sync;

impl MethodFactory {
    /// A factory from a function `(name, RNE trust model of the scenario) -> method`.
    pub fn new(
        f: impl Fn(&str, &TrustModel) -> rne_core::Result<Box<dyn GroupingMethod>>
        + Send
        + Sync
        + 'static,
    ) -> Self {
        Self(Arc::new(f))
    }

    /// The built-in methods, by [`method_from_name`].
    pub fn builtin() -> Self {
        Self::new(method_from_name)
    }

    /// Builds the method called `name`.
    ///
    /// # Errors
    /// Whatever the factory reports for an unknown name (the built-ins list the valid names).
    pub fn build(
        &self,
        name: &str,
        model: &TrustModel,
    ) -> rne_core::Result<Box<dyn GroupingMethod>> {
        (self.0)(name, model)
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

/// Canonical (upper-case) name of a method, as `TrialResult::method` spells it.
///
/// # Errors
/// An unknown method name.
pub fn canonical_method(name: &str, factory: &MethodFactory, model: &TrustModel) -> Result<String> {
    let m = factory
        .build(name, model)
        .with_context(|| format!("method {name:?}"))?;
    Ok(m.name().to_ascii_uppercase())
}

/// The RNE trust model of `scenario` (its `needs_weights`; see
/// [`usar_sim::mission::trust_model`]).
///
/// # Errors
/// Weights rne-core rejects.
pub fn trust_model(scenario: &Scenario) -> Result<TrustModel> {
    usar_sim::mission::trust_model(scenario).context("scenario needs_weights")
}
