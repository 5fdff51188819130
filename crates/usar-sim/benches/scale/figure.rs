//! The scaling bench's figure: steps per CPU second against team size, log-log, for the logic
//! and its bare-Rapier replay, at the scenario's control period and with the software every
//! step; the logic on one thread and on a pool, steps per wall-clock second; with lines at 10x
//! and 25x real time.

use plotters::prelude::*;

/// One team's rates for the figure, steps per CPU second.
pub struct Point {
    /// Robots.
    pub robots: usize,
    /// Physics step, seconds.
    pub dt_s: f64,
    /// Logic and bare replay at the scenario's control period (`None` without one).
    pub control: Option<(f64, f64)>,
    /// Logic and bare replay with the software every step (`None` if not measured).
    pub every_step: Option<(f64, f64)>,
    /// Logic at the scenario's control period on one thread and on the bench's pool, steps
    /// per wall-clock second (`None` if not measured).
    pub threads: Option<(f64, f64)>,
}

/// A curve: label, colour, dashed, and its value of a point.
type Series<'a> = (String, RGBColor, bool, &'a dyn Fn(&Point) -> Option<f64>);

/// Draws `points` as a log-log plot into the SVG file `path`; `threads` names the pool of
/// [`Point::threads`]. Errors: the file cannot be written.
pub fn draw(
    points: &[Point],
    threads: usize,
    path: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (760, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let all = |p: &Point| {
        [p.control, p.every_step, p.threads]
            .into_iter()
            .flatten()
            .flat_map(|(a, b)| [a, b])
            .collect::<Vec<_>>()
    };
    let values: Vec<f64> = points.iter().flat_map(all).collect();
    let x_max = points.iter().map(|p| p.robots).max().unwrap_or(1000) as f64 * 1.4;
    let dt = points.first().map_or(0.02, |p| p.dt_s);
    let y_max = values.iter().copied().fold(1.0, f64::max) * 2.0;
    let y_min = values.iter().copied().fold(10.0 / dt, f64::min) * 0.5;
    let mut chart = log_log_chart(
        &root,
        "World steps per second against team size",
        (8.0, x_max),
        (y_min, y_max),
        "world steps per CPU second (one core), per wall second (threads)",
    )?;
    let blue = RGBColor(31, 119, 180);
    let orange = RGBColor(255, 127, 14);
    let purple = RGBColor(148, 103, 189);
    let series: [Series; 6] = [
        ("all logic, 10 Hz control".into(), blue, false, &|p| {
            p.control.map(|c| c.0)
        }),
        ("bare Rapier replaying it".into(), blue, true, &|p| {
            p.control.map(|c| c.1)
        }),
        (
            "all logic, software every step".into(),
            orange,
            false,
            &|p| p.every_step.map(|c| c.0),
        ),
        ("bare Rapier replaying it".into(), orange, true, &|p| {
            p.every_step.map(|c| c.1)
        }),
        (
            "all logic, 1 thread, per wall second".into(),
            purple,
            true,
            &|p| p.threads.map(|t| t.0),
        ),
        (
            format!("all logic, {threads} threads, per wall second"),
            purple,
            false,
            &|p| p.threads.map(|t| t.1),
        ),
    ];
    for (label, colour, dashed, value) in series {
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter_map(|p| value(p).map(|v| (p.robots as f64, v)))
            .collect();
        curve(&mut chart, &pts, label, colour, dashed)?;
    }
    real_time_lines(&mut chart, dt, x_max)?;
    legend(&mut chart)?;
    root.present()?;
    Ok(())
}

/// A log-log chart over `root` titled `caption`, `x` (robots) and `y` its (low, high) ranges,
/// the y axis named `y_desc`, with its mesh drawn. Errors: as the drawing backend's.
pub fn log_log_chart<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    caption: &str,
    x: (f64, f64),
    y: (f64, f64),
    y_desc: &str,
) -> Result<Chart<'a, 'b>, Box<dyn std::error::Error>> {
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d((x.0..x.1).log_scale(), (y.0..y.1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("robots")
        .y_desc(y_desc)
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    Ok(chart)
}

/// Draws the legend of the curves drawn on `chart`, top right. Errors: as the drawing
/// backend's.
pub fn legend<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>) -> Result<(), Box<dyn std::error::Error>> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    Ok(())
}

/// The chart of [`draw`]: log-log, robots against steps per CPU second (or, in
/// `robot_step_figure.rs`, against nanoseconds per robot-step).
pub type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<
        plotters::coord::combinators::LogCoord<f64>,
        plotters::coord::combinators::LogCoord<f64>,
    >,
>;

/// Draws the curve through `pts` (solid, or dashed when `dashed`) with a dot at each point,
/// and its legend entry `label`. Errors: as the drawing backend's.
pub fn curve(
    chart: &mut Chart<'_, '_>,
    pts: &[(f64, f64)],
    label: String,
    colour: RGBColor,
    dashed: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let style = colour.stroke_width(2);
    if dashed {
        chart
            .draw_series(DashedLineSeries::new(pts.to_vec(), 6, 4, style))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(1))
            });
    } else {
        chart
            .draw_series(LineSeries::new(pts.to_vec(), style))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
    }
    chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
    Ok(())
}

/// Draws the 10x and 25x real-time lines (steps per second at step `dt` seconds) across the
/// chart, up to `x_max` robots. Errors: as the drawing backend's.
fn real_time_lines(
    chart: &mut Chart<'_, '_>,
    dt: f64,
    x_max: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    for (times, colour) in [(10.0, RGBColor(214, 39, 40)), (25.0, RGBColor(44, 160, 44))] {
        let target = times / dt;
        chart
            .draw_series(LineSeries::new(
                [(8.0, target), (x_max, target)],
                colour.stroke_width(1),
            ))?
            .label(format!("{times:.0}x real time"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(1))
            });
    }
    Ok(())
}
