//! Every `usar ...` command the README and the docs show parses: a test that reads the
//! Markdown files' code blocks and gives each command line to the same parser `usar` uses.
//!
//! A command is a line of a fenced code block that starts with `usar ` (after an optional
//! `$ `) or runs the binary through `cargo run ... --bin usar -- `; lines ending in `\` continue
//! it. It ends at a comment (` #`), a pipe, a redirection, `&&` or `;`. A synopsis (a line with
//! a placeholder such as `SCENARIO`, `[sweep options]` or `...`) is not a command and is
//! skipped. Scenario files the command names under `scenarios/` must exist.
//!
//! The same files say what is true now: no commit hash (a word of 7 to 40 hex digits with a
//! letter and a digit) and no "measured again" outside `docs/measurements.md`, the one dated
//! history of measurements (CHANGELOG.md is not scanned).

use std::path::{Path, PathBuf};

use clap::Parser;

use crate::cli::Cli;

/// The workspace root (this crate is `crates/experiments`).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The Markdown files whose commands are checked: README.md, CONTRIBUTING.md, docs/*.md and
/// each crate's README.md.
fn markdown_files() -> Vec<PathBuf> {
    let root = root();
    let mut files = vec![root.join("README.md"), root.join("CONTRIBUTING.md")];
    for dir in [root.join("docs"), root.join("crates")] {
        let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("directory entry").path())
            .flat_map(|p| {
                if p.is_dir() {
                    vec![p.join("README.md")]
                } else {
                    vec![p]
                }
            })
            .filter(|p| p.extension().is_some_and(|e| e == "md") && p.is_file())
            .collect();
        found.sort();
        files.extend(found);
    }
    files
}

/// Whether `word` looks like a commit hash: 7 to 40 lower-case hex digits, at least one
/// letter and one digit (so neither `0.0037255` nor `deadbeef`-free words like `facade` match).
fn looks_like_hash(word: &str) -> bool {
    (7..=40).contains(&word.len())
        && word
            .chars()
            .all(|c| c.is_ascii_digit() || ('a'..='f').contains(&c))
        && word.chars().any(|c| c.is_ascii_digit())
        && word.chars().any(|c| c.is_ascii_alphabetic())
}

/// The places in `md` (named `name`) that log history: hash-like words and "measured again".
fn history_in(name: &str, md: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (i, line) in md.lines().enumerate() {
        let hashes = line
            .split(|c: char| !c.is_ascii_alphanumeric())
            .filter(|w| looks_like_hash(w));
        for word in hashes {
            found.push(format!("{name}:{}: commit hash? {word}", i + 1));
        }
        if line.to_lowercase().contains("measured again") {
            found.push(format!("{name}:{}: \"measured again\"", i + 1));
        }
    }
    found
}

/// One command found in a file: where it starts, and its text with continuations joined.
struct Shown {
    place: String,
    text: String,
}

/// The arguments after `usar` in `line`, if the line runs `usar`.
fn usar_args(line: &str) -> Option<&str> {
    let line = line.strip_prefix("$ ").unwrap_or(line);
    if let Some(rest) = line.strip_prefix("usar ") {
        return Some(rest);
    }
    let (cargo, rest) = line.split_once(" -- ")?;
    (cargo.starts_with("cargo run") && cargo.contains("--bin usar")).then_some(rest)
}

/// The commands shown in the fenced code blocks of `md` (named `name` in messages).
fn commands_in(name: &str, md: &str) -> Vec<Shown> {
    let mut shown = Vec::new();
    let mut in_block = false;
    let mut open: Option<Shown> = None;
    for (i, line) in md.lines().enumerate() {
        let t = line.trim();
        if t.starts_with("```") {
            in_block = !in_block;
            continue;
        }
        if !in_block {
            continue;
        }
        let piece = match open.take() {
            Some(mut cmd) => {
                cmd.text.push(' ');
                cmd.text.push_str(t.trim_end_matches('\\').trim_end());
                cmd
            }
            None => match usar_args(t) {
                Some(args) => Shown {
                    place: format!("{name}:{}", i + 1),
                    text: args.trim_end_matches('\\').trim_end().to_owned(),
                },
                None => continue,
            },
        };
        if t.ends_with('\\') {
            open = Some(piece);
        } else {
            shown.push(piece);
        }
    }
    shown
}

/// `text` up to its first comment, pipe, redirection, `&&` or `;` outside quotes.
fn command_part(text: &str) -> &str {
    let mut quote: Option<char> = None;
    let mut prev = ' ';
    for (i, c) in text.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '\'' | '"') => quote = Some(c),
            (None, '#') if prev == ' ' => return &text[..i],
            (None, '|' | '>' | ';') => return &text[..i],
            (None, '&') if text[i..].starts_with("&&") => return &text[..i],
            _ => {}
        }
        prev = c;
    }
    text
}

/// Whether `word` is a placeholder of a synopsis (`SCENARIO`, `DIR`, `I/N`, `[sweep`, `...`).
fn is_placeholder(word: &str) -> bool {
    let caps = word.chars().any(|c| c.is_ascii_uppercase())
        && word
            .chars()
            .all(|c| c.is_ascii_uppercase() || c == '/' || c == '_');
    caps || word.starts_with('[') && !word.contains('=') || word.contains("...")
}

#[test]
fn every_usar_command_in_the_readme_and_docs_parses() {
    let mut checked = 0;
    let mut failures = Vec::new();
    for file in markdown_files() {
        let md = std::fs::read_to_string(&file).expect("readable Markdown");
        let name = file
            .strip_prefix(root())
            .unwrap_or(&file)
            .display()
            .to_string();
        for cmd in commands_in(&name, &md) {
            let Some(words) = shlex::split(command_part(&cmd.text)) else {
                failures.push(format!("{}: unbalanced quotes: {}", cmd.place, cmd.text));
                continue;
            };
            if words.iter().any(|w| is_placeholder(w)) {
                continue;
            }
            checked += 1;
            let argv = std::iter::once("usar".to_owned()).chain(words.iter().cloned());
            if let Err(e) = Cli::try_parse_from(argv) {
                let first = e.render().to_string();
                let first = first.lines().next().unwrap_or("").to_owned();
                failures.push(format!("{}: usar {}: {first}", cmd.place, words.join(" ")));
            }
            for w in words.iter().filter(|w| w.starts_with("scenarios/")) {
                if !root().join(w).exists() {
                    failures.push(format!("{}: no such file {w}", cmd.place));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The README alone shows more than 15; fewer means the scan stopped finding them.
    assert!(checked >= 40, "only {checked} commands found");
    eprintln!("{checked} commands parse");
}

#[test]
fn the_readme_and_docs_carry_no_commit_hash_outside_the_measurements_file() {
    let mut found = Vec::new();
    for file in markdown_files() {
        if file.ends_with("docs/measurements.md") {
            continue;
        }
        let md = std::fs::read_to_string(&file).expect("readable Markdown");
        let name = file.strip_prefix(root()).unwrap_or(&file).display();
        found.extend(history_in(&name.to_string(), &md));
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn the_history_scan_finds_hashes_and_remeasurements_but_not_numbers() {
    let md = "at commit 7382cd6 it\nMeasured again later\n0.0037255 and 1,845 and facade\n";
    assert_eq!(
        history_in("t.md", md),
        ["t.md:1: commit hash? 7382cd6", "t.md:2: \"measured again\""]
    );
}

#[test]
fn the_scan_finds_continued_cargo_run_and_prompted_commands_and_cuts_their_tails() {
    let md = "text\n```sh\n$ usar check a.ron  # look\ncargo run --release -p experiments \
              --bin usar -- sweep s.ron \\\n    --trials 2 > out.txt\nusar merge x | head\n\
              echo usar run\n```\nusar run outside.ron\n";
    let got: Vec<String> = commands_in("t.md", md)
        .iter()
        .map(|c| format!("{} {}", c.place, command_part(&c.text).trim()))
        .collect();
    assert_eq!(
        got,
        [
            "t.md:3 check a.ron",
            "t.md:4 sweep s.ron --trials 2",
            "t.md:6 merge x"
        ]
    );
    assert!(is_placeholder("SCENARIO") && is_placeholder("I/N") && is_placeholder("[sweep"));
    assert!(!is_placeholder("rne:0,dis:3") && !is_placeholder("'radiation_zones[*].x=1'"));
}

#[test]
fn a_wrong_flag_in_a_shown_command_fails_the_parse() {
    let words = shlex::split(command_part("sweep scenarios/paper.ron --trails 3 # typo"))
        .expect("balanced");
    let argv = std::iter::once("usar".to_owned()).chain(words);
    assert!(Cli::try_parse_from(argv).is_err());
}
