//! Property test: every figure of a study (a calibration's targets panels and convergence, a
//! multiverse's specification curves) is drawn, within a time limit, from random finite inputs,
//! 1e308 and `f64::MAX` among them, bands open on one side included. A band reaching 1.7e308
//! once made plotters' tick loop spin forever (issue 52); [`usar_report::chart::axis_range`] is
//! what every axis now comes from. (A sweep's own figures: the same test in `usar-report`.)

use proptest::prelude::*;
use usar_report::claims::paper_claims;
use usar_report::targets::metric_ref::MetricRef;
use usar_report::targets::{Band, Statistic, Target};
use usar_report::testing::{amount, config, number, within};

use crate::calibrate::figure::losses_svg;
use crate::calibrate::targets_figure::targets_svg;
use crate::multiverse::plan::tests::plan;
use crate::multiverse::record::tests::record;
use crate::multiverse::spec_curve::spec_curve_svg;

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
