#!/usr/bin/env bash
# Rapier's `parallel` feature, measured: why the simulator steps Rapier serially
# (docs/scaling.md, "Rapier's parallel feature").
#
#   1. builds `usar` as it is (target/release) and, from a throwaway git worktree of HEAD whose
#      Cargo.toml asks for `rapier2d` with `features = ["parallel"]`, a second `usar` in
#      target/rapier-parallel;
#   2. runs one trial of scenarios/swarm-10000.ron (DIS, trial 0, DURATION seconds) with the
#      usual build on 1 thread and with the parallel build on 1 and 2 threads, prints each
#      run's wall-clock and CPU time and the speed-ups, and compares the three JSON results
#      byte for byte;
#   3. runs a short paper sweep (`--duration 60`, trials in parallel, one per thread) with each
#      build under a timeout of SWEEP_TIMEOUT_S seconds, and says whether it finished;
#   4. removes the worktree (also on failure).
#
# Usage: scripts/rapier-parallel.sh          (about 15 min on 2 cores with the default 300 s)
# Environment: DURATION (default 300: simulated seconds of the 10,000-robot trial),
#              SWEEP_TIMEOUT_S (default 120).
# Exit status: non-zero when a build fails or the three results differ.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"
duration="${DURATION:-300}"
sweep_timeout_s="${SWEEP_TIMEOUT_S:-120}"
work="$(mktemp -d)"
src="$work/src"
cleanup() {
    git -C "$repo" worktree remove --force "$src" >/dev/null 2>&1 || true
    rm -rf "$work"
}
trap cleanup EXIT

echo "== building usar (usual) and usar with rapier2d/parallel"
cargo build --release -q -p experiments --bin usar
git worktree add -q --detach "$src" HEAD
sed -i 's/^rapier2d = "\(.*\)"$/rapier2d = { version = "\1", features = ["parallel"] }/' \
    "$src/Cargo.toml"
grep -q '^rapier2d = { version = ".*", features = \["parallel"\] }' "$src/Cargo.toml" || {
    echo "error: $src/Cargo.toml: rapier2d: the line \`rapier2d = \"...\"\` was not found" >&2
    exit 1
}
(cd "$src" && CARGO_TARGET_DIR="$repo/target/rapier-parallel" \
    cargo build --release -q -p experiments --bin usar)
usual="$repo/target/release/usar"
parallel="$repo/target/rapier-parallel/release/usar"

# run LABEL BINARY THREADS: one trial into $work/LABEL.json, its times into $work/LABEL.time
run() {
    /usr/bin/time -f "%e %U %S" -o "$work/$1.time" "$2" run scenarios/swarm-10000.ron \
        --method dis --duration "$duration" --threads "$3" --json "$work/$1.json" >/dev/null
    read -r wall user sys <"$work/$1.time"
    awk -v l="$1" -v t="$3" -v w="$wall" -v u="$user" -v s="$sys" \
        'BEGIN { printf "%-20s threads %s: %8.2f s wall, %8.2f s CPU\n", l, t, w, u + s }'
}
echo "== swarm-10000.ron, DIS, trial 0, $duration s simulated"
run usual "$usual" 1
run parallel-1-thread "$parallel" 1
run parallel-2-threads "$parallel" 2
# ratio A B: wall-clock of run A over that of run B
ratio() {
    awk '{ w[NR] = $1 } END { printf "%.2f\n", w[1] / w[2] }' "$work/$1.time" "$work/$2.time"
}
echo "wall-clock speed-up, parallel build on 2 threads over the usual on 1:" \
    "$(ratio usual parallel-2-threads)"
echo "wall-clock speed-up, parallel build on 2 threads over itself on 1:" \
    "$(ratio parallel-1-thread parallel-2-threads)"
status=0
for r in parallel-1-thread parallel-2-threads; do
    if cmp -s "$work/usual.json" "$work/$r.json"; then
        echo "result of $r: identical to the usual build's"
    else
        echo "result of $r: DIFFERS from the usual build's"
        status=1
    fi
done

echo "== paper sweep, 60 s trials, one trial per thread, under a ${sweep_timeout_s} s timeout"
for b in usual parallel; do
    bin="$usual"
    [ "$b" = parallel ] && bin="$parallel"
    if timeout -k 5 "$sweep_timeout_s" "$bin" sweep scenarios/paper.ron --duration 60 \
        --out "$work/sweep-$b" -q >/dev/null 2>&1; then
        echo "$b build: the sweep finished"
    else
        echo "$b build: the sweep did NOT finish within ${sweep_timeout_s} s"
    fi
done
exit "$status"
