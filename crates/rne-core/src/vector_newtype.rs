//! Accessors shared by the vector newtypes [`crate::NeedsVector`], [`crate::Weights`] and
//! [`crate::Distribution`]: each wraps a non-empty `nalgebra::DVector<f64>` of length `j`.

/// Implements `as_dvector`, `as_slice`, `len`, `is_empty` and `From<T> for Vec<f64>` for a
/// newtype `T(DVector<f64>)` whose entries are called `$what` in the docs; with `validated`,
/// also `TryFrom<Vec<f64>>` through the type's own `new` (used by serde's `try_from`).
macro_rules! vector_newtype {
    ($t:ident, $what:literal) => {
        impl $t {
            #[doc = concat!("The ", $what, " as an `nalgebra` column vector of length `j`.")]
            pub fn as_dvector(&self) -> &nalgebra::DVector<f64> {
                &self.0
            }

            #[doc = concat!("The ", $what, " as a slice of length `j`.")]
            pub fn as_slice(&self) -> &[f64] {
                self.0.as_slice()
            }

            /// Number of needs categories `j` (always `>= 1`).
            pub fn len(&self) -> usize {
                self.0.len()
            }

            /// Always `false` (there is at least one entry); provided for clippy's
            /// `len_without_is_empty`.
            pub fn is_empty(&self) -> bool {
                self.0.is_empty()
            }
        }

        impl From<$t> for Vec<f64> {
            fn from(v: $t) -> Self {
                v.0.as_slice().to_vec()
            }
        }
    };
    ($t:ident, $what:literal, validated) => {
        vector_newtype!($t, $what);

        impl TryFrom<Vec<f64>> for $t {
            type Error = crate::error::RneError;
            fn try_from(values: Vec<f64>) -> crate::error::Result<Self> {
                Self::new(values)
            }
        }
    };
}

pub(crate) use vector_newtype;
