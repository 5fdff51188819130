# Recipes for the commands in the README. `just --list` shows them.

# Show the recipes.
default:
    @just --list

# The main job: RNE trust values of the paper's Example 1.
trust:
    cargo run --release -p experiments --bin usar -- trust --weights 6,4,2 --needs 86,120,30 --needs 20,30,10 --needs 80,115,25

# The README's test command (what CI runs).
test:
    cargo test --workspace

# Everything CI checks: formatting, lints, tests.
ci:
    bash .ci/run

# Criterion benchmarks.
bench:
    cargo bench --workspace
