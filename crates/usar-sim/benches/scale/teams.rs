//! The scaling bench's teams: which scenario a team of `n` robots is, and how a base
//! scenario is scaled to `n` (kind counts and quotas; beyond the base's team, the geometry).

use std::path::Path;

use usar_sim::scenario::{
    self, CircleSpec, DebrisSpec, Locomotion, PhysicsStepping, Positive, RectSpec,
    RescueeLayoutSpec, Scenario, ScenarioSpec, StartsSpec, XyM,
};

/// The scenario whose kind counts are scaled (`--base`): its `Grid` start layouts follow the
/// counts (a base with `List` starts too short for a team gets [`spread_starts`]).
pub const BASE: &str = "scenarios/swarm-1000.ron";

/// The 12-robot team.
pub const PAPER: &str = "scenarios/paper.ron";

/// `rel` (a path relative to the workspace root) as a path cargo's bench folder reaches.
pub fn path(rel: &str) -> String {
    if Path::new(rel).is_absolute() {
        return rel.to_owned();
    }
    format!("{}/../../{rel}", env!("CARGO_MANIFEST_DIR"))
}

/// A team to measure: its scenario and where it comes from (printed with the figures).
pub struct Team {
    /// The validated scenario.
    pub scenario: Scenario,
    /// Where it comes from, e.g. `scenarios/swarm-1000.ron, kinds scaled to 100`.
    pub source: String,
}

/// Scales `counts` to sum to `n` (largest remainders; ties to the earlier kind), each >= 1.
fn scale_counts(counts: &[usize], n: usize) -> Vec<usize> {
    let total: usize = counts.iter().sum::<usize>().max(1);
    let exact: Vec<f64> = counts
        .iter()
        .map(|&c| c as f64 * n as f64 / total as f64)
        .collect();
    let mut out: Vec<usize> = exact.iter().map(|&x| (x.floor() as usize).max(1)).collect();
    let mut order: Vec<usize> = (0..counts.len()).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())));
    let mut k = 0;
    while out.iter().sum::<usize>() < n && !order.is_empty() {
        out[order[k % order.len()]] += 1;
        k += 1;
    }
    while out.iter().sum::<usize>() > n {
        let big = (0..out.len()).max_by_key(|&i| out[i]).unwrap_or(0);
        out[big] -= 1;
    }
    out
}

/// Sets every kind's count to its share of `n` robots and its quotas to the same shares of the
/// new count; a kind's `List` of starts longer than its new count keeps its first positions.
fn scale_team(spec: &mut ScenarioSpec, n: usize) {
    let counts: Vec<usize> = spec.kinds.iter().map(|k| k.count).collect();
    for (kind, count) in spec.kinds.iter_mut().zip(scale_counts(&counts, n)) {
        let names: Vec<String> = kind.quota.0.keys().cloned().collect();
        let shares: Vec<usize> = kind.quota.0.values().copied().collect();
        for (name, q) in names.into_iter().zip(scale_counts(&shares, count)) {
            kind.quota.0.insert(name, q);
        }
        kind.count = count;
        if let StartsSpec::List(starts) = &mut kind.starts {
            starts.truncate(count);
        }
    }
}

/// Distance from `p` to a listed debris item's bounding circle, metres (negative inside).
fn debris_gap(d: &DebrisSpec, p: XyM) -> f64 {
    let (c, r) = match d {
        DebrisSpec::Circle {
            center_m, radius_m, ..
        } => (*center_m, radius_m.get()),
        DebrisSpec::Rect {
            center_m, size_m, ..
        } => (*center_m, 0.5 * size_m[0].hypot(size_m[1])),
    };
    (p[0] - c[0]).hypot(p[1] - c[1]) - r
}

/// Starts for a scaled `paper.ron`: ground robots on a 1 m lattice in the bottom band (y 1.5 to
/// 12.5 m, clear of listed debris), aerial robots on a 1 m lattice at y 22 to 25 m. Kinds take
/// their lattice points in order.
fn spread_starts(spec: &mut ScenarioSpec) {
    let width = spec.arena.width_m.get();
    let lattice = |y0: f64, y1: f64| {
        let mut pts = Vec::new();
        let mut y = y0;
        while y <= y1 {
            let mut x = 1.5;
            while x <= width - 1.5 {
                pts.push([x, y]);
                x += 1.0;
            }
            y += 1.0;
        }
        pts
    };
    let debris = spec.debris.clone();
    let clear = |p: &XyM| debris.iter().all(|d| debris_gap(d, *p) > 1.0);
    let mut ground = lattice(1.5, 12.5).into_iter().filter(clear);
    let mut aerial = lattice(22.0, 25.0).into_iter();
    for kind in &mut spec.kinds {
        let pts: &mut dyn Iterator<Item = XyM> = match kind.locomotion {
            Locomotion::Ground => &mut ground,
            Locomotion::Aerial => &mut aerial,
        };
        kind.starts = StartsSpec::List(pts.take(kind.count).collect());
    }
}

/// `p` times `f`.
fn times(p: XyM, f: f64) -> XyM {
    [p[0] * f, p[1] * f]
}

/// `x` times `f` (> 0), still positive.
fn longer(x: Positive, f: f64) -> Positive {
    Positive::new(x.get() * f).unwrap_or(x)
}

fn grow_circle(c: &mut CircleSpec, f: f64) {
    c.center_m = times(c.center_m, f);
    c.radius_m = longer(c.radius_m, f);
}

fn grow_rect(r: &mut RectSpec, f: f64) {
    r.min_m = times(r.min_m, f);
    r.max_m = times(r.max_m, f);
}

/// Columns of a `Grid` start layout of `count` robots in `columns` columns once the plan is
/// stretched by `f` (> 1) and the team grows about `f^2` times: `f` times the columns, rounded;
/// with `cap_rows`, enough more that the grid has at most `f` times its rows (rounded down),
/// so its last row stays a spacing clear of another kind's grid the base placed one spacing
/// below it (the rounded columns can leave it closer than two bodies).
fn grown_columns(count: usize, columns: u32, f: f64, cap_rows: bool) -> u32 {
    let rounded = (f64::from(columns) * f).round().max(1.0) as usize;
    if !cap_rows {
        return u32::try_from(rounded).unwrap_or(u32::MAX);
    }
    let rows = count.div_ceil(columns.max(1) as usize).max(1);
    let grown_rows = ((rows as f64 * f).floor() as usize).max(1);
    let grown_count = (count as f64 * f * f).ceil() as usize;
    let needed = grown_count.div_ceil(grown_rows);
    u32::try_from(needed.max(rounded)).unwrap_or(u32::MAX)
}

/// Stretches the scenario's plan by `f` (> 1) in both directions, so a team `f^2` times as
/// large has the base's room per robot: the arena, every position and every area (search
/// areas, drop-offs, rest stations, radiation zones, listed debris, debris-field regions) are
/// `f` times as long and debris fields hold `f^2` times as many shapes; a `Grid` start layout
/// starts at `f` times its first position with about `f` times as many columns
/// ([`grown_columns`], rows capped when `cap_rows`), its spacing kept.
/// Robot bodies, speeds, ranges, the rescuees' spacing and the generated shapes keep their
/// sizes, so search areas hold about `f^2` times as many rescuees.
fn grow(spec: &mut ScenarioSpec, f: f64, cap_rows: bool) {
    spec.arena.width_m = longer(spec.arena.width_m, f);
    spec.arena.height_m = longer(spec.arena.height_m, f);
    for kind in &mut spec.kinds {
        match &mut kind.starts {
            StartsSpec::Grid {
                first_m, columns, ..
            } => {
                *first_m = times(*first_m, f);
                *columns = grown_columns(kind.count, *columns, f, cap_rows);
            }
            StartsSpec::Row { first_m, .. } => *first_m = times(*first_m, f),
            StartsSpec::List(list) => list.iter_mut().for_each(|p| *p = times(*p, f)),
        }
    }
    let stations = match &mut spec.rest_station {
        scenario::RestStationsSpec::One(c) => std::slice::from_mut(c),
        scenario::RestStationsSpec::Many(list) => list.as_mut_slice(),
    };
    stations.iter_mut().for_each(|c| grow_circle(c, f));
    for task in &mut spec.tasks {
        grow_rect(&mut task.search_area, f);
        task.goal_m = times(task.goal_m, f);
        grow_circle(&mut task.drop_off, f);
        if let RescueeLayoutSpec::List(list) = &mut task.rescuees {
            list.iter_mut().for_each(|p| *p = times(*p, f));
        }
    }
    for d in &mut spec.debris {
        match d {
            DebrisSpec::Rect {
                center_m, size_m, ..
            } => {
                *center_m = times(*center_m, f);
                *size_m = times(*size_m, f);
            }
            DebrisSpec::Circle { center_m, radius_m } => {
                *center_m = times(*center_m, f);
                *radius_m = longer(*radius_m, f);
            }
        }
    }
    for field in &mut spec.debris_fields {
        grow_rect(&mut field.region, f);
        field.count = (field.count as f64 * f * f).round() as usize;
    }
    for zone in &mut spec.radiation_zones {
        zone.center_m = times(zone.center_m, f);
        zone.radius_m = longer(zone.radius_m, f);
    }
}

/// Reads and parses the scenario file `file`. Errors (one line): unreadable or unparsable.
fn read_spec(file: &str) -> Result<ScenarioSpec, String> {
    let src = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    scenario::parse_spec(&src, file).map_err(|e| e.to_string())
}

/// Robots in a scenario spec.
fn robots(spec: &ScenarioSpec) -> usize {
    spec.kinds.iter().map(|k| k.count).sum()
}

/// The team of `n` robots: the first of `given` (`--scenario` files) with `n` robots; else
/// `paper.ron` for 12; else `scenarios/swarm-<n>.ron` when that file exists; else `base`
/// with its kinds scaled to `n` (and beyond the base's team its plan stretched by
/// `sqrt(n / base robots)`, see [`grow`]). Errors (one line): a file does not read or parse,
/// `scenarios/swarm-<n>.ron` does not hold `n` robots, or the team does not validate (for
/// example its start grids no longer fit the arena).
pub fn team(n: usize, base: &str, given: &[String]) -> Result<Team, String> {
    for file in given {
        let spec = read_spec(file)?;
        if robots(&spec) == n {
            return validated(spec, file, short(file));
        }
    }
    let own = path(&format!("scenarios/swarm-{n}.ron"));
    if n == 12 || Path::new(&own).exists() {
        let file = if n == 12 { path(PAPER) } else { own };
        let spec = read_spec(&file)?;
        if robots(&spec) != n {
            return Err(format!("{file}: {} robots, not {n}", robots(&spec)));
        }
        return validated(spec, &file, short(&file));
    }
    let spec = read_spec(base)?;
    // Columns rounded first (the layouts of every team measured so far); where that leaves two
    // kinds' grids too close (a team of 2,000), rows capped.
    scaled(spec.clone(), n, base, false)
        .or_else(|first| scaled(spec, n, base, true).map_err(|_| first))
}

/// `spec` (the base, from the file `base`) with its kinds scaled to `n` robots and, beyond the
/// base's team, its plan stretched ([`grow`], `cap_rows` as there), validated.
fn scaled(mut spec: ScenarioSpec, n: usize, base: &str, cap_rows: bool) -> Result<Team, String> {
    let had = robots(&spec);
    let mut source = format!("{}, kinds scaled to {n}", short(base));
    if n > had && had > 0 {
        let f = (n as f64 / had as f64).sqrt();
        grow(&mut spec, f, cap_rows);
        source = format!(
            "{source}, plan stretched x{f:.3} (arena {:.0} m x {:.0} m){}",
            spec.arena.width_m.get(),
            spec.arena.height_m.get(),
            if cap_rows { ", start rows capped" } else { "" }
        );
    }
    if had != n {
        scale_team(&mut spec, n);
        let short_list = spec
            .kinds
            .iter()
            .any(|k| matches!(&k.starts, StartsSpec::List(l) if l.len() < k.count));
        if short_list {
            spread_starts(&mut spec);
        }
    }
    validated(spec, &format!("{base} x {n}"), source)
}

/// The team of `spec`, with Rapier stepped every step (`sim.physics: EveryStep`, whatever the
/// file says): the bare-Rapier replay steps every body every step, so only then do the
/// replayed bodies stand where the world's do (`measure.rs`); `docs/scaling.md`, "Physics
/// only near contacts", measures the gated steppings.
fn validated(mut spec: ScenarioSpec, file: &str, mut source: String) -> Result<Team, String> {
    if spec.sim.physics != PhysicsStepping::EveryStep {
        spec.sim.physics = PhysicsStepping::EveryStep;
        source = format!("{source}, physics every step");
    }
    let scenario = spec.validate(file).map_err(|e| format!("{file}: {e}"))?;
    Ok(Team { scenario, source })
}

/// `file` relative to the workspace root when it lies under it.
pub fn short(file: &str) -> String {
    let root = path("");
    file.strip_prefix(&root).unwrap_or(file).to_owned()
}
