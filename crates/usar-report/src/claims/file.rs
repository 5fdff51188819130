//! A claims file (`CLAIMS.ron`) and the checked list of claims it holds.
//!
//! ```ron
//! Claims(
//!     claims: [
//!         (id: "1", sentence: "RNE rescues the most in total", subject: "RNE",
//!          metric: "rescued_total", direction: More),
//!         (id: "4b", sentence: "RNE has the lowest HP cost per rescuee in the hard task",
//!          subject: "RNE", rivals: Only(["DIS", "ENG"]), metric: "hp_per_hard_rescuee_pct",
//!          direction: Less, test: MannWhitney, alpha: 0.01, correction: Holm),
//!     ],
//! )
//! ```
//!
//! Fields and defaults: [`Claim`]. Errors are one line naming the file, line, column and
//! field: `my-claims.ron:7:20: claims[1].rivals: the subject "RNE" is among its rivals`.

use std::path::Path;
use std::sync::OnceLock;

use rne_core::grouping::METHOD_NAMES;
use usar_sim::scenario::did_you_mean;

use super::claim::{Claim, Rivals, method_key};
use crate::targets::ron_file::{self, MAX_NAME_CHARS, Source, StudyFile, check_name};

/// Longest claims file read, bytes (1 MiB): a longer file is refused instead of read into
/// memory.
pub const MAX_CLAIMS_BYTES: u64 = 1 << 20;

/// Longest claim id, characters.
const MAX_ID_CHARS: usize = 32;

/// Why claims could not be read or used: one line, `origin[:line:col]: [field: ]message`, the
/// [`Located`](ron_file::Located) error it wraps (its field is `claims[1].rivals` and the like).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(transparent)]
pub struct ClaimsError(#[from] pub ron_file::Located);

/// A checked list of claims (at least one; ids unique and usable in file names; sentences
/// one line; no subject among its rivals; every metric a `trials.csv` column name for some
/// task names; every alpha in (0, 0.5]), with where it came from.
#[derive(Debug, Clone)]
pub struct Claims {
    source: Source,
    claims: Vec<Claim>,
}

impl PartialEq for Claims {
    /// The same claims, wherever they were read from.
    fn eq(&self, other: &Self) -> bool {
        self.claims == other.claims
    }
}

/// The file's top level, `Claims(claims: [...])`, as read before [`Claims`] checks it.
#[derive(serde::Deserialize)]
#[serde(rename = "Claims", deny_unknown_fields)]
pub struct ClaimsFile {
    claims: Vec<Claim>,
}

/// The text of `scenarios/paper-claims.ron` (through the crate's `data/paper-claims.ron`, a
/// link to it, so that the packaged crate carries the file).
pub const PAPER_CLAIMS_RON: &str = include_str!("../../data/paper-claims.ron");

/// The paper's five claims (section VI, Fig. 3), parsed once from [`PAPER_CLAIMS_RON`]: what
/// `scenarios/paper.ron`'s reports check. Nothing checks them unless a scenario or a command
/// names the file.
///
/// # Panics
/// Never: the embedded file is checked by this module's tests.
pub fn paper_claims() -> &'static Claims {
    static CLAIMS: OnceLock<Claims> = OnceLock::new();
    CLAIMS.get_or_init(|| {
        Claims::parse(PAPER_CLAIMS_RON, "scenarios/paper-claims.ron")
            .unwrap_or_else(|e| panic!("the embedded paper claims do not parse: {e}"))
    })
}

impl Claims {
    /// Checks `claims` (named `origin` in errors; no line numbers).
    ///
    /// # Errors
    /// As [`Claims::parse`] for the checks after parsing.
    pub fn new(claims: Vec<Claim>, origin: &str) -> Result<Self, ClaimsError> {
        let c = Self {
            source: Source::given(origin),
            claims,
        };
        c.check_file()?;
        Ok(c)
    }

    /// Parses and checks the RON text `src` of a claims file named `origin` in errors (a
    /// leading byte-order mark is skipped).
    ///
    /// # Errors
    /// RON syntax or shape (unknown field or variant, with ron's line and column; a missing
    /// field, at the claim that lacks it); no claims; an id that is empty, too long, repeated
    /// (also when only its case differs) or has other characters than letters, digits, `_`,
    /// `-` and `.`; an empty sentence, one with a line break or one longer than
    /// [`MAX_NAME_CHARS`] characters; an empty subject, or a method name longer than that;
    /// `Only([])`, a rival named twice or the subject among its rivals; an unknown
    /// metric (the message lists the metric names); an alpha outside (0, 0.5]. Each names the
    /// line, column and field.
    pub fn parse(src: &str, origin: &str) -> Result<Self, ClaimsError> {
        Self::parse_checked(src, origin)
    }

    /// Reads and parses the claims file at `path` (named in errors as given).
    ///
    /// # Errors
    /// The file cannot be read, is longer than [`MAX_CLAIMS_BYTES`] or is not UTF-8; else as
    /// [`Claims::parse`].
    pub fn load(path: &Path) -> Result<Self, ClaimsError> {
        Self::load_checked(path)
    }

    /// The claims, in file order.
    pub fn claims(&self) -> &[Claim] {
        &self.claims
    }

    /// Where they were read from (a path as given, or the origin given to [`Claims::new`]).
    pub fn origin(&self) -> &str {
        self.source.origin()
    }

    /// Checks that every claim's metric exists for a scenario with task names `tasks`.
    ///
    /// # Errors
    /// The first metric naming a task not in `tasks`, at the claim's metric, naming the
    /// scenario's tasks.
    pub fn check_tasks(&self, tasks: &[String]) -> Result<(), ClaimsError> {
        for (i, c) in self.claims.iter().enumerate() {
            c.metric
                .resolve(tasks)
                .map_err(|e| self.error(&format!("claims[{i}].metric"), e))?;
        }
        Ok(())
    }

    /// [`Claims::check_tasks`] against the task names `tasks` of the scenario read from
    /// `scenario` (a path as given), which the error names (`...; scenario: PATH`).
    ///
    /// # Errors
    /// As [`Claims::check_tasks`], with the scenario after the message
    /// ([`Located::in_scenario`](crate::targets::ron_file::Located::in_scenario)).
    pub fn check_tasks_of_scenario(
        &self,
        tasks: &[String],
        scenario: &str,
    ) -> Result<(), ClaimsError> {
        self.check_tasks(tasks)
            .map_err(|e| ClaimsError(e.0.in_scenario(scenario)))
    }

    /// Checks that every method a claim names is one of `methods` (a sweep's, or the methods
    /// a factory knows) or a built-in method (`rne_core::grouping::METHOD_NAMES`; a built-in
    /// method left out of a sweep leaves its claims untested, not wrong).
    ///
    /// # Errors
    /// The first unknown name, at the claim's subject or rivals, with the names there are and
    /// the nearest one.
    pub fn check_methods(&self, methods: &[String]) -> Result<(), ClaimsError> {
        let mut known: Vec<String> = METHOD_NAMES.iter().map(|m| method_key(m)).collect();
        for m in methods {
            if !known.contains(&method_key(m)) {
                known.push(method_key(m));
            }
        }
        for (i, c) in self.claims.iter().enumerate() {
            let rivals = match &c.rivals {
                Rivals::Every => &[][..],
                Rivals::Only(names) => &names[..],
            };
            let named = std::iter::once((c.subject.as_str(), "subject"))
                .chain(rivals.iter().map(|r| (r.as_str(), "rivals")));
            for (name, field) in named {
                if !known.contains(&method_key(name)) {
                    return Err(self.error(
                        &format!("claims[{i}].{field}"),
                        format!(
                            "unknown method {name:?} (methods: {}){}",
                            known.join(", "),
                            did_you_mean(&method_key(name), known.iter().map(String::as_str))
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// An error about `field`, placed where the field is in the file when known.
    fn error(&self, field: &str, message: String) -> ClaimsError {
        self.source.error(field, message).into()
    }

    fn check_id(&self, i: usize, c: &Claim) -> Result<(), String> {
        let id = &c.id;
        if id.is_empty()
            || id.chars().count() > MAX_ID_CHARS
            || !id
                .chars()
                .all(|ch| ch.is_ascii_alphanumeric() || matches!(ch, '_' | '-' | '.'))
            || id.starts_with('.')
        {
            return Err(format!(
                "{id:?}: an id is 1 to {MAX_ID_CHARS} letters, digits, `_`, `-` or `.` (not \
                 first): it names the claim's files"
            ));
        }
        if let Some(j) = self.claims[..i].iter().position(|o| &o.id == id) {
            return Err(format!("duplicate id {id:?} (claims[{j}] has it too)"));
        }
        // Ids name files (`spec_curve_<id>.svg`), which collide where case is ignored.
        if let Some(j) = self.claims[..i]
            .iter()
            .position(|o| o.id.eq_ignore_ascii_case(id))
        {
            return Err(format!(
                "ids {id:?} and {:?} (claims[{j}]) differ only by case: they name files \
                 (spec_curve_<id>.svg), which would be one file where case is ignored",
                self.claims[j].id
            ));
        }
        Ok(())
    }

    fn check_rivals(c: &Claim) -> Result<(), String> {
        let Rivals::Only(names) = &c.rivals else {
            return Ok(());
        };
        if names.is_empty() {
            return Err("Only([]) names no rival: name one, or write Every".into());
        }
        for (k, name) in names.iter().enumerate() {
            check_name(name, "method")?;
            if c.is_subject(name) {
                return Err(format!(
                    "the subject {:?} is among its rivals ({name:?})",
                    c.subject
                ));
            }
            if names[..k].iter().any(|o| method_key(o) == method_key(name)) {
                return Err(format!("{name:?} is named twice"));
            }
        }
        Ok(())
    }
}

impl StudyFile for Claims {
    type File = ClaimsFile;
    type Error = ClaimsError;
    const MAX_BYTES: u64 = MAX_CLAIMS_BYTES;
    const KIND: &'static str = "a claims file";

    fn from_file(file: ClaimsFile, source: Source) -> Self {
        Self {
            source,
            claims: file.claims,
        }
    }

    fn check_file(&self) -> Result<(), ClaimsError> {
        if self.claims.is_empty() {
            return Err(self.error("claims", "no claims: give at least one".into()));
        }
        for (i, c) in self.claims.iter().enumerate() {
            let at = |field: &str| format!("claims[{i}].{field}");
            self.check_id(i, c).map_err(|m| self.error(&at("id"), m))?;
            if c.sentence.trim().is_empty()
                || c.sentence.chars().any(char::is_control)
                || c.sentence.chars().count() > MAX_NAME_CHARS
            {
                return Err(self.error(
                    &at("sentence"),
                    format!(
                        "expected the claim in words on one line (not empty, no line break or \
                         control character, at most {MAX_NAME_CHARS} characters)"
                    ),
                ));
            }
            if c.subject.trim().is_empty() {
                return Err(self.error(&at("subject"), "empty: name a method".into()));
            }
            check_name(&c.subject, "method").map_err(|m| self.error(&at("subject"), m))?;
            Self::check_rivals(c).map_err(|m| self.error(&at("rivals"), m))?;
            c.metric.task().map_err(|e| self.error(&at("metric"), e))?;
            if !(c.alpha > 0.0 && c.alpha <= 0.5) {
                return Err(self.error(
                    &at("alpha"),
                    format!("expected a one-sided level in (0, 0.5], found {}", c.alpha),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::{Correction, DEFAULT_ALPHA, Direction, Test};

    #[test]
    fn the_paper_file_holds_the_five_claims_of_section_vi() {
        let c = paper_claims();
        let ids: Vec<&str> = c.claims().iter().map(|c| c.id.as_str()).collect();
        assert_eq!(ids, ["1", "2", "3", "4a", "4b"]);
        let metrics: Vec<&str> = c.claims().iter().map(|c| c.metric.0.as_str()).collect();
        assert_eq!(
            metrics,
            [
                "rescued_total",
                "rescued_hard",
                "rescued_easy",
                "energy_per_hard_rescuee_pct",
                "hp_per_hard_rescuee_pct"
            ]
        );
        for claim in c.claims() {
            assert_eq!(claim.rivals, Rivals::Every);
            assert_eq!(
                (claim.test, claim.correction),
                (Test::PairedT, Correction::None)
            );
            assert!((claim.alpha - 0.05).abs() < 1e-15);
        }
        assert_eq!(c.claims()[3].direction, Direction::Less);
        let tasks = ["easy".to_string(), "hard".to_string()];
        assert!(c.check_tasks(&tasks).is_ok());
        assert!(c.check_tasks(&tasks[..1]).is_err());
    }

    #[test]
    fn defaults_fill_what_a_claim_leaves_out() {
        let c = Claims::parse(
            "(claims: [(id: \"a\", sentence: \"s\", subject: \"x\", metric: \"rounds\", \
             direction: Less)])",
            "c.ron",
        )
        .unwrap();
        let claim = &c.claims()[0];
        assert_eq!(claim.rivals, Rivals::Every);
        assert_eq!(
            (claim.test, claim.correction),
            (Test::PairedT, Correction::None)
        );
        assert!((claim.alpha - DEFAULT_ALPHA).abs() < 1e-15);
        // A method of one's own is known once it is among the sweep's methods.
        assert!(c.check_methods(&[]).is_err());
        assert!(c.check_methods(&["X".to_string()]).is_ok());
    }

    fn err(src: &str) -> String {
        Claims::parse(src, "c.ron").unwrap_err().to_string()
    }

    /// Regression (issue 70): `Claim` and `claim` were both accepted, and named the same
    /// `spec_curve_claim.svg` where case is ignored.
    #[test]
    fn ids_that_differ_only_by_case_are_refused_naming_both() {
        let src = "(claims: [\n  (id: \"Claim\", sentence: \"s\", subject: \"x\", metric: \
                   \"rounds\", direction: Less),\n  (id: \"claim\", sentence: \"t\", subject: \
                   \"x\", metric: \"rounds\", direction: Less),\n])";
        assert_eq!(
            err(src),
            "c.ron:3:4: claims[1].id: ids \"claim\" and \"Claim\" (claims[0]) differ only by \
             case: they name files (spec_curve_<id>.svg), which would be one file where case is \
             ignored"
        );
    }

    /// Regression (issue 70): a missing field was reported at the entry's last field
    /// (`claims[0].correction: Unexpected missing field named id`).
    #[test]
    fn a_missing_field_is_named_at_the_start_of_its_claim() {
        let src = "Claims(claims: [\n  (id: \"a\", sentence: \"s\", subject: \"x\", metric: \
                   \"rounds\", direction: Less),\n  (\n    sentence: \"t\", subject: \"x\",\n    \
                   metric: \"rounds\", direction: Less, correction: Holm\n  ),\n])";
        assert_eq!(err(src), "c.ron:3:3: claims[1]: missing field `id`");
    }

    /// Regression (issue 70): an alpha of 1e308 was written in full, 309 digits.
    #[test]
    fn a_huge_alpha_is_written_short() {
        let e = err(
            "(claims: [(id: \"a\", sentence: \"s\", subject: \"x\", metric: \"rounds\", \
                     direction: Less, alpha: 1e308)])",
        );
        assert!(
            e.ends_with("claims[0].alpha: expected a one-sided level in (0, 0.5], found 1e308"),
            "{e}"
        );
    }

    /// Regression (issue 70): sentences and method names of any length were read.
    #[test]
    fn sentences_and_method_names_are_bounded() {
        let claim = |sentence: &str, subject: &str| {
            format!(
                "(claims: [(id: \"a\", sentence: {sentence:?}, subject: {subject:?}, metric: \
                 \"rounds\", direction: Less)])"
            )
        };
        let long = "x".repeat(MAX_NAME_CHARS + 1);
        let e = err(&claim(&long, "x"));
        assert!(
            e.starts_with(
                "c.ron:1:21: claims[0].sentence: expected the claim in words on one \
                           line (not empty, no line break or control character, at most 200 \
                           characters)"
            ),
            "{e}"
        );
        let e = err(&claim("s", &long));
        assert!(
            e.contains(
                "claims[0].subject: method name of 201 characters, longer than the limit \
                        of 200"
            ),
            "{e}"
        );
        let most = "x".repeat(MAX_NAME_CHARS);
        assert!(Claims::parse(&claim(&most, "y"), "c.ron").is_ok());
    }

    #[test]
    fn ids_must_name_files() {
        for bad in ["", "a b", "../x", ".hidden", &"x".repeat(33)] {
            let src = format!(
                "(claims: [(id: {bad:?}, sentence: \"s\", subject: \"x\", metric: \"rounds\", \
                 direction: Less)])"
            );
            let e = Claims::parse(&src, "c.ron").unwrap_err();
            assert_eq!(e.0.field.as_deref(), Some("claims[0].id"), "{e}");
        }
    }
}
