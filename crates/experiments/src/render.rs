//! Top-down SVG picture of a scenario, optionally with the paths robots took (`usar render`).

use std::path::Path;

use anyhow::Result;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use usar_sim::scenario::{Circle as Disc, Debris, Locomotion, PointM, Rect, Role, Scenario};

use crate::atomic::write_atomic;

/// Length of the longer side of the drawn field (arena plus walls and a margin), pixels; the
/// scale is clamped to [`MIN_PX_PER_M`, `MAX_PX_PER_M`].
const MAP_TARGET_PX: f64 = 960.0;
/// Smallest scale, pixels per metre.
const MIN_PX_PER_M: f64 = 4.0;
/// Largest scale, pixels per metre (a narrow corridor is drawn large, not huge).
const MAX_PX_PER_M: f64 = 40.0;
/// Vertices used to draw a circle as a polygon in world coordinates.
const CIRCLE_VERTICES: usize = 40;
/// Width of the legend column, pixels.
const LEGEND_PX: u32 = 200;
/// Height of one legend entry, pixels.
const LEGEND_ROW_PX: i32 = 20;
/// Approximate width of one character of the 12 px description font, pixels (for wrapping).
const DESCRIPTION_CHAR_PX: f64 = 6.6;

const WALL: RGBColor = RGBColor(60, 60, 60);
const DEBRIS: RGBColor = RGBColor(140, 100, 60);
const RESCUEE: RGBColor = RGBColor(90, 90, 90);
const EASY: RGBColor = RGBColor(198, 219, 239);
const HARD: RGBColor = RGBColor(253, 208, 162);
const REST: RGBColor = RGBColor(180, 140, 220);
/// Radiation colour of the weakest zone; the strongest is [`RADIATION_HIGH`].
const RADIATION_LOW: RGBColor = RGBColor(245, 215, 60);
const RADIATION_HIGH: RGBColor = RGBColor(225, 95, 0);
/// Opacity of radiation zones (search areas and rescuees stay visible below them).
const RADIATION_ALPHA: f64 = 0.5;

/// The path one robot took: its positions in the world frame, metres, in time order.
pub type Trace = Vec<PointM>;

/// Colour of a robot by role: carriers blue, suppliers green, observers red.
pub fn role_color(role: Role) -> RGBColor {
    match role {
        Role::Carrier => RGBColor(31, 119, 180),
        Role::Supplier => RGBColor(44, 160, 44),
        Role::Observer => RGBColor(214, 39, 40),
    }
}

/// Colour of kind `k` of `s`: its role's colour ([`role_color`]); a second or later kind of
/// the same role is drawn darker, so kinds stay apart.
pub fn kind_color(s: &Scenario, k: usize) -> RGBColor {
    let role = s.kinds[k].role;
    let same_role_before = s.kinds[..k].iter().filter(|o| o.role == role).count();
    let c = role_color(role);
    let f = 0.6_f64.powi(same_role_before.min(3) as i32);
    let dim = |v: u8| (f64::from(v) * f).round() as u8;
    RGBColor(dim(c.0), dim(c.1), dim(c.2))
}

/// Draws `scenario` top-down as SVG and writes it to `out` with [`write_atomic`] (atomically
/// for a regular file, through a symlink, directly to a FIFO or character device).
///
/// Shows the walls, debris (brown), radiation zones (shaded by dose rate factor: the weakest
/// yellow, the strongest orange, labelled `x<factor>` when the factors differ), both search
/// areas with their rescuees, goal points (crosses), drop-offs, the rest station, robots at
/// their start positions by kind (colour by role, see [`kind_color`]; aerial robots with a
/// ring; labelled by id in teams of up to [`MAX_LABELLED_ROBOTS`]), a legend and a scale bar,
/// and, when `traces` is given (indexed by robot id), the path each robot took with a hollow
/// disc where it ended.
///
/// # Errors
/// If drawing or writing the file fails.
pub fn render_svg(scenario: &Scenario, traces: Option<&[Trace]>, out: &Path) -> Result<()> {
    let svg = render_svg_string(scenario, traces)?;
    write_atomic(out, svg.as_bytes())
}

/// The drawing's geometry: field extent in metres and the scale.
struct Layout {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    px_per_m: f64,
    map_w: u32,
    map_h: u32,
}

impl Layout {
    fn new(s: &Scenario) -> Self {
        let (w, h) = (s.arena.width(), s.arena.height());
        let pad = drawn_wall_m(s) + 1.0;
        let (x0, x1) = (-pad, w + pad);
        let (y0, y1) = (-pad, h + pad);
        let px_per_m = (MAP_TARGET_PX / (x1 - x0).max(y1 - y0)).clamp(MIN_PX_PER_M, MAX_PX_PER_M);
        Self {
            x0,
            x1,
            y0,
            y1,
            px_per_m,
            map_w: ((x1 - x0) * px_per_m).round() as u32,
            map_h: ((y1 - y0) * px_per_m).round() as u32,
        }
    }
}

/// Splits `text` into lines of at most `width` characters at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.len() + 1 + word.len() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Same as [`render_svg`] but returns the SVG text.
///
/// # Errors
/// If plotters fails to draw (it should not for a valid scenario).
pub fn render_svg_string(scenario: &Scenario, traces: Option<&[Trace]>) -> Result<String> {
    let l = Layout::new(scenario);
    let total_w = l.map_w + LEGEND_PX;
    let description = wrap(
        &scenario.description,
        ((f64::from(total_w) - 16.0) / DESCRIPTION_CHAR_PX) as usize,
    );
    let header_px = 30 + 16 * description.len() as u32;
    let legend = legend_entries(scenario, traces.is_some());
    let legend_h = 16 + LEGEND_ROW_PX as u32 * (legend.len() as u32 + 2);
    let total_h = header_px + l.map_h.max(legend_h);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (total_w, total_h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (header, body) = root.split_vertically(header_px);
        draw_header(&header, scenario, &description)?;
        let (map_column, legend_area) = body.split_horizontally(l.map_w);
        let (map_area, _) = map_column.split_vertically(l.map_h);
        let mut chart = ChartBuilder::on(&map_area)
            .build_cartesian_2d(l.x0..l.x1, l.y0..l.y1)
            .map_err(draw_err)?;
        draw_static(&mut chart, scenario, true)?;
        if let Some(traces) = traces {
            draw_paths(&mut chart, scenario, traces)?;
        }
        draw_robots(&mut chart, scenario)?;
        if let Some(traces) = traces {
            draw_ends(&mut chart, scenario, traces)?;
        }
        draw_legend(&legend_area, &legend, l.px_per_m)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// Where the map of [`render_map_svg`] lies: pixel `(0, 0)` is the field's top-left corner
/// `(x0_m, y1_m)` and one metre is `px_per_m` pixels on both axes (y grows upwards in the
/// world, downwards in the picture).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MapFrame {
    /// World x of the picture's left edge, metres (the wall's outer side minus a 1 m margin).
    pub x0_m: f64,
    /// World x of the right edge, metres.
    pub x1_m: f64,
    /// World y of the bottom edge, metres.
    pub y0_m: f64,
    /// World y of the top edge, metres.
    pub y1_m: f64,
    /// Scale, pixels per metre, in `[4, 40]` (the longer side about 960 px where that fits).
    pub px_per_m: f64,
    /// Picture width, pixels.
    pub width_px: u32,
    /// Picture height, pixels.
    pub height_px: u32,
}

/// The map alone, as `usar render` draws it (walls, search areas, drop-offs, radiation by dose,
/// debris, the rest station, goal points and labels) but without rescuees, robots, header or
/// legend, as SVG text, with the frame that maps world metres to its pixels. The replay page
/// draws rescuees and robots over it.
///
/// # Errors
/// If plotters fails to draw (it should not for a valid scenario).
pub fn render_map_svg(scenario: &Scenario) -> Result<(String, MapFrame)> {
    let l = Layout::new(scenario);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (l.map_w, l.map_h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&root)
            .build_cartesian_2d(l.x0..l.x1, l.y0..l.y1)
            .map_err(draw_err)?;
        draw_static(&mut chart, scenario, false)?;
        root.present().map_err(draw_err)?;
    }
    let frame = MapFrame {
        x0_m: l.x0,
        x1_m: l.x1,
        y0_m: l.y0,
        y1_m: l.y1,
        px_per_m: l.px_per_m,
        width_px: l.map_w,
        height_px: l.map_h,
    };
    Ok((svg, frame))
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

fn draw_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing the SVG failed: {e}")
}

fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().into()
}

fn draw_header(area: &Area<'_>, s: &Scenario, description: &[String]) -> Result<()> {
    let title = ("sans-serif", 16)
        .into_font()
        .style(FontStyle::Bold)
        .into_text_style(area);
    area.draw(&Text::new(
        format!(
            "{} ({} m x {} m, {} robots)",
            s.name,
            s.arena.width_m,
            s.arena.height_m,
            s.robots.len()
        ),
        (8, 6),
        title,
    ))
    .map_err(draw_err)?;
    for (i, line) in description.iter().enumerate() {
        area.draw(&Text::new(line.clone(), (8, 28 + 16 * i as i32), font(12)))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// `CIRCLE_VERTICES` points on a disc's rim ([`Disc::outline`]).
fn disc_polygon(c: &Disc) -> Vec<(f64, f64)> {
    xy(c.outline(CIRCLE_VERTICES))
}

fn xy(points: Vec<PointM>) -> Vec<(f64, f64)> {
    points.into_iter().map(|p| (p.x, p.y)).collect()
}

/// The closed outline of a disc (first vertex repeated at the end).
fn disc_outline(c: &Disc) -> Vec<(f64, f64)> {
    let mut pts = disc_polygon(c);
    pts.push(pts[0]);
    pts
}

/// A debris item's outline from its parry shape ([`Debris::shape`]): a rectangle's corners, or
/// `CIRCLE_VERTICES` points of a disc.
fn debris_polygon(d: &Debris) -> Vec<(f64, f64)> {
    xy(d.shape().outline(CIRCLE_VERTICES))
}

/// Pastel colours of tasks between the hardest ([`HARD`]) and the easiest ([`EASY`]).
const MIDDLE_TASKS: [RGBColor; 4] = [
    RGBColor(199, 233, 192),
    RGBColor(218, 218, 235),
    RGBColor(252, 197, 192),
    RGBColor(255, 247, 188),
];

/// Colour of task `t` of `s` by its difficulty: the hardest orange, the easiest blue, the ones
/// between in other pastel colours (a single task is orange). Search areas and drop-offs are
/// filled with it.
pub fn task_color(s: &Scenario, t: usize) -> RGBColor {
    by_difficulty(s, t, (HARD, EASY, &MIDDLE_TASKS))
}

/// Saturated colours of the tasks between the hardest and the easiest, in the order of
/// [`MIDDLE_TASKS`].
const MIDDLE_TASKS_STRONG: [RGBColor; 4] = [
    RGBColor(49, 163, 84),
    RGBColor(117, 107, 177),
    RGBColor(203, 24, 29),
    RGBColor(191, 150, 0),
];

/// A saturated colour of task `t` of `s`, of the same hue as its area colour
/// ([`task_color`]): the hardest dark orange, the easiest dark blue. Drawn on the task's own
/// pastel area it stays visible (the replay fills robots with their group's colour).
pub fn task_strong_color(s: &Scenario, t: usize) -> RGBColor {
    let (hard, easy) = (RGBColor(230, 85, 13), RGBColor(49, 130, 189));
    by_difficulty(s, t, (hard, easy, &MIDDLE_TASKS_STRONG))
}

/// The colour of task `t` of `s` from a palette of (hardest, easiest, the ones between).
fn by_difficulty(
    s: &Scenario,
    t: usize,
    (hardest, easiest, middle): (RGBColor, RGBColor, &[RGBColor; 4]),
) -> RGBColor {
    let order = s.hardest_first();
    let rank = order.iter().position(|&x| x == t).unwrap_or(0);
    if rank == 0 {
        hardest
    } else if rank + 1 == order.len() {
        easiest
    } else {
        middle[(rank - 1) % middle.len()]
    }
}

/// Colour of the rescuees' dots.
pub const RESCUEE_COLOR: RGBColor = RESCUEE;

/// Colour of a radiation zone of dose rate factor `f` among factors in `[lo, hi]`.
fn radiation_color(f: f64, lo: f64, hi: f64) -> RGBColor {
    let t = if hi > lo { (f - lo) / (hi - lo) } else { 0.0 };
    let mix = |a: u8, b: u8| (f64::from(a) + t * (f64::from(b) - f64::from(a))).round() as u8;
    RGBColor(
        mix(RADIATION_LOW.0, RADIATION_HIGH.0),
        mix(RADIATION_LOW.1, RADIATION_HIGH.1),
        mix(RADIATION_LOW.2, RADIATION_HIGH.2),
    )
}

/// The distinct dose rate factors of the scenario's zones, ascending.
fn dose_levels(s: &Scenario) -> Vec<f64> {
    let mut v: Vec<f64> = s
        .radiation_zones
        .iter()
        .map(|z| z.dose_rate_factor)
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// A label centred on `(x, y)` horizontally, hanging below it (`VPos::Top`) or sitting on it.
fn label_at(text: String, x: f64, y: f64, size: u32, v: VPos) -> Text<'static, (f64, f64), String> {
    Text::new(text, (x, y), font(size).pos(Pos::new(HPos::Center, v)))
}

/// The walls' drawn thickness, metres: `arena.wall_thickness_m`, but at most a tenth of the
/// arena's longer side, so that thick walls (up to 10 km) do not shrink the arena in the
/// picture to a dot.
fn drawn_wall_m(s: &Scenario) -> f64 {
    let longer_side_m = s.arena.width().max(s.arena.height());
    s.arena.wall_thickness_m.get().min(0.1 * longer_side_m)
}

/// Draws everything that does not move: walls, search areas (with their rescuees when
/// `rescuees`), drop-offs, radiation zones, debris, the rest station, goal points and labels.
fn draw_static(chart: &mut Chart<'_, '_>, s: &Scenario, rescuees: bool) -> Result<()> {
    let (w, h) = (s.arena.width(), s.arena.height());
    let t = drawn_wall_m(s);
    let walls = [
        [(-t, -t), (w + t, 0.0)],
        [(-t, h), (w + t, h + t)],
        [(-t, 0.0), (0.0, h)],
        [(w, 0.0), (w + t, h)],
    ];
    chart
        .draw_series(walls.iter().map(|r| Rectangle::new(*r, WALL.filled())))
        .map_err(draw_err)?;

    // Search areas and rescuees first: radiation, debris and labels go on top.
    for (t, task) in s.tasks.iter().enumerate() {
        let r = task.search_area;
        chart
            .draw_series([Rectangle::new(
                [(r.min.x, r.min.y), (r.max.x, r.max.y)],
                task_color(s, t).filled(),
            )])
            .map_err(draw_err)?;
        if rescuees {
            chart
                .draw_series(
                    task.rescuees
                        .iter()
                        .map(|p| Circle::new((p.x, p.y), 1, RESCUEE.filled())),
                )
                .map_err(draw_err)?;
        }
        chart
            .draw_series([Polygon::new(
                disc_polygon(&task.drop_off),
                task_color(s, t).filled(),
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(
                disc_outline(&task.drop_off),
                task_color(s, t).mix(1.0).stroke_width(1),
            )])
            .map_err(draw_err)?;
    }

    let doses = dose_levels(s);
    let (lo, hi) = (
        doses.first().copied().unwrap_or(1.0),
        doses.last().copied().unwrap_or(1.0),
    );
    for z in &s.radiation_zones {
        let c = radiation_color(z.dose_rate_factor, lo, hi);
        chart
            .draw_series([Polygon::new(
                disc_polygon(&z.area),
                c.mix(RADIATION_ALPHA).filled(),
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(disc_outline(&z.area), c.stroke_width(1))])
            .map_err(draw_err)?;
    }
    chart
        .draw_series(
            s.debris
                .iter()
                .map(|d| Polygon::new(debris_polygon(d), DEBRIS.filled())),
        )
        .map_err(draw_err)?;
    if doses.len() > 1 {
        chart
            .draw_series(s.radiation_zones.iter().map(|z| {
                label_at(
                    format!("x{}", z.dose_rate_factor),
                    z.area.center.x,
                    z.area.center.y,
                    10,
                    VPos::Center,
                )
            }))
            .map_err(draw_err)?;
    }
    chart
        .draw_series(
            s.rest_stations
                .iter()
                .map(|rs| Polygon::new(disc_polygon(rs), REST.mix(0.6).filled())),
        )
        .map_err(draw_err)?;

    // Labels last so nothing covers them.
    for task in &s.tasks {
        let r = task.search_area;
        let text = format!(
            "{} search area ({} rescuees)",
            task.name,
            task.rescuees.len()
        );
        draw_area_label(chart, s, &r, text)?;
        let d = task.drop_off;
        chart
            .draw_series([label_at(
                format!("{} drop-off", task.name),
                d.center.x,
                d.center.y - d.radius_m,
                11,
                VPos::Top,
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([Cross::new(
                (task.goal.x, task.goal.y),
                6,
                BLACK.stroke_width(2),
            )])
            .map_err(draw_err)?;
    }
    chart
        .draw_series(s.rest_stations.iter().map(|rs| {
            label_at(
                "rest station".into(),
                rs.center.x,
                rs.center.y - rs.radius_m,
                11,
                VPos::Top,
            )
        }))
        .map_err(draw_err)?;
    Ok(())
}

/// Labels a search area above its top-left corner; where the wall leaves no room, below it,
/// else inside its top edge on a white band. Right-aligned when it would run past the arena.
fn draw_area_label(chart: &mut Chart<'_, '_>, s: &Scenario, r: &Rect, text: String) -> Result<()> {
    let px_per_m = Layout::new(s).px_per_m;
    let w_m = text.len() as f64 * DESCRIPTION_CHAR_PX / px_per_m;
    let h_m = 10.0 / px_per_m;
    let (y, v, inside) = if r.max.y + h_m <= s.arena.height() {
        (r.max.y, VPos::Bottom, false)
    } else if r.min.y - h_m >= 0.0 {
        (r.min.y, VPos::Top, false)
    } else {
        (r.max.y, VPos::Top, true)
    };
    let (x, h) = if r.min.x + w_m > s.arena.width() {
        (r.max.x, HPos::Right)
    } else {
        (r.min.x, HPos::Left)
    };
    if inside {
        let (bx0, bx1) = match h {
            HPos::Right => (r.max.x - w_m, r.max.x),
            _ => (r.min.x, r.min.x + w_m),
        };
        chart
            .draw_series([Rectangle::new(
                [(bx0, r.max.y - h_m), (bx1, r.max.y)],
                WHITE.mix(0.8).filled(),
            )])
            .map_err(draw_err)?;
    }
    chart
        .draw_series([Text::new(text, (x, y), font(12).pos(Pos::new(h, v)))])
        .map_err(draw_err)?;
    Ok(())
}

fn draw_paths(chart: &mut Chart<'_, '_>, s: &Scenario, traces: &[Trace]) -> Result<()> {
    for (id, trace) in traces.iter().enumerate().take(s.robots.len()) {
        let color = kind_color(s, s.robots[id].kind);
        chart
            .draw_series([PathElement::new(
                trace.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>(),
                color.mix(0.6).stroke_width(1),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Where each traced robot ended: hollow discs of the body's size, on top of everything.
fn draw_ends(chart: &mut Chart<'_, '_>, s: &Scenario, traces: &[Trace]) -> Result<()> {
    for (id, trace) in traces.iter().enumerate().take(s.robots.len()) {
        let kind = s.kind_of(id);
        let Some(end) = trace.last() else { continue };
        let body = Disc {
            center: *end,
            radius_m: kind.body_radius_m,
        };
        chart
            .draw_series([Polygon::new(disc_polygon(&body), WHITE.filled())])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(
                disc_outline(&body),
                kind_color(s, s.robots[id].kind).stroke_width(2),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

fn draw_robots(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    for (id, robot) in s.robots.iter().enumerate() {
        let kind = &s.kinds[robot.kind];
        let body = Disc {
            center: robot.start_in_world,
            radius_m: kind.body_radius_m,
        };
        let color = kind_color(s, robot.kind);
        chart
            .draw_series([Polygon::new(disc_polygon(&body), color.filled())])
            .map_err(draw_err)?;
        let mut reach = kind.body_radius_m;
        if kind.locomotion == Locomotion::Aerial {
            reach *= 1.8;
            let ring = Disc {
                radius_m: reach,
                ..body
            };
            chart
                .draw_series([PathElement::new(disc_outline(&ring), color.stroke_width(1))])
                .map_err(draw_err)?;
        }
        if s.robots.len() <= MAX_LABELLED_ROBOTS {
            chart
                .draw_series([label_at(
                    id.to_string(),
                    body.center.x,
                    body.center.y - reach,
                    9,
                    VPos::Top,
                )])
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

/// Teams of more robots than this are drawn without id labels (they would cover each other).
pub const MAX_LABELLED_ROBOTS: usize = 100;

/// What a legend entry shows left of its text.
enum Swatch {
    /// A filled square.
    Square(RGBColor),
    /// A filled square with an outline of the second colour.
    Outlined(RGBColor, RGBColor),
    /// A robot: a disc, ringed for aerial robots.
    Robot(RGBColor, bool),
    /// A hollow disc (where a traced robot ended).
    Hollow(RGBColor),
    /// A small dot (a rescuee).
    Dot(RGBColor),
    /// A cross (a goal point).
    Cross,
    /// A line (a path).
    Line(RGBColor),
}

fn legend_entries(s: &Scenario, traced: bool) -> Vec<(Swatch, String)> {
    let mut v: Vec<(Swatch, String)> = s
        .kinds
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let aerial = k.locomotion == Locomotion::Aerial;
            let how = if aerial { "aerial" } else { "ground" };
            (
                Swatch::Robot(kind_color(s, i), aerial),
                format!("{} x{} ({how})", k.name, k.count),
            )
        })
        .collect();
    if traced {
        v.push((
            Swatch::Line(RGBColor(120, 120, 120)),
            "path (colour by kind)".into(),
        ));
        v.push((
            Swatch::Hollow(RGBColor(120, 120, 120)),
            "where it ended".into(),
        ));
    }
    if !s.debris.is_empty() {
        v.push((Swatch::Square(DEBRIS), "debris".into()));
    }
    let doses = dose_levels(s);
    let (lo, hi) = (
        doses.first().copied().unwrap_or(1.0),
        doses.last().copied().unwrap_or(1.0),
    );
    for f in &doses {
        let c = radiation_color(*f, lo, hi);
        v.push((
            Swatch::Outlined(over_white(c, RADIATION_ALPHA), c),
            format!("radiation, dose x{f}"),
        ));
    }
    for (t, task) in s.tasks.iter().enumerate() {
        v.push((
            Swatch::Square(task_color(s, t)),
            format!("{} task: area, drop-off", task.name),
        ));
    }
    v.push((Swatch::Dot(RESCUEE), "rescuee".into()));
    v.push((Swatch::Cross, "task goal point".into()));
    v.push((Swatch::Square(REST), "rest station".into()));
    v
}

/// What `c` at opacity `alpha` looks like on white paper.
fn over_white(c: RGBColor, alpha: f64) -> RGBColor {
    let blend = |v: u8| (f64::from(v) * alpha + 255.0 * (1.0 - alpha)).round() as u8;
    RGBColor(blend(c.0), blend(c.1), blend(c.2))
}

fn draw_legend(area: &Area<'_>, entries: &[(Swatch, String)], px_per_m: f64) -> Result<()> {
    let mut y = 16;
    for (swatch, label) in entries {
        let (cx, cy) = (14, y);
        match swatch {
            Swatch::Square(c) => area
                .draw(&Rectangle::new([(8, cy - 6), (20, cy + 6)], c.filled()))
                .map_err(draw_err)?,
            Swatch::Outlined(fill, line) => {
                area.draw(&Rectangle::new([(8, cy - 6), (20, cy + 6)], fill.filled()))
                    .map_err(draw_err)?;
                area.draw(&Rectangle::new(
                    [(8, cy - 6), (20, cy + 6)],
                    line.stroke_width(1),
                ))
                .map_err(draw_err)?;
            }
            Swatch::Robot(c, ring) => {
                area.draw(&Circle::new((cx, cy), 5, c.filled()))
                    .map_err(draw_err)?;
                if *ring {
                    area.draw(&Circle::new((cx, cy), 8, c.stroke_width(1)))
                        .map_err(draw_err)?;
                }
            }
            Swatch::Hollow(c) => area
                .draw(&Circle::new((cx, cy), 5, c.stroke_width(2)))
                .map_err(draw_err)?,
            Swatch::Dot(c) => area
                .draw(&Circle::new((cx, cy), 2, c.filled()))
                .map_err(draw_err)?,
            Swatch::Cross => area
                .draw(&Cross::new((cx, cy), 6, BLACK.stroke_width(2)))
                .map_err(draw_err)?,
            Swatch::Line(c) => area
                .draw(&PathElement::new(
                    vec![(6, cy + 4), (12, cy - 3), (16, cy + 2), (22, cy - 5)],
                    c.stroke_width(2),
                ))
                .map_err(draw_err)?,
        }
        area.draw(&Text::new(
            label.clone(),
            (28, cy),
            font(12).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(draw_err)?;
        y += LEGEND_ROW_PX;
    }
    // Scale bar: the longest round length that fits in the legend column.
    let len_m = [100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5]
        .into_iter()
        .find(|m| m * px_per_m <= f64::from(LEGEND_PX) - 40.0)
        .unwrap_or(0.5);
    let len_px = (len_m * px_per_m).round() as i32;
    let by = y + LEGEND_ROW_PX / 2;
    area.draw(&PathElement::new(
        vec![(8, by - 4), (8, by), (8 + len_px, by), (8 + len_px, by - 4)],
        BLACK.stroke_width(2),
    ))
    .map_err(draw_err)?;
    area.draw(&Text::new(
        format!("{len_m} m"),
        (8 + len_px / 2, by + 3),
        font(11).pos(Pos::new(HPos::Center, VPos::Top)),
    ))
    .map_err(draw_err)?;
    Ok(())
}
