#!/usr/bin/env bash
# A real Slurm in the tests: runs a short sharded sweep on a one-node Slurm cluster on this
# machine and checks that the merged CSV files are byte-identical to a sweep on one machine.
#
#   1. installs Debian's slurm-wlm and munge packages when they are absent (needs root and
#      Debian's package archive; a failed install fails this script, it is never skipped);
#   2. starts munged, slurmctld and slurmd of its own in a temporary folder, with a minimal
#      slurm.conf for this machine's CPUs and memory (`slurmd -C`) and ports of its own, so a
#      Slurm or munge already on the machine is neither used nor disturbed;
#   3. runs `usar slurm scenarios/paper.ron --methods rne,dis --trials 2 --duration 60
#      --shards 4 --submit`, waits for the array and the chained merge job, and compares
#      trials.csv, trials_long.csv and summary.csv with `usar sweep` of the same sweep;
#   4. stops the daemons it started (by pid) and removes its temporary folder, also on failure.
#
# Usage (as root, from anywhere): scripts/slurm-test.sh    (CI: .ci/run runs it)
# Environment: USAR_BIN (a built usar; default: cargo build --release -p experiments --bin usar),
#              USAR_SLURM_PORT (default 36817; slurmd uses the next port),
#              USAR_SLURM_TIMEOUT_S (default 600: the longest wait for the jobs).
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"
started_at=$(date +%s)
port="${USAR_SLURM_PORT:-36817}"
timeout_s="${USAR_SLURM_TIMEOUT_S:-600}"

fail() {
    echo "slurm-test: FAILED: $*" >&2
    exit 1
}

[ "$(id -u)" -eq 0 ] || fail "must run as root (it installs packages and runs slurmd)"

# --- 1. packages ----------------------------------------------------------------------------
PATH="$PATH:/usr/sbin:/sbin"
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
    || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null \
    || ! command -v mungekey >/dev/null; then
    echo "== installing Debian's slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q || fail "apt-get update failed: cannot install slurm-wlm and munge"
    apt-get install -y -q --no-install-recommends slurm-wlm munge \
        || fail "apt-get install slurm-wlm munge failed"
fi
for p in slurmctld slurmd sbatch squeue sinfo scontrol munged mungekey; do
    command -v "$p" >/dev/null || fail "$p is not installed (packages slurm-wlm, munge)"
done
echo "slurm: $(slurmctld -V), munge: $(munged --version 2>&1 | head -n1)"

# --- 2. a one-node cluster ------------------------------------------------------------------
tmp="$(mktemp -d /tmp/usar-slurm-test.XXXXXX)"
pids=()
cleanup() {
    status=$?
    for pid in "${pids[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${pids[@]}"; do
        for _ in $(seq 50); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.2
        done
        kill -9 "$pid" 2>/dev/null || true
    done
    rm -rf "$tmp"
    exit "$status"
}
trap cleanup EXIT
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
chmod 755 "$tmp"
chmod 755 "$tmp/munge"   # clients need to reach the socket; the key file itself is 0600

mungekey --create --keyfile="$tmp/munge/munge.key"
munged --foreground --force --socket="$tmp/munge/munge.socket" \
    --key-file="$tmp/munge/munge.key" --pid-file="$tmp/munge/munged.pid" \
    --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/munged.seed" \
    >"$tmp/log/munged.out" 2>&1 &
pids+=("$!")
for _ in $(seq 50); do [ -S "$tmp/munge/munge.socket" ] && break; sleep 0.2; done
[ -S "$tmp/munge/munge.socket" ] || { cat "$tmp/log/munged.log" >&2 || true; fail "munged did not start"; }

host="$(hostname -s)"
# This machine's CPUs and memory, as slurmd sees them ("NodeName=... CPUs=2 ... RealMemory=N").
node="$(slurmd -C | head -n1 | sed "s/^NodeName=[^ ]*/NodeName=$host NodeAddr=127.0.0.1/")"
export SLURM_CONF="$tmp/slurm.conf"
cat >"$SLURM_CONF" <<CONF
# A one-node cluster on localhost for scripts/slurm-test.sh.
ClusterName=usartest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MinJobAge=600
$node
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -D -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=("$!")
slurmd -D -N "$host" -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=("$!")
show_logs() {
    for f in "$tmp"/log/*; do echo "--- $f" >&2; tail -n 30 "$f" >&2 || true; done
}
state=""
for _ in $(seq 120); do
    state="$(sinfo -h -n "$host" -o %t 2>/dev/null || true)"
    [ "$state" = "idle" ] && break
    sleep 0.5
done
[ "$state" = "idle" ] || { show_logs; fail "the node did not come up (state: '${state:-none}')"; }
echo "one-node cluster up: $node"

# --- 3. the sharded sweep and the local sweep ------------------------------------------------
# USAR_BIN: a release build of usar already made (CI passes the one its release tests built).
if [ -n "${USAR_BIN:-}" ]; then
    usar="$USAR_BIN"
else
    cargo build --release -q -p experiments --bin usar
    usar="$repo/target/release/usar"
fi
sweep=(scenarios/paper.ron --methods rne,dis --trials 2 --duration 60)

"$usar" sweep "${sweep[@]}" --quiet --out "$tmp/local" >/dev/null
submitted="$("$usar" slurm "${sweep[@]}" --out "$tmp/sharded" --shards 4 --cpus-per-task 1 \
    --time 10 --submit)" || { show_logs; fail "usar slurm --submit failed"; }
echo "$submitted"
array="$(echo "$submitted" | sed -n 's/.*array as job \([0-9]*\).*/\1/p')"
merge="$(echo "$submitted" | sed -n 's/.*merge as job \([0-9]*\).*/\1/p')"
[ -n "$array" ] && [ -n "$merge" ] || fail "no job ids in the output of usar slurm"

waited=0
while [ -n "$(squeue -h -j "$array,$merge" 2>/dev/null)" ]; do
    [ "$waited" -lt "$timeout_s" ] || { squeue; show_logs; fail "the jobs did not end in ${timeout_s} s"; }
    sleep 2
    waited=$((waited + 2))
done
logs="$tmp/sharded/slurm/logs"
job_states() { scontrol -o show job "$1" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c; }
echo "array $array: $(job_states "$array" | tr '\n' ' ')"
echo "merge $merge: $(job_states "$merge" | tr '\n' ' ')"
if job_states "$array" | grep -v -q 'JobState=COMPLETED' \
    || job_states "$merge" | grep -v -q 'JobState=COMPLETED'; then
    for f in "$logs"/*; do echo "--- $f" >&2; cat "$f" >&2; done
    show_logs
    fail "a job did not complete"
fi
[ "$(ls "$logs"/sweep-*.out | wc -l)" -eq 4 ] || fail "expected 4 array task logs in $logs"
cat "$logs"/merge-*.out

for f in trials.csv trials_long.csv summary.csv; do
    cmp "$tmp/local/$f" "$tmp/sharded/$f" || fail "$f of the merge differs from the local sweep"
done
for f in report.md fig3a_rescuees.svg; do
    [ -s "$tmp/sharded/$f" ] || fail "the merge wrote no $f"
done
echo "slurm-test: OK: 4 shards on Slurm, merged CSV files byte-identical to the local sweep" \
    "($(($(date +%s) - started_at)) s)"
