# Recipes for the commands in the README. `just --list` shows them.

usar := "cargo run --release -p experiments --bin usar --"

# Show the recipes.
default:
    @just --list

# The main job: the paper's comparison (4 methods x 10 trials x 600 s) into results/paper/,
# with the paper's calibration targets and claims checked in report.md (paper.ron's `report`
# section asks for both).
sweep *ARGS:
    {{usar}} sweep scenarios/paper.ron {{ARGS}}

# The README's test command: the default tier (about 1 min with the dependencies built).
test:
    cargo test --workspace

# Both tiers: the default one in debug, then the long one (#[ignore]d: whole-trial checks, the
# calibration bands, swarm-1000's round bound; not swarm-10000's, `just swarm-bound-10k`) in
# release, as CI runs them.
test-all:
    cargo test --workspace
    cargo test --release --workspace -- --ignored --skip swarm_10000

# The default tier through cargo-nextest with CI's profile: per-test timings, and any test over
# 30 s fails by name (.config/nextest.toml); then the slowest ten.
test-timed:
    cargo nextest run --workspace --profile ci
    python3 scripts/slowest-tests.py target/nextest/ci/junit.xml 10

# Everything CI checks (a table of each step's seconds at the end).
ci:
    bash .ci/run

# The libraries alone (usar-sweep: no clap, no figures; usar-report: no clap; usar-study: the
# studies without the command line): lints and tests.
lib-only:
    cargo clippy -p usar-sweep -p usar-report -p usar-study --all-targets -- -D warnings
    cargo test -p usar-sweep -p usar-report -p usar-study

# One trial of paper.ron with a grouping method (rne, dis, eng, hp_dis).
run METHOD="rne" TRIAL="0":
    {{usar}} run scenarios/paper.ron --method {{METHOD}} --trial {{TRIAL}}

# Validate a scenario file and print a summary.
check FILE="scenarios/paper.ron":
    {{usar}} check {{FILE}}

# Draw paper.ron, and the paths of the first 200 s of trial 0, as SVG.
render:
    {{usar}} render scenarios/paper.ron --out docs/img/paper-arena.svg
    {{usar}} render scenarios/paper.ron --out docs/img/paper-trace.svg --trace --duration 200

# Watch trial 0 of paper.ron (RNE) in a browser: writes replay.html.
replay METHOD="rne" TRIAL="0":
    {{usar}} replay scenarios/paper.ron --method {{METHOD}} --trial {{TRIAL}} --out replay.html

# The README's replay screenshot (docs/img/replay.png), taken by the browser test in chromium.
replay-screenshot:
    USAR_WRITE_SCREENSHOT="$PWD/docs/img/replay.png" cargo test -p experiments --test integration readme_screenshot -- --ignored --nocapture

# swarm-1000's round bound: every round but the last completes in 1,800 s, every method (about 3 min on 2 cores).
swarm-bound:
    cargo test --release -p integration-tests --test integration swarm -- --ignored --nocapture --skip swarm_10000

# swarm-10000's round bound, every method (about 6 min on 2 cores; CI runs it last, when time
# allows: docs/scaling.md).
swarm-bound-10k:
    cargo test --release -p integration-tests --test integration -- --ignored --nocapture swarm_10000

# Rapier's `parallel` feature measured: a 10,000-robot trial on 1 and 2 threads (same results?
# how much faster?) and a paper sweep with it (docs/scaling.md, "Rapier's parallel feature";
# about 15 min on 2 cores).
rapier-parallel:
    scripts/rapier-parallel.sh

# The comparison in every combination of the paper's open choices, each calibrated first
# (docs/multiverse.md; the axes are scenarios/paper-axes.ron).
multiverse *ARGS:
    {{usar}} multiverse scenarios/paper.ron --axes scenarios/paper-axes.ron --targets scenarios/paper-targets.ron --free 'mission.hp_pct_per_step_in_radiation=0.001..0.02:log' --free 'mission.search_time_budget_s=6..30' --sample 64 --out results/multiverse-paper {{ARGS}}

# RNE trust values of the paper's Example 1.
trust:
    {{usar}} trust --weights 6,4,2 --needs 86,120,30 --needs 20,30,10 --needs 80,115,25

# Benchmarks: grouping, world stepping vs bare Rapier, one trial and the whole sweep.
bench:
    cargo bench --workspace
