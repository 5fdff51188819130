//! Throughput of the simulator through the experiments layer (a `harness = false` bench that
//! prints its figures):
//!
//! 1. one `scenarios/paper.ron` trial (RNE, trial 0, 600 s), best and median of 5 runs;
//! 2. the whole default sweep (4 methods x 10 trials x 600 s) on 1 thread and on 2 threads,
//!    with the simulated seconds per wall-clock second per core and the 2-thread speed-up.
//!
//! Run in release: `cargo bench -p experiments --bench sweep`.

use std::path::PathBuf;
use std::time::Instant;

use rne_core::grouping::{METHOD_NAMES, method_from_name};
use usar_report::analysis::Analysis;
use usar_report::output::write_outputs;
use usar_sim::mission::Simulation;
use usar_sweep::sweep::{SweepConfig, run_sweep, trust_model};

fn main() {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/paper.ron"
    ));
    let scenario = usar_sim::scenario::load(&path).expect("paper.ron loads");
    let model = trust_model(&scenario).expect("weights");
    let duration = scenario.mission().duration_s.get();

    // 1. One trial.
    let mut times = Vec::new();
    for _ in 0..5 {
        let method = method_from_name("rne", &model).expect("rne");
        let t0 = Instant::now();
        let r = Simulation::for_trial(&scenario, method, 0)
            .run_to_end()
            .expect("trial runs");
        times.push(t0.elapsed().as_secs_f64());
        std::hint::black_box(r);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "one paper.ron trial (RNE, {duration} s): best {:.3} s, median {:.3} s -> {:.0} sim-s per wall-s on one core",
        times[0],
        times[2],
        duration / times[2]
    );

    // 2. The default sweep on 1 and 2 threads.
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let mut walls = Vec::new();
    for threads in [1usize, 2] {
        let tmp = tempfile::tempdir().expect("temp dir");
        let cfg = SweepConfig {
            methods: METHOD_NAMES.iter().map(|s| s.to_string()).collect(),
            trials: 10,
            threads,
            out_dir: tmp.path().to_path_buf(),
            progress: false,
            ..SweepConfig::new(scenario.clone(), path.clone())
        };
        let t0 = Instant::now();
        let o = run_sweep(&cfg).expect("sweep runs");
        write_outputs(&cfg, &o, &Analysis::of(&o), &[]).expect("files written");
        let wall = t0.elapsed().as_secs_f64();
        let sim = o.simulated_s();
        println!(
            "default sweep (4 methods x 10 trials x {duration} s) on {threads} thread(s): {wall:.2} s wall \
             (trials {:.2} s, files {:.2} s), {:.0} sim-s per wall-s, {:.0} per core",
            o.wall_s,
            wall - o.wall_s,
            sim / wall,
            sim / wall / threads as f64
        );
        walls.push(wall);
    }
    println!(
        "2-thread speed-up over 1 thread: {:.2}x (machine has {cores} core(s))",
        walls[0] / walls[1]
    );
}
