//! Needs vectors, weight vectors and group needs matrices (paper Sec. III, Defs. 1-3).

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::vector_newtype::vector_newtype;

fn check_needs(values: &[f64]) -> Result<()> {
    if values.is_empty() {
        return Err(RneError::Empty {
            what: "needs vector",
        });
    }
    match values.iter().position(|v| !v.is_finite() || *v < 0.0) {
        Some(index) => Err(RneError::InvalidNeed {
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// One robot's needs vector `N_R = (n_1, ..., n_j)` (paper Def. 1, Eqs. 19-21).
///
/// Shape: `j >= 1` entries, one per needs category (e.g. `hp, v, sen, eng, res, cap, obs` in the
/// paper's USAR team). Each entry is finite and `>= 0`, in whatever unit the category uses;
/// only ratios matter after weighting and normalisation (Eq. 8).
///
/// Serialises as a plain list of numbers; deserialising validates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct NeedsVector(DVector<f64>);

impl NeedsVector {
    /// Builds a needs vector.
    ///
    /// # Errors
    /// [`RneError::Empty`] if `values` is empty; [`RneError::InvalidNeed`] naming the first
    /// negative, NaN or infinite entry.
    pub fn new(values: impl Into<Vec<f64>>) -> Result<Self> {
        let values = values.into();
        check_needs(&values)?;
        Ok(Self(DVector::from_vec(values)))
    }
}

vector_newtype!(NeedsVector, "needs", validated);

/// The weight vector `W = (w_1, ..., w_j)` giving each needs category's priority (Def. 1, Eq. 8).
///
/// Shape: `j >= 1` entries, each finite and `> 0` (dimensionless). Example 1 uses `[6, 4, 2]`.
/// Serialises as a plain list of numbers; deserialising validates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct Weights(DVector<f64>);

impl Weights {
    /// Builds a weight vector.
    ///
    /// # Errors
    /// [`RneError::Empty`] if `values` is empty; [`RneError::InvalidWeight`] naming the first
    /// entry that is `<= 0`, NaN or infinite.
    pub fn new(values: impl Into<Vec<f64>>) -> Result<Self> {
        let values = values.into();
        if values.is_empty() {
            return Err(RneError::Empty {
                what: "weight vector",
            });
        }
        if let Some(index) = values.iter().position(|w| !w.is_finite() || *w <= 0.0) {
            return Err(RneError::InvalidWeight {
                index,
                value: values[index],
            });
        }
        Ok(Self(DVector::from_vec(values)))
    }

    /// `j` equal weights of 1 (the paper's footnote to Example 1 mentions equal weights).
    ///
    /// # Errors
    /// [`RneError::Empty`] if `j == 0`.
    pub fn uniform(j: usize) -> Result<Self> {
        Self::new(vec![1.0; j])
    }
}

vector_newtype!(Weights, "weights", validated);

/// A group's needs matrix (Eq. 15): `i` rows (robots) by `j` columns (needs categories).
///
/// Every entry is finite and `>= 0`; `i >= 1` and `j >= 1`. Serialises as a list of rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<Vec<f64>>", into = "Vec<Vec<f64>>")]
pub struct NeedsMatrix(DMatrix<f64>);

impl NeedsMatrix {
    /// Builds the matrix from the members' needs vectors (one row each).
    ///
    /// # Errors
    /// [`RneError::Empty`] for an empty group; [`RneError::LengthMismatch`] if the members'
    /// vectors differ in length (reference: the first member).
    pub fn from_members<'a>(members: impl IntoIterator<Item = &'a NeedsVector>) -> Result<Self> {
        let members: Vec<&NeedsVector> = members.into_iter().collect();
        let Some(first) = members.first() else {
            return Err(RneError::Empty { what: "group" });
        };
        let j = first.len();
        if let Some(bad) = members.iter().find(|m| m.len() != j) {
            return Err(RneError::LengthMismatch {
                what: "group member needs vector",
                expected: j,
                actual: bad.len(),
            });
        }
        Ok(Self(DMatrix::from_fn(members.len(), j, |r, c| {
            members[r].as_slice()[c]
        })))
    }

    /// Builds the matrix from raw rows, validating every entry like [`NeedsVector::new`].
    ///
    /// # Errors
    /// As [`NeedsVector::new`] for each row, and as [`NeedsMatrix::from_members`].
    pub fn from_rows(rows: &[Vec<f64>]) -> Result<Self> {
        let members = rows
            .iter()
            .map(|r| NeedsVector::new(r.clone()))
            .collect::<Result<Vec<_>>>()?;
        Self::from_members(&members)
    }

    /// The matrix (`i x j`, row = robot).
    pub fn as_dmatrix(&self) -> &DMatrix<f64> {
        &self.0
    }

    /// Number of robots `i` (rows, `>= 1`).
    pub fn robots(&self) -> usize {
        self.0.nrows()
    }

    /// Number of needs categories `j` (columns, `>= 1`).
    pub fn categories(&self) -> usize {
        self.0.ncols()
    }
}

impl TryFrom<Vec<Vec<f64>>> for NeedsMatrix {
    type Error = RneError;
    fn try_from(rows: Vec<Vec<f64>>) -> Result<Self> {
        Self::from_rows(&rows)
    }
}

impl From<NeedsMatrix> for Vec<Vec<f64>> {
    fn from(m: NeedsMatrix) -> Self {
        m.0.row_iter()
            .map(|r| r.iter().copied().collect())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_needs_and_names_index() {
        assert_eq!(
            NeedsVector::new(vec![1.0, -2.0]),
            Err(RneError::InvalidNeed {
                index: 1,
                value: -2.0
            })
        );
        assert!(matches!(
            NeedsVector::new(vec![f64::NAN]),
            Err(RneError::InvalidNeed { index: 0, .. })
        ));
        assert_eq!(
            NeedsVector::new(Vec::<f64>::new()),
            Err(RneError::Empty {
                what: "needs vector"
            })
        );
    }

    #[test]
    fn rejects_bad_weights() {
        assert_eq!(
            Weights::new(vec![1.0, 0.0]),
            Err(RneError::InvalidWeight {
                index: 1,
                value: 0.0
            })
        );
        assert!(Weights::new(vec![f64::INFINITY]).is_err());
    }

    #[test]
    fn matrix_checks_lengths_and_emptiness() {
        let a = NeedsVector::new(vec![1.0, 2.0]).unwrap();
        let b = NeedsVector::new(vec![1.0]).unwrap();
        assert!(matches!(
            NeedsMatrix::from_members([&a, &b]),
            Err(RneError::LengthMismatch {
                expected: 2,
                actual: 1,
                ..
            })
        ));
        assert_eq!(
            NeedsMatrix::from_members(std::iter::empty()),
            Err(RneError::Empty { what: "group" })
        );
        let m = NeedsMatrix::from_members([&a, &a]).unwrap();
        assert_eq!((m.robots(), m.categories()), (2, 2));
    }

    #[test]
    fn conversions_used_by_serde_validate() {
        let n = NeedsVector::try_from(vec![1.0, 2.0]).unwrap();
        assert_eq!(Vec::<f64>::from(n), vec![1.0, 2.0]);
        assert!(NeedsVector::try_from(vec![-1.0]).is_err());
        let m = NeedsMatrix::try_from(vec![vec![1.0, 2.0], vec![3.0, 4.0]]).unwrap();
        assert_eq!(
            Vec::<Vec<f64>>::from(m),
            vec![vec![1.0, 2.0], vec![3.0, 4.0]]
        );
    }
}
