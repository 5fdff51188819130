//! The figure of `--robot-step`: nanoseconds per robot-step against team size, log-log, one
//! curve per physics mode and thread count (one thread by the process's CPU clock, dashed; the
//! pool by the wall clock, solid) and bare Rapier replaying `EveryStep`'s commands (one
//! thread, by its CPU clock, black dashed).

use plotters::prelude::*;

use crate::figure::{Chart, curve, legend, log_log_chart};
use crate::robot_step::{TeamCost, ns};

/// A mode's colour, by its place in [`crate::robot_step::MODES`].
const COLOURS: [RGBColor; 3] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
];

/// A curve: label, colour, dashed, points (robots, nanoseconds per robot-step).
type Curve = (String, RGBColor, bool, Vec<(f64, f64)>);

/// Draws `costs` into the SVG file `path`; `threads` names the pool. Errors: the file cannot
/// be written.
pub fn draw(
    costs: &[TeamCost],
    threads: usize,
    path: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut curves: Vec<Curve> = Vec::new();
    for (k, colour) in COLOURS.iter().enumerate() {
        let mut one = Vec::new();
        let mut many = Vec::new();
        let mut name = String::new();
        for c in costs {
            let Some((mode, t)) = c.modes.get(k) else {
                continue;
            };
            name = format!("{mode:?}");
            let Some(t) = t else { continue };
            let x = c.robots as f64;
            one.push((x, ns(t.one_cpu_s, t.steps, c.robots)));
            many.push((x, ns(t.many_wall_s, t.steps, c.robots)));
        }
        curves.push((format!("{name}, 1 thread (CPU)"), *colour, true, one));
        curves.push((
            format!("{name}, {threads} threads (wall)"),
            *colour,
            false,
            many,
        ));
    }
    let bare = costs
        .iter()
        .map(|c| {
            let b = &c.bare;
            (c.robots as f64, ns(b.bare_cpu_s, b.steps, c.robots))
        })
        .collect();
    curves.push(("bare Rapier, 1 thread (CPU)".into(), BLACK, true, bare));
    let ys = curves.iter().flat_map(|c| c.3.iter().map(|p| p.1));
    let y_max = ys.clone().fold(1.0, f64::max) * 3.0;
    let y_min = ys.fold(f64::INFINITY, f64::min).min(y_max) * 0.5;
    let x_min = costs.iter().map(|c| c.robots).min().unwrap_or(1000) as f64 / 1.6;
    let x_max = costs.iter().map(|c| c.robots).max().unwrap_or(1000) as f64 * 1.6;
    let root = SVGBackend::new(path, (760, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart: Chart<'_, '_> = log_log_chart(
        &root,
        "The cost per robot-step against team size",
        (x_min, x_max),
        (y_min, y_max),
        "nanoseconds per robot per step",
    )?;
    for (label, colour, dashed, pts) in curves {
        curve(&mut chart, &pts, label, colour, dashed)?;
    }
    legend(&mut chart)?;
    root.present()?;
    Ok(())
}
