//! Scenario fingerprints: the hash that journals, reports and `usar check` show for a
//! validated scenario, so a grid cell's `scenario.ron` can be matched to its cell.

use serde_json::Value;
use usar_sim::scenario::{ADDED_FIELDS, Scenario};

/// FNV-1a 64-bit hash of `bytes`, as 16 hex digits (stable across platforms and releases).
pub fn fnv1a64_hex(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The scenario hash: [`fnv1a64_hex`] of the validated scenario serialised as JSON, without
/// the fields added later ([`ADDED_FIELDS`], kept next to the parameter blocks in `usar_sim::scenario`) that hold their old value. Any change to what the
/// scenario means changes it; comments, layout, the `report` section (data no trial reads;
/// not part of the validated scenario's JSON), and writing out a default value or leaving it
/// out do not.
///
/// # Errors
/// A scenario serde_json cannot serialise (not expected), with serde_json's error.
pub fn scenario_hash(scenario: &Scenario) -> Result<String, serde_json::Error> {
    let mut value = serde_json::to_value(scenario)?;
    for (section, field, old) in ADDED_FIELDS {
        if let Some(fields) = value.get_mut(section).and_then(Value::as_object_mut)
            && fields.get(field).and_then(Value::as_str) == Some(old)
        {
            fields.shift_remove(field);
        }
    }
    let json = serde_json::to_vec(&value)?;
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

    #[test]
    fn the_report_section_is_not_hashed() {
        let src = include_str!("../../../scenarios/paper.ron");
        let hash =
            |text: &str| scenario_hash(&usar_sim::scenario::from_str(text, "s").unwrap()).unwrap();
        let none = src.replace(
            "report: (targets: \"paper-targets.ron\", claims: \"paper-claims.ron\"),",
            "",
        );
        assert_ne!(none, src);
        let other = src.replace("paper-claims.ron", "mine.ron");
        assert_eq!(hash(&none), hash(src));
        assert_eq!(hash(&other), hash(src));
    }

    #[test]
    fn a_field_added_later_keeps_the_hashes_of_scenarios_that_do_not_use_it() {
        // The hashes before `mission.idle_before_area`, `empty_on_leave`, `rest_at`,
        // `sim.physics` and `collision.steering` existed (`usar check FILE --hash`); paper.ron
        // as it was then is today's without its `physics: NearContacts` and with the steering
        // of then written out (today's default, `KeepSide`, changes the model).
        let hash_of = |src: &str| {
            let s = usar_sim::scenario::from_str(src, "s").unwrap();
            scenario_hash(&s).unwrap()
        };
        // paper-v1.ron (pinned: it uses none of the added fields and writes out the old
        // steering) and three-tasks.ron with the old steering written out.
        let old_steering = |src: &str| {
            let to = "deadlock_after_s: 2.0, steering: Memoryless)";
            src.replacen("deadlock_after_s: 2.0)", to, 1)
        };
        let paper_v1 = include_str!("../../../scenarios/paper-v1.ron").replacen(
            ",\n        steering: Memoryless",
            ", steering: Memoryless",
            1,
        );
        let three_tasks = old_steering(include_str!("../../../scenarios/three-tasks.ron"));
        let before = [
            (paper_v1.as_str(), "2641e2e6fd51e303"),
            (three_tasks.as_str(), "97fe69ca418d0202"),
        ];
        // Each added field (after the field it is written before): the value that keeps the
        // old model, and one that changes it.
        let added = [
            ("idle_before_area", "pickup_s:", "Wait", "GoToArea"),
            (
                "empty_on_leave",
                "pickup_s:",
                "ViaDropOff",
                "StraightToStart",
            ),
            ("rest_at", "pickup_s:", "RestStation", "OwnStart"),
            ("physics", "dt_s: 0.02", "EveryStep", "NearContacts"),
            (
                "round_clock",
                "pickup_s:",
                "AllBack",
                "Timer(length_s: 100.0)",
            ),
            ("rest_timing", "pickup_s:", "OutOfRound", "InSlack"),
            (
                "cost_clock",
                "pickup_s:",
                "PaperStep",
                "Frames(steps_per_s: 130.0)",
            ),
            ("costs_count", "pickup_s:", "InGroup", "Every"),
        ];
        let with = |src: &str, field: &str, before: &str, value: &str| {
            hash_of(&src.replacen(before, &format!("{field}: {value}, {before}"), 1))
        };
        for (src, hash) in before {
            assert_eq!(hash_of(src), hash);
            let default_steering = src.replacen(", steering: Memoryless", "", 1);
            assert_ne!(hash_of(&default_steering), hash, "steering: KeepSide");
            for (field, before, old, new) in added {
                assert_eq!(
                    with(src, field, before, old),
                    hash,
                    "{field}: {old} written out"
                );
                assert_ne!(with(src, field, before, new), hash, "{field}: {new}");
            }
        }
    }
}
