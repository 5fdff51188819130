//! Edits of a validated scenario: change a copy of its spec, validate again.
//!
//! A [`Scenario`] cannot be changed in place (its fields are private). [`Scenario::edit`]
//! hands a copy of its [`ScenarioSpec`] to a closure and validates the result, so an edit that
//! breaks a rule (a kind's quotas no longer adding up to its count, say) is a
//! [`ScenarioError`] naming the field, never a scenario a trial could run. Numbers of the spec
//! are validated types ([`super::numbers`]); [`number_at`] checks a plain `f64` for one of them
//! and names the field when it is out of range.

use super::error::{ScenarioError, SourceLocation};
use super::numbers::RangeError;
use super::spec::ScenarioSpec;
use super::validated::Scenario;

/// What an edit closure returns: nothing (`()`), or `Result<(), ScenarioError>` for a closure
/// that checks numbers with [`number_at`] and `?`. Implemented for those two only.
pub trait EditOutcome {
    /// The closure's verdict: `Ok(())` to go on to validation.
    ///
    /// # Errors
    /// The closure's own error.
    fn into_result(self) -> Result<(), ScenarioError>;
}

impl EditOutcome for () {
    fn into_result(self) -> Result<(), ScenarioError> {
        Ok(())
    }
}

impl EditOutcome for Result<(), ScenarioError> {
    fn into_result(self) -> Result<(), ScenarioError> {
        self
    }
}

impl Scenario {
    /// A new scenario: this one's spec ([`Scenario::to_spec`]) changed by `f`, then validated
    /// again ([`ScenarioSpec::validate`]). `self` is unchanged.
    ///
    /// ```
    /// # use usar_sim::scenario::{self, Positive, number_at};
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
    /// let paper = scenario::load(path)?;
    /// // Four carriers on each task: count and quotas change together.
    /// let more = paper.edit(|s| {
    ///     s.kinds[0].count = 8;
    ///     s.kinds[0].quota.0.insert("easy".into(), 4);
    ///     s.kinds[0].quota.0.insert("hard".into(), 4);
    /// })?;
    /// assert_eq!(more.robots().len(), 14);
    /// // A plain number is checked for its field, and the error names it.
    /// let err = paper
    ///     .edit(|s| {
    ///         s.kinds[0].max_speed_m_per_s = number_at("kinds[0].max_speed_m_per_s", -1.0)?;
    ///         Ok(())
    ///     })
    ///     .unwrap_err();
    /// assert_eq!(err.field(), Some("kinds[0].max_speed_m_per_s"));
    /// # Ok::<(), scenario::ScenarioError>(())
    /// ```
    ///
    /// # Errors
    /// The closure's error, or the first rule the edited spec breaks
    /// ([`ScenarioError::Invalid`], with the field path and no line or column); its origin is
    /// the scenario's name followed by ` (edited)`.
    pub fn edit<O: EditOutcome>(
        &self,
        f: impl FnOnce(&mut ScenarioSpec) -> O,
    ) -> Result<Scenario, ScenarioError> {
        let origin = format!("{} (edited)", self.name());
        let mut spec = self.to_spec();
        f(&mut spec)
            .into_result()
            .map_err(|e| with_origin(e, &origin))?;
        spec.validate(&origin)
    }
}

/// `value` as the validated number type `T` of the spec field at path `field` (e.g.
/// `number_at::<Positive>("kinds[0].max_speed_m_per_s", 2.0)`), for edits and specs written
/// in code.
///
/// # Errors
/// [`ScenarioError::Invalid`] at `field` when `value` is out of `T`'s range, e.g.
/// `kinds[0].max_speed_m_per_s: expected a finite number > 0, found -1`. Its origin is empty;
/// [`Scenario::edit`] and [`super::ScenarioBuilder::build`] fill in theirs.
pub fn number_at<T>(field: &str, value: f64) -> Result<T, ScenarioError>
where
    T: TryFrom<f64, Error = RangeError>,
{
    T::try_from(value).map_err(|e| field_error(field, e.0))
}

/// An [`ScenarioError::Invalid`] at `field` with no origin and no position (the caller's
/// [`with_origin`] fills the origin in).
pub(crate) fn field_error(field: &str, message: String) -> ScenarioError {
    ScenarioError::Invalid {
        location: SourceLocation {
            origin: String::new(),
            line_col: None,
        },
        field: field.to_owned(),
        message,
    }
}

/// `e` with `origin` as its origin when it has none (an error of [`number_at`]).
pub(crate) fn with_origin(mut e: ScenarioError, origin: &str) -> ScenarioError {
    if let ScenarioError::Invalid { location, .. } | ScenarioError::Syntax { location, .. } = &mut e
        && location.origin.is_empty()
    {
        location.origin = origin.to_owned();
    }
    e
}
