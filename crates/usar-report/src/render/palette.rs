//! The map's palette: the colours of walls, debris, rescuees, the rest station, radiation by
//! dose, robots by role and kind, and tasks by difficulty. The replay page draws with the same
//! colours ([`crate::replay`]).

use plotters::prelude::RGBColor;
use usar_sim::scenario::{Role, Scenario};

pub(crate) const WALL: RGBColor = RGBColor(60, 60, 60);

pub(crate) const DEBRIS: RGBColor = RGBColor(140, 100, 60);

pub(crate) const RESCUEE: RGBColor = RGBColor(90, 90, 90);

pub(crate) const EASY: RGBColor = RGBColor(198, 219, 239);

pub(crate) const HARD: RGBColor = RGBColor(253, 208, 162);

pub(crate) const REST: RGBColor = RGBColor(180, 140, 220);

/// Radiation colour of the weakest zone; the strongest is [`RADIATION_HIGH`].
pub(crate) const RADIATION_LOW: RGBColor = RGBColor(245, 215, 60);

pub(crate) const RADIATION_HIGH: RGBColor = RGBColor(225, 95, 0);

/// Opacity of radiation zones (search areas and rescuees stay visible below them).
pub(crate) const RADIATION_ALPHA: f64 = 0.5;

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
    let role = s.kinds()[k].role;
    let same_role_before = s.kinds()[..k].iter().filter(|o| o.role == role).count();
    let c = role_color(role);
    let f = 0.6_f64.powi(same_role_before.min(3) as i32);
    let dim = |v: u8| (f64::from(v) * f).round() as u8;
    RGBColor(dim(c.0), dim(c.1), dim(c.2))
}

/// Pastel colours of tasks between the hardest ([`HARD`]) and the easiest ([`EASY`]).
pub(crate) const MIDDLE_TASKS: [RGBColor; 4] = [
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
pub(crate) const MIDDLE_TASKS_STRONG: [RGBColor; 4] = [
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
pub(crate) fn by_difficulty(
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
pub(crate) fn radiation_color(f: f64, lo: f64, hi: f64) -> RGBColor {
    let t = if hi > lo { (f - lo) / (hi - lo) } else { 0.0 };
    let mix = |a: u8, b: u8| (f64::from(a) + t * (f64::from(b) - f64::from(a))).round() as u8;
    RGBColor(
        mix(RADIATION_LOW.0, RADIATION_HIGH.0),
        mix(RADIATION_LOW.1, RADIATION_HIGH.1),
        mix(RADIATION_LOW.2, RADIATION_HIGH.2),
    )
}

/// The distinct dose rate factors of the scenario's zones, ascending.
pub(crate) fn dose_levels(s: &Scenario) -> Vec<f64> {
    let mut v: Vec<f64> = s
        .radiation_zones()
        .iter()
        .map(|z| z.dose_rate_factor)
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// What `c` at opacity `alpha` looks like on white paper.
pub(crate) fn over_white(c: RGBColor, alpha: f64) -> RGBColor {
    let blend = |v: u8| (f64::from(v) * alpha + 255.0 * (1.0 - alpha)).round() as u8;
    RGBColor(blend(c.0), blend(c.1), blend(c.2))
}
