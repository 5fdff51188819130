//! The scenario fields added after scenario hashes were first published, kept next to the
//! parameter blocks they belong to: a new field whose default keeps the old model is listed
//! here with that default, so a scenario that does not use it keeps its hash
//! (`usar_sweep::fingerprint::scenario_hash`). CONTRIBUTING.md, "A scenario field" and "A
//! mission rule".

/// Fields added after scenario hashes were first published, as (section, field, the value
/// that keeps the model as it was, as the validated scenario's JSON writes it): left out of
/// the hashed form while they hold that value. A field whose old value is not a unit enum
/// variant (a JSON string) cannot be listed; give it one.
pub const ADDED_FIELDS: [(&str, &str, &str); 10] = [
    ("mission", "idle_before_area", "Wait"),
    ("mission", "empty_on_leave", "ViaDropOff"),
    ("mission", "rest_at", "RestStation"),
    ("mission", "round_clock", "AllBack"),
    ("mission", "rest_timing", "OutOfRound"),
    ("mission", "resource_stock", "PerRound"),
    ("mission", "cost_clock", "PaperStep"),
    ("mission", "costs_count", "InGroup"),
    ("sim", "physics", "EveryStep"),
    ("collision", "steering", "Memoryless"),
];
