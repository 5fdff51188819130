//! Scaling bench (issue 10): for teams of 12, 100, 300 and 1,000 robots, world steps per second
//! with all logic (`Simulation::step`: rounds, decisions, navigation, resolver, Rapier,
//! accounting), the same bodies stepped by bare Rapier (same colliders, integration parameters
//! and static obstacles, each robot driven at its top speed towards its first goal, no logic;
//! the two run in alternating blocks of 50 steps, so both see the same load of the machine),
//! their ratio, simulated seconds per wall second with all logic, the same with the robots'
//! software run every step for a scenario with a control period (`sim.control_period_s`:
//! `swarm-1000.ron` decides every 0.1 s), and the process's peak resident memory (`VmHWM` of `/proc/self/status`, after each team; teams run smallest first).
//!
//! A team of `n` is [`BASE`] with its kinds' counts (and per-task quotas) scaled to `n`; 12
//! robots is `scenarios/paper.ron` itself. Prints one table in one run. Rates are per CPU
//! second of the stepping thread (`clock_gettime`'s thread CPU clock), so other load on a shared
//! machine does not count.
//!
//! Run in release: `cargo bench -p usar-sim --bench scale` (about a minute), or
//! `cargo bench -p usar-sim --bench scale -- --quick` (teams of 12 and 100, a few steps: a
//! smoke test). Options: `--base FILE` (the scenario to scale, default [`BASE`]),
//! `--method NAME` (default `dis`: the grouping is not what is measured
//! here), `--steps N` (steps per measurement, default 1,500 = 30 simulated seconds),
//! `--budget-s S` (wall-clock cap per measurement, default 20 s), `--teams 12,100,...` (team
//! sizes, default 12, 100, 300, 1,000), `--svg FILE` (relative to the workspace root; also
//! draw the measured curve: steps per
//! CPU second with all logic and with bare Rapier against team size, log-log, with the
//! 25x-real-time line; `docs/img/scaling.svg` is made this way).
//!
//! A team that cannot be built (for example `--teams 1500` with the default base: the scaled
//! start grids overlap) or an unknown `--method` stops the bench with a one-line error
//! naming the scenario field, exit status 1.

use std::time::Instant;

use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, DebrisSpec, Locomotion, Scenario, ScenarioSpec, StartsSpec, XyM};
use usar_sim::world::bodies::{PhysicsScene, to_vec2};

/// The scenario whose kind counts are scaled: its `Grid` start layouts follow the counts (a
/// base with `List` starts too short for a team gets [`spread_starts`]).
const BASE: &str = "scenarios/swarm-1000.ron";

/// The 12-robot team.
const PAPER: &str = "scenarios/paper.ron";

fn path(rel: &str) -> String {
    format!("{}/../../{rel}", env!("CARGO_MANIFEST_DIR"))
}

/// Command-line options (after `--`).
struct Options {
    base: String,
    method: String,
    steps: u64,
    budget_s: f64,
    /// Team sizes to measure.
    teams: Vec<usize>,
    /// Where to draw the measured curve (SVG), if anywhere.
    svg: Option<String>,
}

/// Ends the bench with a one-line error about option `name`.
fn refuse(name: &str, why: &str) -> ! {
    eprintln!("error: scale bench: {name}: {why}");
    std::process::exit(2)
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        match args.get(i + 1) {
            Some(v) => Some(v.clone()),
            None => refuse(name, "expected a value after it"),
        }
    };
    // A positive number, or the default when the option is absent.
    fn positive<T: std::str::FromStr + PartialOrd + Default>(
        name: &str,
        v: Option<String>,
        default: T,
    ) -> T {
        let Some(v) = v else { return default };
        match v.trim().parse::<T>() {
            Ok(x) if x > T::default() => x,
            _ => refuse(name, &format!("expected a number > 0, found {v:?}")),
        }
    }
    let quick = args.iter().any(|a| a == "--quick");
    let teams = value("--teams").map(|v| {
        v.split(',')
            .map(|t| positive("--teams", Some(t.to_owned()), 0usize))
            .collect()
    });
    Options {
        base: value("--base").unwrap_or_else(|| path(BASE)),
        method: value("--method").unwrap_or_else(|| "dis".into()),
        steps: positive("--steps", value("--steps"), if quick { 20 } else { 1500 }),
        budget_s: positive(
            "--budget-s",
            value("--budget-s"),
            if quick { 5.0 } else { 20.0 },
        ),
        // Relative to the workspace root (cargo runs benches in the crate's folder).
        svg: value("--svg").map(|f| {
            if std::path::Path::new(&f).is_absolute() {
                f
            } else {
                path(&f)
            }
        }),
        teams: teams.unwrap_or_else(|| {
            if quick {
                vec![12, 100]
            } else {
                vec![12, 100, 300, 1000]
            }
        }),
    }
}

/// Scales `counts` to sum to `n` (largest remainders; ties to the earlier kind), each >= 1.
fn scale_counts(counts: &[usize], n: usize) -> Vec<usize> {
    let total: usize = counts.iter().sum();
    let exact: Vec<f64> = counts
        .iter()
        .map(|&c| c as f64 * n as f64 / total as f64)
        .collect();
    let mut out: Vec<usize> = exact.iter().map(|&x| (x.floor() as usize).max(1)).collect();
    let mut order: Vec<usize> = (0..counts.len()).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())));
    let mut k = 0;
    while out.iter().sum::<usize>() < n {
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

/// The team of `n` robots (see the module docs): `paper.ron` for 12, else `base` scaled.
/// Errors (one line): the base does not read or parse, or the scaled team does not validate
/// (for example its start grids no longer fit the arena).
fn team(n: usize, base: &str) -> Result<Scenario, String> {
    let paper = path(PAPER);
    let base = if n == 12 { paper.as_str() } else { base };
    let src = std::fs::read_to_string(base).map_err(|e| format!("{base}: {e}"))?;
    let mut spec = scenario::parse_spec(&src, base).map_err(|e| e.to_string())?;
    let count = spec.kinds.iter().map(|k| k.count).sum::<usize>();
    if count != n {
        scale_team(&mut spec, n);
        let short = spec
            .kinds
            .iter()
            .any(|k| matches!(&k.starts, StartsSpec::List(l) if l.len() < k.count));
        if base == paper || short {
            spread_starts(&mut spec);
        }
    }
    spec.validate(&format!("{base} x {n}"))
        .map_err(|e| format!("team of {n}: {e}"))
}

/// Peak resident set size of this process so far, MiB (`VmHWM`; 0 where unavailable).
fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// CPU time of this thread so far, seconds (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, exact
/// to the nanosecond: `/proc/thread-self/schedstat` moves only at scheduler ticks, 4 ms
/// here), so other load on a shared machine does not count.
fn cpu_s() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// Steps per measured block: the logic and bare Rapier run in alternating blocks of this
/// many steps, so both see the same load of a shared machine.
const BLOCK_STEPS: u64 = 50;

/// Steps run and CPU seconds spent.
type Timed = (u64, f64);

/// Runs `logic` and `bare` alternately, [`BLOCK_STEPS`] at a time, each up to `steps` times,
/// until `budget_s` of wall time, or until `logic` returns `false`; returns the steps run
/// and CPU seconds of this thread spent by each.
fn time_steps(
    steps: u64,
    budget_s: f64,
    mut logic: impl FnMut() -> bool,
    mut bare: impl FnMut(),
) -> (Timed, Timed) {
    let t0 = Instant::now();
    let (mut logic_done, mut logic_s, mut bare_done, mut bare_s) = (0, 0.0, 0, 0.0);
    let mut go_on = true;
    while go_on && logic_done < steps && t0.elapsed().as_secs_f64() <= budget_s {
        let block = BLOCK_STEPS.min(steps - logic_done);
        let c0 = cpu_s();
        let mut ran = 0;
        while ran < block && go_on {
            go_on = logic();
            ran += 1;
        }
        logic_done += ran;
        let c1 = cpu_s();
        // As many bare steps as the logic ran in this block.
        for _ in 0..ran {
            bare();
        }
        bare_done += ran;
        let c2 = cpu_s();
        logic_s += c1 - c0;
        bare_s += c2 - c1;
    }
    ((logic_done, logic_s), (bare_done, bare_s))
}

/// The same bodies in bare Rapier, each robot moving at its top speed towards its first
/// task's goal (ground) or search-area centre (aerial).
fn bare_scene(s: &Scenario) -> PhysicsScene {
    let mut scene = PhysicsScene::new(s);
    for (id, r) in s.robots().iter().enumerate() {
        let kind = &s.kinds()[r.kind];
        let task = &s.tasks()[id % s.tasks().len()];
        let goal = match kind.locomotion {
            Locomotion::Ground => task.goal,
            Locomotion::Aerial => task.search_area.center(),
        };
        let v = to_vec2(&goal) - to_vec2(&r.start_in_world);
        let body = &mut scene.physics.bodies[scene.robot_bodies[id]];
        body.set_linvel(v.normalize_or_zero() * kind.max_speed_m_per_s as f32, true);
    }
    scene
}

/// Steps and CPU seconds of the full simulation of `s` and of its bodies in bare Rapier, run
/// in alternating blocks. Errors (one line): the simulation does not build (an unknown
/// `--method`) or a step fails.
fn run_both(s: &Scenario, o: &Options) -> Result<(Timed, Timed), String> {
    let mut sim = Simulation::builder(s)
        .method_named(&o.method)
        .trial(0)
        .duration_s(1e5)
        .build()
        .map_err(|e| e.to_string())?;
    let mut scene = bare_scene(s);
    let mut failed = None;
    let timed = time_steps(
        o.steps,
        o.budget_s,
        || {
            failed = sim.step().err();
            failed.is_none()
        },
        || scene.step(),
    );
    failed.map_or(Ok(timed), |e| Err(format!("step {}: {e}", timed.0.0)))
}

/// One measured team: robots, steps per CPU second with all logic and with bare Rapier, step
/// length in seconds; for a scenario with a control period (`sim.control_period_s`) also the
/// steps per CPU second with the robots' software run every step, and bare Rapier's rate
/// measured beside that run.
struct Row {
    robots: usize,
    logic: f64,
    bare: f64,
    dt_s: f64,
    every_step: Option<(f64, f64)>,
}

/// Steps per CPU second of what [`run_both`] timed (logic, bare).
fn rates(((ls, lw), (bs, bw)): (Timed, Timed)) -> (f64, f64) {
    (ls as f64 / lw, bs as f64 / bw)
}

/// Builds the team of `n` and measures it (and, with a control period, the same team with
/// its software run every step). Errors: as [`team`] and [`run_both`].
fn measure(n: usize, o: &Options) -> Result<Row, String> {
    let s = team(n, &o.base)?;
    let (logic, bare) = rates(run_both(&s, o)?);
    let every_step = match s.sim().control_period_s {
        Some(_) => {
            let each = s
                .edit(|spec| spec.sim.control_period_s = None)
                .map_err(|e| e.to_string())?;
            Some(rates(run_both(&each, o)?))
        }
        None => None,
    };
    Ok(Row {
        robots: n,
        logic,
        bare,
        dt_s: s.sim().dt_s.get(),
        every_step,
    })
}

/// A curve of the figure: its label, colour and value of a row.
type Series<'a> = (&'a str, plotters::style::RGBColor, &'a dyn Fn(&Row) -> f64);

/// Draws `rows` as a log-log plot into the SVG file `path`.
fn draw(rows: &[Row], path: &str) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (720, 460)).into_drawing_area();
    root.fill(&WHITE)?;
    let x_max = rows.iter().map(|r| r.robots).max().unwrap_or(1000) as f64 * 1.3;
    let y_max = rows.iter().map(|r| r.bare.max(r.logic)).fold(1.0, f64::max) * 1.5;
    let y_min = rows
        .iter()
        .map(|r| {
            r.logic
                .min(r.bare)
                .min(r.every_step.map_or(r.logic, |(l, _)| l))
        })
        .fold(f64::MAX, f64::min)
        * 0.5;
    let mut chart = ChartBuilder::on(&root)
        .caption("Steps per CPU second against team size", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d((8.0..x_max).log_scale(), (y_min..y_max).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("robots")
        .y_desc("world steps per CPU second")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    let every_step = |r: &Row| r.every_step.map_or(r.logic, |(l, _)| l);
    let series: [Series; 3] = [
        (
            "all logic, as the scenario (software every control period)",
            RGBColor(31, 119, 180),
            &|r| r.logic,
        ),
        (
            "all logic, software every step",
            RGBColor(255, 127, 14),
            &every_step,
        ),
        ("bare Rapier, same bodies", RGBColor(127, 127, 127), &|r| {
            r.bare
        }),
    ];
    for (label, colour, value) in series {
        let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.robots as f64, value(r))).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
    }
    if let Some(dt) = rows.first().map(|r| r.dt_s) {
        let target = 25.0 / dt;
        let red = RGBColor(214, 39, 40);
        chart
            .draw_series(LineSeries::new(
                [(8.0, target), (x_max, target)],
                red.stroke_width(1),
            ))?
            .label("25x real time")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], red.stroke_width(1)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

fn main() {
    let o = options();
    println!(
        "scaling bench: {} scaled, method {}, up to {} steps or {} s per measurement, one thread, rates per CPU second of the thread",
        o.base, o.method, o.steps, o.budget_s
    );
    println!(
        "| robots | logic steps/s | bare Rapier steps/s | step cost logic/bare | sim-s per wall-s | software every step: logic steps/s | bare steps/s | logic/bare | peak RSS MiB |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut rows = Vec::new();
    for &n in &o.teams {
        let row = measure(n, &o).unwrap_or_else(|e| {
            eprintln!("error: {e}");
            std::process::exit(1);
        });
        let every = row.every_step.map_or_else(
            || "(no control period) | | |".to_string(),
            |(l, b)| format!("{l:.0} | {b:.0} | {:.2} |", b / l),
        );
        println!(
            "| {n} | {:.0} | {:.0} | {:.2} | {:.1} | {every} {:.0} |",
            row.logic,
            row.bare,
            row.bare / row.logic,
            row.logic * row.dt_s,
            peak_rss_mib()
        );
        rows.push(row);
    }
    rows.retain(|r| r.logic.is_finite() && r.bare.is_finite() && r.logic > 0.0 && r.bare > 0.0);
    if let Some(path) = &o.svg {
        match draw(&rows, path) {
            Ok(()) => println!("figure: {path}"),
            Err(e) => {
                eprintln!("error: cannot draw {path}: {e}");
                std::process::exit(1);
            }
        }
    }
}
