//! Property test: every figure of a sweep and of a grid is drawn, within a time limit, from
//! random finite inputs, 1e308 and `f64::MAX` among them. A band reaching 1.7e308 once made
//! plotters' tick loop spin forever (issue 52); [`crate::chart::axis_range`] is what every axis
//! now comes from. (The studies' figures have the same test in `experiments`.)

use proptest::prelude::*;
use usar_sim::mission::TrialResult;

use crate::analysis::CellAnalysis;
use crate::figures::{FIGURES, figure_svg};
use crate::grid_outputs::grid_figures::{heat_maps, line_chart};
use crate::stats::Summary;
use crate::testing::{amount, config, number, trial, within};

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
