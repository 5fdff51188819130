//! `multiverse.csv`: every universe in long ("tidy") form, for pandas, R and seaborn.
//!
//! Columns: `universe`, one per axis (named by the axis, holding the alternative's name),
//! `admissible`, `loss`, one per free field (named by its path, holding the calibrated
//! value), then `status, row, method, metric, n, mean, sd, claim, verdict, effect, ci_low,
//! ci_high, p, rival, message` ([`super::columns`]). Each universe has one row with `row =
//! universe` (its status and message), one `row = metric` per method x metric of its
//! comparison (`method, metric, n, mean, sd`, as `summary.csv`) and one `row = claim` per
//! claim of the multiverse's claims (`claim, verdict, effect, ci_low, ci_high, p, rival`)
//! and one `row = target` per calibration target (`metric` the target's name, `mean` its
//! statistic over the comparison's trials, `verdict` `in`, `OUT`, `in (reported)` or `OUT
//! (reported)` as [`usar_report::targets::Target::mark`]); every row repeats the universe's
//! columns up to `status`. Cells a row does not use are
//! empty; so are undefined numbers (NaN), while an infinite loss is `inf`. Universes come in
//! index order, methods in `--methods` order, metrics in `summary.csv` order. Numbers are
//! written in their shortest round-trip form: the file depends on the records alone.

use usar_report::error::{ReportError, Result};

use super::columns::{LEADING, MIDDLE, TRAILING};
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use usar_report::csv_tables::stat_cell;

/// A number for the file: shortest round-trip form, `inf`/`-inf`, empty for NaN.
fn num(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_string()
    } else {
        stat_cell(x)
    }
}

/// The header row.
pub fn header(plan: &MultiversePlan) -> Vec<String> {
    let id = &plan.identity;
    LEADING
        .iter()
        .map(|c| c.to_string())
        .chain(id.axes.axes.iter().map(|a| a.name.trim().to_string()))
        .chain(MIDDLE.iter().map(|c| c.to_string()))
        .chain(id.free.iter().map(|f| f.field.clone()))
        .chain(TRAILING.iter().map(|c| c.to_string()))
        .collect()
}

/// The cells every row of universe `r` starts with: up to and including `status`.
fn context(plan: &MultiversePlan, r: &UniverseRecord) -> Vec<String> {
    let id = &plan.identity;
    let mut row = vec![r.id.clone()];
    for (axis, &alt) in id.axes.axes.iter().zip(&r.choices) {
        row.push(
            axis.alternatives
                .get(alt)
                .map_or(String::new(), |a| a.name.clone()),
        );
    }
    row.push(r.admissible().to_string());
    let cal = r.calibration.as_ref();
    row.push(cal.map_or(String::new(), |c| num(c.loss)));
    for i in 0..id.free.len() {
        row.push(
            cal.and_then(|c| c.values.get(i))
                .map_or(String::new(), |&x| num(x)),
        );
    }
    row.push(r.status.word().to_string());
    row
}

/// `context` followed by the trailing cells after `status` named in `cells` (others empty).
fn row(context: &[String], cells: &[(&str, String)]) -> Vec<String> {
    let mut out = context.to_vec();
    for column in &TRAILING[1..] {
        out.push(
            cells
                .iter()
                .find(|(c, _)| c == column)
                .map_or(String::new(), |(_, v)| v.clone()),
        );
    }
    out
}

/// `multiverse.csv` of the records (in universe order).
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn multiverse_csv(plan: &MultiversePlan, records: &[UniverseRecord]) -> Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header(plan))?;
    for r in records {
        let ctx = context(plan, r);
        let message = r.message.clone().unwrap_or_default();
        w.write_record(row(
            &ctx,
            &[("row", "universe".into()), ("message", message)],
        ))?;
        let Some(cmp) = &r.comparison else {
            continue;
        };
        for m in &cmp.metrics {
            w.write_record(row(
                &ctx,
                &[
                    ("row", "metric".into()),
                    ("method", m.method.clone()),
                    ("metric", m.metric.clone()),
                    ("n", m.n.to_string()),
                    ("mean", num(m.mean)),
                    ("sd", num(m.sd)),
                ],
            ))?;
        }
        for (t, &x) in plan.identity.targets.iter().zip(&cmp.targets) {
            w.write_record(row(
                &ctx,
                &[
                    ("row", "target".into()),
                    ("metric", t.name.clone()),
                    ("mean", num(x)),
                    ("verdict", t.mark(x).into()),
                ],
            ))?;
        }
        for c in &cmp.claims {
            w.write_record(row(
                &ctx,
                &[
                    ("row", "claim".into()),
                    ("claim", c.claim.clone()),
                    ("verdict", c.verdict.clone()),
                    ("effect", num(c.effect)),
                    ("ci_low", num(c.ci_low)),
                    ("ci_high", num(c.ci_high)),
                    ("p", num(c.p)),
                    ("rival", c.rival.clone().unwrap_or_default()),
                ],
            ))?;
        }
    }
    w.into_inner()
        .map_err(ReportError::finish("finishing multiverse.csv"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::Status;
    use crate::multiverse::record::tests::record;

    #[test]
    fn rows_per_universe_metric_target_and_claim_with_the_universes_columns() {
        let p = plan();
        let mut invalid = record(4, &[1, 1], 0.0);
        invalid.status = Status::Invalid;
        invalid.message = Some("set mission.pickup_s=2: rule, with a comma".into());
        invalid.calibration = None;
        invalid.comparison = None;
        let text =
            String::from_utf8(multiverse_csv(&p, &[record(1, &[0, 1], 0.0), invalid]).unwrap())
                .unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "universe,a,b,admissible,loss,mission.energy_pct_per_m,\
             mission.hp_pct_per_step_in_radiation,status,row,method,metric,n,mean,sd,claim,\
             verdict,effect,ci_low,ci_high,p,rival,message"
        );
        assert_eq!(
            lines[1],
            "u001,a0,b1,true,0,1.25,0.003,ok,universe,,,,,,,,,,,,,"
        );
        assert_eq!(
            lines[2],
            "u001,a0,b1,true,0,1.25,0.003,ok,metric,RNE,rescued_total,2,150.5,,,,,,,,,"
        );
        // The target's statistic over the comparison, marked as the tables mark it.
        assert_eq!(
            lines[3],
            "u001,a0,b1,true,0,1.25,0.003,ok,target,,rounds,,148,,,OUT,,,,,,"
        );
        assert_eq!(
            lines[4],
            "u001,a0,b1,true,0,1.25,0.003,ok,claim,,,,,,1,holds,2.5,0.5,4.5,0.01,DIS,"
        );
        assert_eq!(
            lines[5],
            "u004,a1,b1,false,,,,invalid,universe,,,,,,,,,,,,,\"set mission.pickup_s=2: rule, with a comma\""
        );
        assert_eq!(lines.len(), 6);
        let columns = lines[0].split(',').count();
        let mut r = csv::Reader::from_reader(text.as_bytes());
        for rec in r.records() {
            assert_eq!(rec.unwrap().len(), columns);
        }
        // An infinite loss is written `inf`, which pandas reads as a float.
        let t =
            String::from_utf8(multiverse_csv(&p, &[record(0, &[0, 0], f64::INFINITY)]).unwrap())
                .unwrap();
        assert!(
            t.lines()
                .nth(1)
                .unwrap()
                .starts_with("u000,a0,b0,false,inf,"),
            "{t}"
        );
    }
}
