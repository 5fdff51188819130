//! The published JSON Schemas (`docs/schema/`) of what `usar run --json` writes and of the
//! sweep journal's lines (shard journals included) are those of the code, and real outputs fit
//! them. `USAR_WRITE_SCHEMA=1 cargo test -p experiments --test integration json_schema` rewrites them.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;
use usar_sweep::journal::JournalLine;
use usar_sweep::trial_json::TrialJson;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `(file under docs/schema, the schema the code gives)`.
fn schemas() -> Vec<(&'static str, String)> {
    let pretty = |s: schemars::Schema| serde_json::to_string_pretty(&s).expect("JSON") + "\n";
    vec![
        (
            "trial.schema.json",
            pretty(schemars::schema_for!(TrialJson)),
        ),
        (
            "journal-line.schema.json",
            pretty(schemars::schema_for!(JournalLine)),
        ),
    ]
}

#[test]
fn the_published_schemas_are_the_codes() {
    let write = std::env::var_os("USAR_WRITE_SCHEMA").is_some();
    for (file, schema) in schemas() {
        let path = root().join("docs/schema").join(file);
        if write {
            std::fs::write(&path, &schema).expect("writable docs/schema");
            continue;
        }
        let published = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            published == schema,
            "docs/schema/{file} is stale: rewrite it with \
             USAR_WRITE_SCHEMA=1 cargo test -p experiments --test integration json_schema"
        );
    }
}

/// The names `schema` allows at the top level of an object of the definition `def` (or of the
/// root when `def` is `None`), and those it requires.
fn properties(schema: &Value, path: &[&str]) -> (Vec<String>, Vec<String>) {
    let mut node = schema;
    for p in path {
        node = &node[*p];
    }
    let names = |v: &Value| -> Vec<String> {
        v.as_object()
            .map(|o| o.keys().cloned().collect())
            .unwrap_or_default()
    };
    let required = node["required"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|v| v.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default();
    (names(&node["properties"]), required)
}

/// Every key of `obj` is allowed and every required key is there.
fn fits(obj: &Value, allowed: &[String], required: &[String], what: &str) {
    let keys: Vec<&String> = obj.as_object().expect("an object").keys().collect();
    for k in &keys {
        assert!(allowed.contains(k), "{what}: {k} is not in the schema");
    }
    for r in required {
        assert!(keys.contains(&r), "{what}: required {r} missing");
    }
}

fn usar(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("usar runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn run_json_and_journal_lines_fit_their_schemas() {
    let tmp = tempfile::tempdir().unwrap();
    let json = tmp.path().join("t.json");
    let out = tmp.path().join("sweep");
    usar(&[
        "run",
        "scenarios/paper.ron",
        "--duration",
        "5",
        "--json",
        json.to_str().unwrap(),
    ]);
    usar(&[
        "sweep",
        "scenarios/paper.ron",
        "--methods",
        "rne",
        "--trials",
        "1",
        "--duration",
        "5",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let trial_schema: Value = serde_json::from_str(&schemas()[0].1).unwrap();
    let trial: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let (allowed, required) = properties(&trial_schema, &[]);
    fits(&trial, &allowed, &required, "usar run --json");
    serde_json::from_value::<TrialJson>(trial).expect("reads back as the schema's type");

    let journal = std::fs::read_to_string(out.join("journal.jsonl")).unwrap();
    let lines: Vec<&str> = journal.lines().collect();
    assert_eq!(lines.len(), 2, "a header and one trial");
    for (i, line) in lines.iter().enumerate() {
        let parsed: JournalLine = serde_json::from_str(line).expect("a journal line");
        let header = matches!(parsed, JournalLine::Header { .. });
        assert_eq!(header, i == 0, "line {i}: the header first, then trials");
        let value: Value = serde_json::from_str(line).unwrap();
        fits(
            &value,
            &["header".into(), "trial".into(), "sum".into()],
            &["sum".into()],
            "line",
        );
    }
}
