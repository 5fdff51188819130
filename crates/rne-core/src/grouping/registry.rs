//! Building a grouping method from its name.

use crate::error::{Result, RneError};
use crate::grouping::dis::Dis;
use crate::grouping::eng::Eng;
use crate::grouping::hierarchical::HierarchicalRne;
use crate::grouping::hp_dis::HpDis;
use crate::grouping::method::GroupingMethod;
use crate::rne::TrustModel;

/// The names accepted by [`method_from_name`], in the paper's order of Sec. VI.C.
pub const METHOD_NAMES: [&str; 4] = ["rne", "dis", "eng", "hp_dis"];

/// The key a method name is compared by, built-in or not: surrounding spaces dropped, lower
/// case, `-` read as `_` (`" HP-dis "`, `"hp_dis"` and `"HP_DIS"` are one method). The one
/// place method names are normalised: [`builtin_name`], [`method_from_name`] and every
/// caller that compares method names (a claims file's subjects and rivals) use it.
///
/// ```
/// use rne_core::grouping::method_key;
///
/// assert_eq!(method_key(" HP-dis "), "hp_dis");
/// assert_eq!(method_key("My-Method"), "my_method");
/// ```
pub fn method_key(name: &str) -> String {
    name.trim().to_ascii_lowercase().replace('-', "_")
}

/// The built-in method a name means (its [`method_key`]): one of [`METHOD_NAMES`], or `None`.
///
/// ```
/// use rne_core::grouping::builtin_name;
///
/// assert_eq!(builtin_name(" HP-dis "), Some("hp_dis"));
/// assert_eq!(builtin_name("mine"), None);
/// ```
pub fn builtin_name(name: &str) -> Option<&'static str> {
    let key = method_key(name);
    METHOD_NAMES.iter().copied().find(|m| *m == key)
}

/// Builds a built-in grouping method from its name (case-insensitive, surrounding spaces
/// ignored): `"rne"` ([`HierarchicalRne`] with `rne_model`), `"dis"` ([`Dis`]), `"eng"`
/// ([`Eng`]), `"hp_dis"` ([`HpDis`]; `"hp-dis"` is accepted too). `rne_model` is only used by
/// `"rne"`. Their [`GroupingMethod::display_name`]s are the paper's `RNE`, `DIS`, `ENG` and
/// `HP_DIS`.
///
/// ```
/// use rne_core::{TrustModel, Weights};
/// use rne_core::grouping::method_from_name;
///
/// let model = TrustModel::with_weights(Weights::uniform(7)?);
/// let m = method_from_name("HP_DIS", &model)?;
/// assert_eq!((m.name(), m.display_name()), ("hp_dis", "HP_DIS"));
/// let err = method_from_name("random", &model).err().unwrap();
/// assert_eq!(err.to_string(), r#"unknown grouping method "random"; valid names: rne, dis, eng, hp_dis"#);
/// # Ok::<(), rne_core::RneError>(())
/// ```
///
/// # Errors
/// [`RneError::UnknownMethod`] listing the valid names.
pub fn method_from_name(name: &str, rne_model: &TrustModel) -> Result<Box<dyn GroupingMethod>> {
    match builtin_name(name) {
        Some("rne") => Ok(Box::new(HierarchicalRne::new(rne_model.clone()))),
        Some("dis") => Ok(Box::new(Dis)),
        Some("eng") => Ok(Box::new(Eng)),
        Some("hp_dis") => Ok(Box::new(HpDis)),
        _ => Err(RneError::UnknownMethod {
            name: name.to_string(),
            valid: METHOD_NAMES.join(", "),
        }),
    }
}
