//! `tradeoff.svg`: what holds two targets apart. For the two fitted targets farthest outside
//! their bands at the best evaluation ([`tradeoff_pair`]), every evaluation is a dot at its
//! two distances outside the bands (in band units: half the band's width, or for a one-sided
//! band the value's distance to its bound; 0 inside), on `log10(1 + d)` axes. The evaluations
//! no other one beats on both (the Pareto front) are joined by a line and the best one is
//! ringed: a front that never reaches the corner (0, 0) shows the two cannot hold together
//! within the search's reach. With at most one fitted target out of band, the pair is the
//! best's largest two distances (some 0).

use plotters::prelude::*;
use usar_report::error::Result;

use super::loss::target_loss;
use super::outcome::CalibrationOutcome;
use usar_report::chart::{FIGURE_SIZE, axis_range, draw_err, plotted};
use usar_report::targets::file::Target;

/// A target's distance outside its band at statistic `x`, in band units (the root of its
/// share of the loss); +inf for an undefined statistic.
fn distance(t: &Target, x: f64) -> f64 {
    let fitted = Target {
        report_only: false,
        ..t.clone()
    };
    target_loss(&fitted, x).sqrt()
}

/// The indices of the two fitted targets farthest outside their bands at the best
/// evaluation (ties: file order), or `None` with fewer than two fitted targets.
pub fn tradeoff_pair(o: &CalibrationOutcome) -> Option<(usize, usize)> {
    let targets = &o.header.targets;
    let best = &o.best().statistics;
    let mut fitted: Vec<(usize, f64)> = targets
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.report_only)
        .map(|(i, t)| (i, distance(t, best.get(i).copied().unwrap_or(f64::NAN))))
        .collect();
    fitted.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    match fitted[..] {
        [(a, _), (b, _), ..] => Some((a.min(b), a.max(b))),
        _ => None,
    }
}

/// The evaluations on the Pareto front of `points` (both coordinates minimised; points with a
/// non-finite coordinate left out), sorted by the first coordinate.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut lowest = f64::INFINITY;
    for i in order {
        if points[i].1 < lowest {
            lowest = points[i].1;
            front.push(i);
        }
    }
    front
}

/// The SVG text of `tradeoff.svg`, or `None` with fewer than two fitted targets.
///
/// # Errors
/// If plotters fails to draw.
pub fn tradeoff_svg(o: &CalibrationOutcome) -> Result<Option<String>> {
    let Some((a, b)) = tradeoff_pair(o) else {
        return Ok(None);
    };
    let (ta, tb) = (&o.header.targets[a], &o.header.targets[b]);
    let axis = |d: f64| plotted(d.ln_1p() / std::f64::consts::LN_10);
    let points: Vec<(f64, f64)> = o
        .evaluations
        .iter()
        .map(|e| {
            let at = |i: usize| e.statistics.get(i).copied().unwrap_or(f64::NAN);
            (distance(ta, at(a)), distance(tb, at(b)))
        })
        .collect();
    let front = pareto_front(&points);
    let finite = || points.iter().filter(|p| p.0.is_finite() && p.1.is_finite());
    let (x0, x1) = axis_range(finite().map(|p| axis(p.0)).chain([0.0]), 0.06);
    let (y0, y1) = axis_range(finite().map(|p| axis(p.1)).chain([0.0]), 0.06);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, FIGURE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "Calibration of {}: {} against {} ({} evaluations)",
                    o.header.scenario,
                    ta.name,
                    tb.name,
                    o.evaluations.len()
                ),
                ("sans-serif", 17),
            )
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(draw_err)?;
        let tick = |v: &f64| format!("{:.2}", 10f64.powf(*v) - 1.0);
        chart
            .configure_mesh()
            .x_desc(format!(
                "{}: distance outside its band (band units)",
                ta.name
            ))
            .y_desc(format!("{}: distance outside (band units)", tb.name))
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 13))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(draw_err)?;
        let grey = RGBColor(150, 150, 150);
        chart
            .draw_series(
                finite().map(|p| Circle::new((axis(p.0), axis(p.1)), 3, grey.mix(0.6).filled())),
            )
            .map_err(draw_err)?;
        let blue = RGBColor(0, 114, 178);
        let line: Vec<(f64, f64)> = front
            .iter()
            .map(|&i| (axis(points[i].0), axis(points[i].1)))
            .collect();
        chart
            .draw_series(LineSeries::new(line.clone(), blue.stroke_width(2)))
            .map_err(draw_err)?
            .label("Pareto front (no evaluation is nearer on both)")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], blue));
        chart
            .draw_series(line.iter().map(|&p| Circle::new(p, 4, blue.filled())))
            .map_err(draw_err)?;
        let best = points[o.best];
        if best.0.is_finite() && best.1.is_finite() {
            let orange = RGBColor(213, 94, 0);
            chart
                .draw_series([Circle::new(
                    (axis(best.0), axis(best.1)),
                    8,
                    orange.stroke_width(2),
                )])
                .map_err(draw_err)?
                .label(format!("best evaluation (#{})", o.best))
                .legend(move |(x, y)| Circle::new((x + 9, y), 5, orange.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(200, 200, 200))
            .label_font(("sans-serif", 12))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(Some(svg))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_front_keeps_the_points_nothing_beats_on_both() {
        let points = [
            (1.0, 5.0),
            (2.0, 2.0),
            (3.0, 3.0), // beaten by (2, 2)
            (0.5, 9.0),
            (4.0, 1.0),
            (f64::INFINITY, 0.0), // left out
            (2.0, 2.0),           // a tie: the first is on the front
        ];
        assert_eq!(pareto_front(&points), vec![3, 0, 1, 4]);
        assert!(pareto_front(&[]).is_empty());
    }
}
