//! Scenario fingerprints: the hash that journals, reports and `usar check` show for a
//! validated scenario, so a grid cell's `scenario.ron` can be matched to its cell.

use anyhow::{Context, Result};
use usar_sim::scenario::Scenario;

/// FNV-1a 64-bit hash of `bytes`, as 16 hex digits (stable across platforms and releases).
pub fn fnv1a64_hex(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The scenario hash: [`fnv1a64_hex`] of the validated scenario serialised as JSON. Any
/// change to what the scenario means changes it; comments, layout, and writing out a default
/// value or leaving it out do not.
///
/// # Errors
/// A scenario serde_json cannot serialise (not expected).
pub fn scenario_hash(scenario: &Scenario) -> Result<String> {
    let json = serde_json::to_vec(scenario).context("serialising the scenario")?;
    Ok(fnv1a64_hex(&json))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_known_values() {
        assert_eq!(fnv1a64_hex(b""), "cbf29ce484222325");
        assert_eq!(fnv1a64_hex(b"a"), "af63dc4c8601ec8c");
    }

    #[test]
    fn hash_follows_meaning_not_layout() {
        let src = include_str!("../../../scenarios/paper.ron");
        let a = usar_sim::scenario::from_str(src, "a").unwrap();
        let b = usar_sim::scenario::from_str(&format!("// note\n{src}"), "b").unwrap();
        assert_eq!(scenario_hash(&a).unwrap(), scenario_hash(&b).unwrap());
        let c =
            usar_sim::scenario::from_str(&src.replace("recharge_s: 30.0", "recharge_s: 31.0"), "c")
                .unwrap();
        assert_ne!(scenario_hash(&a).unwrap(), scenario_hash(&c).unwrap());
    }
}
