//! The scenario fields a calibration fits: `--free FIELD=LO..HI` (linear) or
//! `FIELD=LO..HI:log` (log scale, `LO > 0`), FIELD any path `--vary` takes
//! ([`usar_sweep::vary::FieldPath`]) that holds a real number (an `Option<f64>` such as
//! `mission.search_time_budget_s` included: a number sets it to `Some(number)`).
//!
//! With `:factor` (`FIELD=LO..HI:factor`, or `:log,factor`) the free value is a factor of the
//! base scenario's value(s), `LO > 0`: `kinds[*].max_speed_m_per_s=0.5..2:factor` scales every
//! kind's speed by the same factor and so keeps their ratios (the paper's
//! `v_c = v_s = 1.5 v_o`), where `kinds[*].max_speed_m_per_s=1..3` would set them equal. It
//! starts at 1 (the base scenario) when 1 lies in the range.
//!
//! The search works on normalised coordinates `u` in `[0, 1]` per field
//! ([`FreeField::to_unit`], [`FreeField::from_unit`]; on a log range `u` is linear in
//! `ln x`), and every value is rounded to a number of significant digits
//! ([`round_significant`]) before it is evaluated, so that what is recorded is exactly what
//! ran.

use std::fmt;

use serde::{Deserialize, Serialize};
use serde_json::Value;
use usar_sim::scenario::ScenarioSpec;

use usar_report::targets::float_text::short;
use usar_sweep::settings::Setting;
use usar_sweep::vary::{
    FieldPath, FieldValue, Override, RonValue, apply_overrides, brief, spec_json,
};

/// One free field and its range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FreeField {
    /// The field path as written (`mission.pickup_s`, `kinds[*].max_speed_m_per_s`).
    pub field: String,
    /// Lowest value (finite; > 0 on a log scale).
    pub lo: f64,
    /// Highest value (finite, > `lo`).
    pub hi: f64,
    /// Search on a log scale.
    pub log: bool,
    /// The value is a factor of the base scenario's value(s) of the field (`:factor`).
    #[serde(default)]
    pub factor: bool,
}

/// A bad `--free` argument, or one that does not fit the scenario: one line,
/// `--free ARG: message`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{} {arg}: {message}", Setting::Free)]
pub struct FreeError {
    /// The argument as given (shortened when long, [`brief`]).
    pub arg: String,
    /// What is wrong.
    pub message: String,
}

impl FreeField {
    /// Parses `FIELD=LO..HI`, optionally followed by `:log`, `:factor` or `:log,factor`.
    ///
    /// # Errors
    /// No `=`, a malformed field path (the `--vary` message), a scale other than `log` and
    /// `factor`, no `..`, a bound that is not a finite number, `LO >= HI` (an empty or reversed
    /// range), or `LO <= 0` on a log scale or for a factor.
    pub fn parse(arg: &str) -> Result<Self, FreeError> {
        let fail = |message: String| FreeError {
            arg: brief(arg),
            message,
        };
        let (field, range) = arg
            .split_once('=')
            .ok_or_else(|| fail("expected FIELD=LO..HI or FIELD=LO..HI:log".into()))?;
        let path = FieldPath::parse(field.trim()).map_err(fail)?;
        let (range, scales) = match range.rsplit_once(':') {
            Some((r, scales)) => (r, scales.split(',').map(str::trim).collect::<Vec<_>>()),
            None => (range, Vec::new()),
        };
        if let Some(bad) = scales.iter().find(|s| !["log", "factor"].contains(s)) {
            return Err(fail(format!(
                "unknown scale {bad:?} after ':' (write log, factor or log,factor)"
            )));
        }
        let (log, factor) = (scales.contains(&"log"), scales.contains(&"factor"));
        let (lo, hi) = range
            .split_once("..")
            .ok_or_else(|| fail(format!("expected a range LO..HI, found {:?}", brief(range))))?;
        if hi.trim_start().starts_with('.') {
            return Err(fail(format!(
                "expected a range LO..HI with two dots, found {:?}",
                brief(range)
            )));
        }
        let bound = |name: &str, text: &str| -> Result<f64, FreeError> {
            let x: f64 = text
                .trim()
                .parse()
                .map_err(|_| fail(format!("{name} {:?} is not a number", brief(text.trim()))))?;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(fail(format!("{name} {x} is not a finite number")))
            }
        };
        let (lo, hi) = (bound("LO", lo)?, bound("HI", hi)?);
        if lo >= hi {
            return Err(fail(format!(
                "the range {lo}..{hi} is empty or reversed: LO must be below HI"
            )));
        }
        if !(hi - lo).is_finite() {
            return Err(fail(format!(
                "the range {}..{} is wider than the largest number: narrow it",
                short(lo),
                short(hi)
            )));
        }
        if log && lo <= 0.0 {
            return Err(fail(format!(
                "a log range needs LO > 0, found {lo} (or drop :log for a linear range)"
            )));
        }
        if factor && lo <= 0.0 {
            return Err(fail(format!(
                "a factor range needs LO > 0, found {lo}: a factor of 0 or less is no speed, \
                 rate or range"
            )));
        }
        Ok(Self {
            field: path.to_string(),
            lo,
            hi,
            log,
            factor,
        })
    }

    /// How the field is named in tables and lines: its path, with ` (factor)` for a factor.
    pub fn label(&self) -> String {
        if self.factor {
            format!("{} (factor)", self.field)
        } else {
            self.field.clone()
        }
    }

    /// The field set to `x` as reports write it: `field=x`, or `field=x (factor)`.
    pub fn assignment(&self, x: f64) -> String {
        if self.factor {
            format!("{}={x} (factor)", self.field)
        } else {
            format!("{}={x}", self.field)
        }
    }

    /// Scales the value(s) this `:factor` field names in `spec_json` (a spec's JSON form) by
    /// `x`.
    ///
    /// # Errors
    /// A path that names nothing, or a value that is not a number (the `--vary` messages).
    pub fn scale_in(&self, spec_json: &mut Value, x: f64) -> Result<(), String> {
        self.path().set(spec_json, &mut |old| match old {
            Value::Number(n) if n.is_f64() => {
                serde_json::Number::from_f64(n.as_f64().unwrap_or(0.0) * x)
                    .map(Value::Number)
                    .ok_or_else(|| "the scaled value is not a finite number".to_string())
            }
            Value::Null => Err("is None; a factor scales a number".into()),
            _ => Err(format!(
                "is not a real number; {} fits real-valued fields only",
                Setting::Free
            )),
        })
    }

    /// The field's path.
    ///
    /// # Panics
    /// Never for a field made by [`FreeField::parse`]; for a hand-made `field` that is not a
    /// path (a programming error).
    pub fn path(&self) -> FieldPath {
        FieldPath::parse(&self.field).unwrap_or_else(|e| panic!("free field: {e}"))
    }

    /// `x` in normalised coordinates: 0 at `lo`, 1 at `hi`, linear in `x` (or in `ln x` on a
    /// log scale); values outside the range map outside `[0, 1]`.
    pub fn to_unit(&self, x: f64) -> f64 {
        if self.log {
            (x.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (x - self.lo) / (self.hi - self.lo)
        }
    }

    /// The value at normalised coordinate `u` (clamped to `[0, 1]`), rounded to `digits`
    /// significant digits and kept in `[lo, hi]` (a rounded value past an end is that end).
    pub fn from_unit(&self, u: f64, digits: u32) -> f64 {
        let u = u.clamp(0.0, 1.0);
        let x = if self.log {
            (self.lo.ln() + u * (self.hi.ln() - self.lo.ln())).exp()
        } else {
            self.lo + u * (self.hi - self.lo)
        };
        round_significant(x, digits).clamp(self.lo, self.hi)
    }

    /// The middle of the range (geometric on a log scale).
    pub fn midpoint(&self) -> f64 {
        if self.log {
            (self.lo * self.hi).sqrt()
        } else {
            (self.lo + self.hi) / 2.0
        }
    }

    /// Where the search starts: `base` (the field's value in the base scenario; 1 for a
    /// factor) when it lies in the range, else the range's [`FreeField::midpoint`].
    pub fn start(&self, base: Option<f64>) -> f64 {
        match base {
            Some(x) if (self.lo..=self.hi).contains(&x) => x,
            _ => self.midpoint(),
        }
    }

    /// The override that sets the field to `x` (every element a `[*]` names).
    pub fn override_for(&self, x: f64) -> Override {
        let text = short(x);
        Override {
            path: self.path(),
            value: FieldValue {
                value: RonValue::Bare(text.clone()),
                text,
            },
        }
    }

    /// Checks that the field names real numbers in `base` and returns its value there: the
    /// number every element it names holds (`None` when they differ or it is `None`).
    ///
    /// # Errors
    /// A path that names nothing (the `--vary` message, listing the fields there are), a
    /// field that is not a number (a list, a string, a whole-number count), or one that takes
    /// none of the range's ends nor its middle (the middle's error; a range the field takes
    /// in part is accepted, its other values run as failed evaluations).
    pub fn base_value(&self, base: &ScenarioSpec) -> Result<Option<f64>, FreeError> {
        let fail = |message: String| FreeError {
            arg: brief(&self.to_string()),
            message,
        };
        let mut json = spec_json(base).map_err(fail)?;
        if self.factor {
            self.scale_in(&mut json, 1.0).map_err(fail)?;
            return Ok(Some(1.0));
        }
        let mut found: Vec<Option<f64>> = Vec::new();
        self.path()
            .set(&mut json, &mut |old| match old {
                Value::Number(n) if n.is_f64() => {
                    found.push(n.as_f64());
                    Ok(old.clone())
                }
                Value::Null => {
                    found.push(None);
                    Ok(Value::Null)
                }
                Value::Number(_) => Err(format!(
                    "holds a whole number (a count or seed); {} fits real-valued fields only",
                    Setting::Free
                )),
                _ => Err(format!(
                    "is not a number; {} fits real-valued fields only",
                    Setting::Free
                )),
            })
            .map_err(fail)?;
        // The field takes numbers when it takes one of the range's (values it refuses run as
        // failed evaluations); when it takes none, the middle's error says why.
        let takes = |x: f64| apply_overrides(base, &[self.override_for(x)]).map_err(|(_, e)| e);
        if takes(self.lo).is_err() && takes(self.hi).is_err() {
            takes(self.midpoint()).map_err(fail)?;
        }
        let first = found.first().copied().flatten();
        Ok(first.filter(|x| found.iter().all(|y| *y == Some(*x))))
    }
}

impl fmt::Display for FreeField {
    /// As written: `mission.pickup_s=0.5..2`, `mission.hp_pct_per_step_in_radiation=0.002..0.02:log`,
    /// `kinds[*].max_speed_m_per_s=0.5..2:factor`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}..{}", self.field, short(self.lo), short(self.hi))?;
        match (self.log, self.factor) {
            (true, true) => f.write_str(":log,factor"),
            (true, false) => f.write_str(":log"),
            (false, true) => f.write_str(":factor"),
            (false, false) => Ok(()),
        }
    }
}

/// Parses every `--free` argument and refuses a field given twice (or two that overlap, such
/// as `kinds[*].x` and `kinds[0].x`).
///
/// # Errors
/// As [`FreeField::parse`]; a repeated or overlapping field.
pub fn parse_free(args: &[String]) -> Result<Vec<FreeField>, FreeError> {
    let fields = args
        .iter()
        .map(|a| FreeField::parse(a))
        .collect::<Result<Vec<_>, _>>()?;
    check_distinct(&fields)?;
    Ok(fields)
}

/// Refuses a field given twice, or two fields that set some of the same values.
///
/// # Errors
/// The later of the two, naming the earlier.
pub fn check_distinct(fields: &[FreeField]) -> Result<(), FreeError> {
    for (i, a) in fields.iter().enumerate() {
        for b in &fields[..i] {
            let message = if a.field == b.field {
                "the field is given twice: free each field once".to_string()
            } else if a.path().overlaps(&b.path()) {
                format!(
                    "overlaps {} {b}: they set some of the same values",
                    Setting::Free
                )
            } else {
                continue;
            };
            return Err(FreeError {
                arg: brief(&a.to_string()),
                message,
            });
        }
    }
    Ok(())
}

/// `x` rounded to `digits` significant digits (1 to 17; 0 counts as 1, more than 17 as 17),
/// through its decimal form, so that the result prints as at most `digits` digits.
pub fn round_significant(x: f64, digits: u32) -> f64 {
    let d = digits.clamp(1, 17) as usize;
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    format!("{:.*e}", d - 1, x).parse().unwrap_or(x)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;
    use usar_sim::scenario::parse_spec;

    use super::*;

    const PAPER: &str = include_str!("../../../../scenarios/paper-v1.ron");

    fn err(arg: &str) -> String {
        FreeField::parse(arg).unwrap_err().to_string()
    }

    #[test]
    fn huge_bounds_print_short() {
        let f = FreeField::parse("mission.pickup_s=1e-300..1e300:log").unwrap();
        assert_eq!(f.to_string(), "mission.pickup_s=1e-300..1e300:log");
        assert_eq!(f.override_for(1e300).value.text, "1e300");
        assert_eq!(f.override_for(1.25).value.text, "1.25");
    }

    #[test]
    fn parses_linear_and_log_ranges() {
        let f = FreeField::parse("mission.pickup_s=0.5..2").unwrap();
        assert_eq!(
            (f.field.as_str(), f.lo, f.hi, f.log),
            ("mission.pickup_s", 0.5, 2.0, false)
        );
        let f = FreeField::parse(" kinds[*].max_speed_m_per_s = 1e-3 .. 2.5e1 :log").unwrap();
        assert_eq!(f.field, "kinds[*].max_speed_m_per_s");
        assert_eq!((f.lo, f.hi, f.log), (0.001, 25.0, true));
        assert_eq!(f.to_string(), "kinds[*].max_speed_m_per_s=0.001..25:log");
        let neg = FreeField::parse("arena.width_m=-2..-1").unwrap();
        assert_eq!((neg.lo, neg.hi), (-2.0, -1.0));
    }

    #[test]
    fn a_factor_scales_every_value_it_names_and_keeps_their_ratios() {
        let f = FreeField::parse("kinds[*].max_speed_m_per_s=0.5..2:factor").unwrap();
        assert!(f.factor && !f.log);
        assert_eq!(f.to_string(), "kinds[*].max_speed_m_per_s=0.5..2:factor");
        assert_eq!(f.label(), "kinds[*].max_speed_m_per_s (factor)");
        assert_eq!(f.assignment(1.2), "kinds[*].max_speed_m_per_s=1.2 (factor)");
        let g = FreeField::parse("mission.pickup_s=0.5..2:log,factor").unwrap();
        assert!(g.factor && g.log);
        assert_eq!(g.to_string(), "mission.pickup_s=0.5..2:log,factor");
        let spec = parse_spec(PAPER, "paper.ron").unwrap();
        // Its base value is the factor 1 (the base scenario), whatever the kinds hold.
        assert_eq!(f.base_value(&spec), Ok(Some(1.0)));
        assert_eq!(f.start(Some(1.0)), 1.0);
        let mut json = spec_json(&spec).unwrap();
        f.scale_in(&mut json, 1.2).unwrap();
        let speeds: Vec<f64> = json["kinds"]
            .as_array()
            .unwrap()
            .iter()
            .map(|k| k["max_speed_m_per_s"].as_f64().unwrap())
            .collect();
        let before: Vec<f64> = spec
            .kinds
            .iter()
            .map(|k| k.max_speed_m_per_s.get())
            .collect();
        for (now, was) in speeds.iter().zip(&before) {
            assert!((now - 1.2 * was).abs() < 1e-12, "{now} vs {was}");
        }
        assert!((speeds[0] / speeds[2] - before[0] / before[2]).abs() < 1e-12);
        let e = FreeField::parse("mission.pickup_s=0..2:factor")
            .unwrap_err()
            .to_string();
        assert!(e.contains("a factor range needs LO > 0"), "{e}");
        let e = FreeField::parse("tasks.hard.goal_m=1..2:factor")
            .unwrap()
            .base_value(&spec)
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not a real number"), "{e}");
    }

    #[test]
    fn bad_arguments_say_what_is_wrong() {
        for (arg, says) in [
            (
                "mission.pickup_s",
                "--free mission.pickup_s: expected FIELD=LO..HI or FIELD=LO..HI:log",
            ),
            (
                "mission..x=1..2",
                "--free mission..x=1..2: field path \"mission..x\": expected a field name",
            ),
            (
                "mission.pickup_s=1..2:ln",
                "unknown scale \"ln\" after ':' (write log, factor or log,factor)",
            ),
            (
                "mission.pickup_s=1-2",
                "expected a range LO..HI, found \"1-2\"",
            ),
            ("mission.pickup_s=a..2", "LO \"a\" is not a number"),
            ("mission.pickup_s=1..", "HI \"\" is not a number"),
            ("mission.pickup_s=1..inf", "HI inf is not a finite number"),
            ("mission.pickup_s=NaN..2", "LO NaN is not a finite number"),
            (
                "mission.pickup_s=2..2",
                "the range 2..2 is empty or reversed: LO must be below HI",
            ),
            (
                "mission.pickup_s=3..2",
                "the range 3..2 is empty or reversed",
            ),
            (
                "mission.pickup_s=0..2:log",
                "a log range needs LO > 0, found 0",
            ),
            (
                "mission.pickup_s=0.5...2",
                "expected a range LO..HI with two dots, found \"0.5...2\"",
            ),
            (
                "mission.pickup_s=-1e308..1e308",
                "the range -1e308..1e308 is wider than the largest number",
            ),
            (
                "mission.pickup_s=-1..2:log",
                "a log range needs LO > 0, found -1",
            ),
        ] {
            let e = err(arg);
            assert!(e.contains(says), "{e}\nshould contain\n{says}");
            assert!(e.starts_with("--free "), "{e}");
        }
    }

    #[test]
    fn a_field_twice_or_overlapping_is_refused() {
        let args = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            parse_free(&args(&["mission.pickup_s=1..2", "mission.pickup_s=0.5..1"]))
                .unwrap_err()
                .to_string(),
            "--free mission.pickup_s=0.5..1: the field is given twice: free each field once"
        );
        let e = parse_free(&args(&[
            "kinds[*].max_speed_m_per_s=1..2",
            "kinds[0].max_speed_m_per_s=1..3",
        ]))
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("overlaps --free kinds[*].max_speed_m_per_s=1..2"),
            "{e}"
        );
        assert_eq!(
            parse_free(&args(&["mission.pickup_s=1..2", "mission.recharge_s=1..2"]))
                .unwrap()
                .len(),
            2
        );
    }

    #[test]
    fn fields_are_checked_against_the_scenario() {
        let spec = parse_spec(PAPER, "paper.ron").unwrap();
        let base = |arg: &str| FreeField::parse(arg).unwrap().base_value(&spec);
        assert_eq!(base("mission.pickup_s=0.5..2"), Ok(Some(1.2)));
        // An Option<f64> holding Some(14.0) is a number.
        assert_eq!(base("mission.search_time_budget_s=8..30"), Ok(Some(14.0)));
        assert_eq!(
            base("mission.hp_pct_per_step_in_radiation=0.002..0.02:log"),
            Ok(Some(0.0055))
        );
        // The observers are slower: the kinds differ, so there is no one base value.
        assert_eq!(base("kinds[*].max_speed_m_per_s=1..3"), Ok(None));
        let e = base("mission.hp_rate=1..2").unwrap_err().to_string();
        assert!(
            e.starts_with("--free mission.hp_rate=1..2: no field \"hp_rate\" in mission (fields: "),
            "{e}"
        );
        let e = base("kinds[0].count=1..5").unwrap_err().to_string();
        assert_eq!(
            e,
            "--free kinds[0].count=1..5: kinds[0].count: holds a whole number (a count or seed); \
             --free fits real-valued fields only"
        );
        let e = base("tasks.hard.goal_m=1..5").unwrap_err().to_string();
        assert!(e.contains("tasks.hard.goal_m: is not a number"), "{e}");
        // A range the field takes in part is accepted; one it takes nowhere is not.
        assert_eq!(base("mission.pickup_s=-1..2"), Ok(Some(1.2)));
        let e = base("mission.pickup_s=-3..-1").unwrap_err().to_string();
        assert!(
            e.starts_with("--free mission.pickup_s=-3..-1: mission.pickup_s: "),
            "{e}"
        );
    }

    #[test]
    fn values_are_rounded_and_kept_in_range() {
        assert_eq!(round_significant(0.0123456, 4), 0.01235);
        assert_eq!(round_significant(123456.0, 2), 120000.0);
        assert_eq!(round_significant(-2.71649, 3), -2.72);
        assert_eq!(round_significant(0.0, 4), 0.0);
        assert_eq!(round_significant(1.0 / 3.0, 17), 1.0 / 3.0);
        let f = FreeField::parse("x=0.123456..0.2").unwrap();
        // 0.123456 rounds to 0.1235, inside; 0.2 stays.
        assert_eq!(f.from_unit(0.0, 4), 0.1235);
        assert_eq!(f.from_unit(-3.0, 4), 0.1235);
        assert_eq!(f.from_unit(7.0, 4), 0.2);
        let g = FreeField::parse("x=0.1..0.123456").unwrap();
        // 0.123456 rounds to 0.1235, past the end: the end itself.
        assert_eq!(g.from_unit(1.0, 4), 0.123456);
        assert_eq!(f.start(Some(0.15)), 0.15);
        assert_eq!(f.start(Some(0.3)), f.midpoint());
        assert_eq!(f.start(None), f.midpoint());
        let log = FreeField::parse("x=0.002..0.02:log").unwrap();
        assert!((log.midpoint() - 0.002f64.sqrt() * 0.02f64.sqrt()).abs() < 1e-15);
        assert!((log.to_unit(log.midpoint()) - 0.5).abs() < 1e-12);
    }

    proptest! {
        /// Normalising and back gives the value again (to the rounding), linear or log.
        #[test]
        fn normalisation_round_trips(
            lo in -1e3f64..1e3,
            width in 1e-3f64..1e4,
            t in 0.0f64..=1.0,
            log in any::<bool>(),
        ) {
            let lo = if log { lo.abs() + 1e-3 } else { lo };
            let f = FreeField { field: "x".into(), lo, hi: lo + width, log, factor: false };
            let x = f.lo + t * (f.hi - f.lo);
            let back = f.from_unit(f.to_unit(x), 17);
            prop_assert!((back - x).abs() <= 1e-9 * x.abs().max(f.hi.abs()), "{} -> {}", x, back);
            let u = f.to_unit(x);
            prop_assert!((-1e-9..=1.0 + 1e-9).contains(&u));
            // Rounded to 4 digits: within half a unit of the fourth digit, and in range.
            let r = f.from_unit(u, 4);
            prop_assert!((f.lo..=f.hi).contains(&r));
            prop_assert!((r - x).abs() <= 5e-4 * x.abs().max(f.lo.abs()).max(f.hi.abs()) * 1.0001);
        }
    }
}
