//! Fuzz test of scenario loading and a short run (issue 11, "Tests that keep it so").
//!
//! proptest draws mutations of the shipped scenarios (`scenarios/*.ron`): bit flips,
//! truncations, deleted lines, duplicated lines (once or thousands of times: huge lists) and
//! numbers replaced by extreme values. Each mutated file goes through `scenario::load` (what
//! `usar check` runs) and, when accepted, a five-step trial with the `rne` method. The test
//! asserts, over all cases: no panic, no hang (each case within [`CASE_BOUND`] of wall-clock
//! time), every rejection one line, and a trial of every accepted file that runs (no error).
//! An abort (a failed allocation) would end the test process, which fails the test too.
//!
//! The number of cases is `USAR_FUZZ_CASES` (default 300, about a minute in CI); the draw is
//! deterministic (proptest's ChaCha test RNG, seed `USAR_FUZZ_SEED`, default 0). The counts
//! are printed (`cargo test -p integration-tests --test integration scenario_fuzz -- --nocapture`).

use std::cell::{Cell, RefCell};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::mpsc;
use std::time::Duration;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use usar_sim::mission::{Simulation, tasks_without_rescue, unreachable_goals};
use usar_sim::scenario;

/// Wall-clock bound of one case (load, validation and the short trial).
const CASE_BOUND: Duration = Duration::from_secs(30);

/// The longest run of digits an error may hold: the longest extreme below (23) quoted back,
/// but not a huge or tiny value written out in full (`1e300` as 301 digits).
const MAX_DIGITS_IN_A_MESSAGE: usize = 24;

/// The longest run of ASCII digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

/// Values an extreme-number mutation writes in place of a number.
const EXTREMES: [&str; 16] = [
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "4294967295",
    "18446744073709551615",
    "99999999999999999999999",
    "1e-9",
    "1e9",
    "-1",
    "0.8",
    "1e-300",
    "2147483648",
    "1.7976931348623157e308",
    "5e-324",
];

/// One edit of a file's bytes; positions are fractions of the length in `[0, 1)`.
#[derive(Debug, Clone)]
enum Mutation {
    /// Flip bit `bit` of the byte at `at`.
    FlipBit { at: f64, bit: u8 },
    /// Keep the bytes before `at`.
    Truncate { at: f64 },
    /// Delete the line at `at`.
    DeleteLine { at: f64 },
    /// Insert `times` copies of the line at `at` after it.
    DuplicateLine { at: f64, times: usize },
    /// Replace the number nearest after `at` by `EXTREMES[value]`.
    ExtremeNumber { at: f64, value: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), 0u8..8).prop_map(|(at, bit)| Mutation::FlipBit { at, bit }),
        at.clone().prop_map(|at| Mutation::Truncate { at }),
        at.clone().prop_map(|at| Mutation::DeleteLine { at }),
        (
            at.clone(),
            prop_oneof![Just(1usize), Just(2), Just(10), Just(300), Just(12_000)]
        )
            .prop_map(|(at, times)| Mutation::DuplicateLine { at, times }),
        (at.clone(), 0..EXTREMES.len())
            .prop_map(|(at, value)| Mutation::ExtremeNumber { at, value }),
        (at, 0..EXTREMES.len()).prop_map(|(at, value)| Mutation::ExtremeNumber { at, value }),
    ]
}

fn index(at: f64, len: usize) -> usize {
    ((at * len as f64) as usize).min(len.saturating_sub(1))
}

/// The byte ranges of the numbers in `text`: a digit run not inside a name, with its sign,
/// fraction and exponent.
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit()
            && (i == 0 || !(text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_'));
        if !starts {
            i += 1;
            continue;
        }
        let begin = if i > 0 && text[i - 1] == b'-' {
            i - 1
        } else {
            i
        };
        let mut end = i;
        while end < text.len()
            && (text[end].is_ascii_digit()
                || matches!(text[end], b'.' | b'e' | b'E')
                || (matches!(text[end], b'+' | b'-') && matches!(text[end - 1], b'e' | b'E')))
        {
            end += 1;
        }
        out.push((begin, end));
        i = end;
    }
    out
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    if bytes.is_empty() {
        return;
    }
    match *m {
        Mutation::FlipBit { at, bit } => {
            let i = index(at, bytes.len());
            bytes[i] ^= 1 << bit;
        }
        Mutation::Truncate { at } => bytes.truncate(index(at, bytes.len())),
        Mutation::DeleteLine { at } | Mutation::DuplicateLine { at, .. } => {
            let mut lines: Vec<Vec<u8>> =
                bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
            let i = index(at, lines.len());
            if let Mutation::DuplicateLine { times, .. } = m {
                let line = lines[i].clone();
                lines.splice(i..i, std::iter::repeat_n(line, *times));
            } else {
                lines.remove(i);
            }
            *bytes = lines.join(&b'\n');
        }
        Mutation::ExtremeNumber { at, value } => {
            let spans = numbers(bytes);
            if spans.is_empty() {
                return;
            }
            let (b, e) = spans[index(at, spans.len())];
            bytes.splice(b..e, EXTREMES[value].bytes());
        }
    }
}

/// What became of one mutated file.
#[derive(Debug)]
enum Outcome {
    /// Loaded, and the short trial ran.
    Accepted,
    /// Loaded, but the short trial failed with this message.
    RunFailed(String),
    /// Rejected by loading: the message and whether it has a line and column.
    Rejected { message: String, positioned: bool },
}

/// Loads `bytes` as a scenario file and, when accepted, checks which goals its robots cannot
/// reach and runs five steps with `rne`.
fn check_and_run(bytes: &[u8], dir: &std::path::Path, case: usize) -> Outcome {
    let path = dir.join(format!("case{case}.ron"));
    std::fs::write(&path, bytes).expect("writing the case file");
    let loaded = scenario::load(&path);
    let _ = std::fs::remove_file(&path);
    let s = match loaded {
        Ok(s) => s,
        Err(e) => {
            return Outcome::Rejected {
                message: e.to_string(),
                positioned: e.line_col().is_some(),
            };
        }
    };
    // The warnings of `usar check` (reachability plans from every start, tasks without rescue)
    // must not panic or hang on any accepted file either.
    std::hint::black_box((unreachable_goals(&s), tasks_without_rescue(&s)));
    let run = Simulation::builder(&s)
        .method_named("rne")
        .duration_s(5.0 * s.sim().dt_s.get())
        .build()
        .and_then(|mut sim| sim.run_to_end());
    match run {
        Ok(_) => Outcome::Accepted,
        Err(e) => Outcome::RunFailed(e.to_string()),
    }
}

/// Tallies of a fuzz run.
#[derive(Debug, Default)]
struct Tally {
    cases: Cell<usize>,
    accepted: Cell<usize>,
    rejected_positioned: Cell<usize>,
    rejected_unpositioned: Cell<usize>,
    multi_line: Cell<usize>,
    long_numbers: Cell<usize>,
    run_failed: Cell<usize>,
    panics: Cell<usize>,
    hangs: Cell<usize>,
    examples: RefCell<Vec<String>>,
}

impl Tally {
    fn bump(c: &Cell<usize>) {
        c.set(c.get() + 1);
    }

    fn example(&self, what: &str, file: usize, muts: &[Mutation], detail: &str) {
        let mut ex = self.examples.borrow_mut();
        if ex.len() < 20 {
            ex.push(format!("{what}: file {file}, {muts:?}: {detail}"));
        }
    }
}

fn shipped() -> Vec<Vec<u8>> {
    [
        "paper.ron",
        "paper-v0.ron",
        "paper-v1.ron",
        "corridor.ron",
        "debris-crossing.ron",
        "three-tasks.ron",
    ]
    .iter()
    .map(|f| std::fs::read(integration_tests::scenario_path(f)).expect("shipped scenario"))
    .collect()
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_scenarios_never_panic_hang_or_give_multi_line_errors() {
    let files = shipped();
    let cases = env_number("USAR_FUZZ_CASES", 300) as u32;
    let seed = env_number("USAR_FUZZ_SEED", 0);
    let dir = tempfile::tempdir().expect("temp dir");
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new_with_rng(config, rng);
    let tally = Tally::default();
    let strategy = (0..files.len(), prop::collection::vec(mutation(), 1..=3));
    let result = runner.run(&strategy, |(file, muts)| {
        if tally.hangs.get() > 0 {
            return Ok(()); // a stuck worker thread is still running: stop testing
        }
        let n = tally.cases.get();
        Tally::bump(&tally.cases);
        let mut bytes = files[file].clone();
        for m in &muts {
            apply(&mut bytes, m);
        }
        let (tx, rx) = mpsc::channel();
        let dir_path = dir.path().to_owned();
        std::thread::spawn(move || {
            let outcome = catch_unwind(AssertUnwindSafe(|| check_and_run(&bytes, &dir_path, n)));
            let _ = tx.send(outcome);
        });
        match rx.recv_timeout(CASE_BOUND) {
            Err(_) => {
                Tally::bump(&tally.hangs);
                tally.example("hang", file, &muts, "no outcome within the bound");
            }
            Ok(Err(panic)) => {
                Tally::bump(&tally.panics);
                let msg = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                    .unwrap_or_default();
                tally.example("panic", file, &muts, &msg);
            }
            Ok(Ok(Outcome::Accepted)) => Tally::bump(&tally.accepted),
            Ok(Ok(Outcome::RunFailed(msg))) => {
                Tally::bump(&tally.run_failed);
                tally.example("run failed", file, &muts, &msg);
            }
            Ok(Ok(Outcome::Rejected {
                message,
                positioned,
            })) => {
                if message.contains('\n') {
                    Tally::bump(&tally.multi_line);
                    tally.example("multi-line error", file, &muts, &message);
                }
                if longest_digit_run(&message) > MAX_DIGITS_IN_A_MESSAGE {
                    Tally::bump(&tally.long_numbers);
                    tally.example("long number", file, &muts, &message);
                }
                if positioned {
                    Tally::bump(&tally.rejected_positioned);
                } else {
                    Tally::bump(&tally.rejected_unpositioned);
                    tally.example("rejected without position", file, &muts, &message);
                }
            }
        }
        Ok(())
    });
    println!(
        "fuzz: {} cases, {} accepted (short run ok), {} rejected with position, {} rejected \
         without position, {} multi-line errors, {} with a number of more than \
         {MAX_DIGITS_IN_A_MESSAGE} digits, {} accepted but the run failed, {} panics, {} hangs",
        tally.cases.get(),
        tally.accepted.get(),
        tally.rejected_positioned.get(),
        tally.rejected_unpositioned.get(),
        tally.multi_line.get(),
        tally.long_numbers.get(),
        tally.run_failed.get(),
        tally.panics.get(),
        tally.hangs.get()
    );
    for e in tally.examples.borrow().iter() {
        println!("  {}", e.chars().take(400).collect::<String>());
    }
    assert!(result.is_ok(), "{result:?}");
    assert_eq!(tally.panics.get(), 0, "panics (examples above)");
    assert_eq!(tally.hangs.get(), 0, "hangs (examples above)");
    assert_eq!(
        tally.multi_line.get(),
        0,
        "multi-line errors (examples above)"
    );
    assert_eq!(
        tally.rejected_unpositioned.get(),
        0,
        "rejections without position"
    );
    assert_eq!(
        tally.long_numbers.get(),
        0,
        "errors writing a long number in full (examples above)"
    );
    assert_eq!(tally.run_failed.get(), 0, "accepted files whose run failed");
    assert!(tally.accepted.get() > 0, "no mutated file was accepted");
}

#[test]
fn mutations_do_what_they_say() {
    let mut b = b"a: 1.5,\nb: -2e3,\nc: x1\n".to_vec();
    assert_eq!(numbers(&b), vec![(3, 6), (11, 15)]);
    apply(&mut b, &Mutation::ExtremeNumber { at: 0.9, value: 2 });
    assert_eq!(b, b"a: 1.5,\nb: 1e308,\nc: x1\n");
    apply(&mut b, &Mutation::DuplicateLine { at: 0.0, times: 2 });
    assert_eq!(b, b"a: 1.5,\na: 1.5,\na: 1.5,\nb: 1e308,\nc: x1\n");
    apply(&mut b, &Mutation::DeleteLine { at: 0.0 });
    apply(&mut b, &Mutation::Truncate { at: 0.5 });
    assert_eq!(b.len(), 16);
}
