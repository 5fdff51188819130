//! Property test: every figure kind is drawn, within a time limit, from random finite inputs,
//! 1e308 and `f64::MAX` among them, bands open on one side included. A band reaching 1.7e308
//! once made plotters' tick loop spin forever (issue 52); [`crate::chart::axis_range`] is what
//! every axis now comes from.

use std::sync::mpsc;
use std::time::Duration;

use proptest::prelude::*;
use usar_sim::mission::TrialResult;

use crate::analysis::CellAnalysis;
use crate::calibrate::figure::losses_svg;
use crate::calibrate::targets_figure::targets_svg;
use crate::claims::paper_claims;
use crate::figures::{FIGURES, figure_svg};
use crate::grid_outputs::grid_figures::{heat_maps, line_chart};
use crate::multiverse::plan::tests::plan;
use crate::multiverse::record::tests::record;
use crate::multiverse::spec_curve::spec_curve_svg;
use crate::stats::Summary;
use crate::targets::metric_ref::MetricRef;
use crate::targets::statistic::tests::trial;
use crate::targets::{Band, Statistic, Target};

/// How long all the cases of one figure kind may take together (debug build).
const LIMIT: Duration = Duration::from_secs(25);
/// Cases per figure kind.
const CASES: u32 = 64;

/// Runs `f` on a thread of its own; fails if it takes longer than [`LIMIT`] (a hung figure
/// leaves its thread behind, and the test fails instead of hanging the suite).
fn within(kind: &str, f: impl FnOnce() + Send + 'static) {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
        let _ = tx.send(outcome);
    });
    match rx.recv_timeout(LIMIT) {
        Ok(Ok(())) => {}
        Ok(Err(panic)) => std::panic::resume_unwind(panic),
        Err(_) => panic!("{kind}: not drawn within {} s", LIMIT.as_secs()),
    }
}

/// A finite number, the extremes as likely as ordinary values.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        Just(0.0),
        Just(1e308),
        Just(-1e308),
        Just(f64::MAX),
        Just(f64::MIN),
        Just(1e-300),
        Just(1e16),
        (-1e308..1e308f64),
    ]
}

/// A non-negative finite number (counts, costs).
fn amount() -> impl Strategy<Value = f64> {
    number().prop_map(f64::abs)
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: CASES,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A band of any kind around `value`, with finite parameters (usable or not: a figure draws
/// whatever targets it is given).
fn band(value: f64) -> impl Strategy<Value = Band> {
    (number(), amount()).prop_flat_map(move |(a, w)| {
        prop_oneof![
            Just(Band::PlusMinus(w)),
            Just(Band::Between(a.min(value), a.max(value))),
            Just(Band::AtLeast(a.min(value))),
            Just(Band::AtMost(a.max(value))),
        ]
    })
}

fn target() -> impl Strategy<Value = Target> {
    number().prop_flat_map(|value| {
        band(value).prop_map(move |band| Target {
            name: "t".into(),
            statistic: Statistic::Mean(MetricRef("rounds".into())),
            value,
            band,
            report_only: false,
        })
    })
}

fn summary() -> impl Strategy<Value = Summary> {
    prop::collection::vec(number(), 0..4).prop_map(|xs| Summary::of(&xs))
}

fn trials() -> impl Strategy<Value = Vec<TrialResult>> {
    let one = (
        0u32..2000,
        0u32..2000,
        amount(),
        amount(),
        amount(),
        amount(),
        prop::bool::ANY,
    );
    prop::collection::vec(one, 1..6).prop_map(|rows| {
        rows.into_iter()
            .map(|(e, h, ee, eh, he, hh, a)| {
                trial(if a { "RNE" } else { "DIS" }, 3, (e, h), (ee, eh), (he, hh))
            })
            .collect()
    })
}

#[test]
fn targets_panels_are_drawn_from_any_finite_input() {
    within("targets.svg", || {
        let strategy = (
            prop::collection::vec(target(), 1..5),
            prop::collection::vec(number(), 0..6),
        );
        proptest!(config(), |((targets, values) in strategy)| {
            let rows: Vec<Vec<f64>> = targets.iter().map(|_| values.clone()).collect();
            let svg = targets_svg("t", &targets, &rows, Some(0)).unwrap();
            prop_assert!(svg.contains("</svg>"));
        });
    });
}

#[test]
fn sweep_figures_are_drawn_from_any_finite_input() {
    within("fig3", || {
        proptest!(config(), |(results in trials())| {
            let tasks = ["hard".to_string(), "easy".to_string()];
            let methods = ["RNE".to_string(), "DIS".to_string()];
            let a = CellAnalysis::of(&results, &methods, &tasks);
            for spec in &FIGURES {
                prop_assert!(figure_svg(spec, &a).unwrap().contains("</svg>"));
            }
        });
    });
}

#[test]
fn grid_figures_are_drawn_from_any_finite_input() {
    within("grid figures", || {
        let strategy = (
            prop::collection::vec(number(), 1..5),
            prop::collection::vec(summary(), 4..5),
        );
        proptest!(config(), |((xs, stats) in strategy)| {
            let values: Vec<String> = xs.iter().map(ToString::to_string).collect();
            let methods = ["A".to_string()];
            let per_method = vec![stats[..values.len().min(4)].to_vec()];
            let svg = line_chart("f", &values, &methods, &per_method, "m").unwrap();
            prop_assert!(svg.contains("</svg>"));
            let (a, b) = (vec!["1".to_string(), "2".to_string()], vec!["x".to_string(), "y".to_string()]);
            let fields = ["f".to_string(), "g".to_string()];
            let svg = heat_maps(&fields, &a, &b, &methods, std::slice::from_ref(&stats), "m").unwrap();
            prop_assert!(svg.contains("</svg>"));
        });
    });
}

#[test]
fn convergence_is_drawn_from_any_loss() {
    within("convergence.svg", || {
        let loss = prop_oneof![amount(), Just(f64::INFINITY)];
        proptest!(config(), |(losses in prop::collection::vec(loss, 0..8), best in 0usize..8)| {
            let svg = losses_svg("s", &losses, best).unwrap();
            prop_assert!(svg.contains("</svg>"));
        });
    });
}

#[test]
fn spec_curves_are_drawn_from_any_finite_effect() {
    within("spec_curve", || {
        let effect = (number(), number(), number());
        proptest!(config(), |(effects in prop::collection::vec(effect, 1..5))| {
            let records: Vec<_> = effects
                .iter()
                .enumerate()
                .map(|(i, &(e, lo, hi))| {
                    let mut r = record(i as u64, &[0, 0], 0.0);
                    if let Some(c) = r.comparison.as_mut() {
                        c.claims[0].effect = e;
                        c.claims[0].ci_low = lo;
                        c.claims[0].ci_high = hi;
                    }
                    r
                })
                .collect();
            let svg = spec_curve_svg(&plan(), &records, &paper_claims().claims()[0]).unwrap();
            prop_assert!(svg.contains("</svg>"));
        });
    });
}
