//! Why a grid cannot be built from its `--vary` arguments ([`crate::grid::build_grid`]).

use crate::settings::Setting;

/// Why a grid was refused: one line naming the `--vary` argument (shortened, as
/// [`crate::vary::brief`] shows it) and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    /// No `--vary` argument.
    #[error("a grid needs at least one {}", Setting::Vary)]
    NoVary,
    /// An argument that is malformed, names no field, or gives a value of the wrong type.
    #[error("{} {arg}: {problem}", Setting::Vary)]
    Vary {
        /// The argument, shortened.
        arg: String,
        /// What is wrong with it.
        problem: String,
    },
    /// One field varied twice.
    #[error("{} {path} is given twice: vary each field once", Setting::Vary)]
    Twice {
        /// The field's path.
        path: String,
    },
    /// Two fields that set some of the same values (`zones[*].r` and `zones[2].r`).
    #[error(
        "{} {first} overlaps {} {second}: they set some of the same values",
        Setting::Vary,
        Setting::Vary
    )]
    Overlap {
        /// The earlier field's path.
        first: String,
        /// The later field's path.
        second: String,
    },
    /// More cells than [`MAX_SWEEP_TRIALS`](crate::sweep::MAX_SWEEP_TRIALS) (found before any
    /// cell is made).
    #[error(
        "the grid's {shape} make {cells} cells, more than the limit of {limit} trials per sweep"
    )]
    TooManyCells {
        /// The value counts as a product, `10 x 10 x 3 values`.
        shape: String,
        /// The cell count (`more than 18446744073709551614` when it overflows).
        cells: String,
        /// The limit.
        limit: usize,
    },
    /// A cell that breaks a scenario rule: the line of
    /// [`rule_error`](crate::vary::rule_error) (`--vary FIELD=VALUE: field.path: message`).
    #[error("{line}")]
    CellRule {
        /// The whole line.
        line: String,
    },
    /// Two values of one `--vary` that give the same scenario in every cell.
    #[error(
        "{} {arg}: values {first} and {second} give the same scenario",
        Setting::Vary
    )]
    SameScenario {
        /// The argument, shortened.
        arg: String,
        /// The first value, shortened.
        first: String,
        /// The second value, shortened.
        second: String,
    },
    /// The base scenario cannot be turned into JSON to set values in (not expected).
    #[error("{problem}")]
    Base {
        /// serde_json's message.
        problem: String,
    },
}
