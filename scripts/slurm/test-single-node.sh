#!/usr/bin/env bash
# `make test-slurm`: scripts/slurm/bench.sbatch for real on a one-node Slurm that this script
# starts on localhost and tears down again. Needs root (slurmd runs jobs as their user), Debian's
# slurm-wlm and munge (scripts/install-deps.sh), and no systemd: munged, slurmctld and slurmd run
# from a temporary folder with a minimal slurm.conf (no cgroups: proctrack/linuxproc, task/none,
# no accounting) on free ports, so a Slurm already on the machine is left alone.
#
#   scripts/slurm/test-single-node.sh build/apps/aperture
#
# It submits a 4-shard `bench gap` of a few short ground-truth trials plus the merge, waits for
# the merge job, runs the same bench unsharded (all cores), and compares: every figure of
# summary.json and every cell of trials.csv equal (wall and CPU times aside), and prints both wall
# times. Exit 0 when they match. Other benches (docs/results/slurm.md measures with these):
#   TEST_SLURM_SHARDS=4 TEST_SLURM_BENCH="gap --trials 40 --duration 2" scripts/slurm/test-single-node.sh A
# TEST_SLURM_KEEP=DIR keeps the shards, the merge and the unsharded run in DIR.
set -euo pipefail

aperture=${1:?usage: $0 PATH/TO/aperture}
aperture=$(cd "$(dirname "$aperture")" && pwd)/$(basename "$aperture")
here=$(cd "$(dirname "$0")" && pwd)
[[ -x "$aperture" ]] || { echo "test-slurm: $aperture is not an executable" >&2; exit 2; }
if [[ $(id -u) -ne 0 ]]; then
  echo "test-slurm: must run as root (it starts munged, slurmctld and slurmd); try sudo make test-slurm" >&2
  exit 2
fi
for tool in munged slurmctld slurmd sbatch squeue sinfo scontrol python3; do
  command -v "$tool" >/dev/null || { echo "test-slurm: $tool missing; run scripts/install-deps.sh" >&2; exit 2; }
done

# The bench: 4 shards of 8 ground-truth trials (no camera), 6 simulated seconds each.
read -r -a bench_args <<<"${TEST_SLURM_BENCH:-gap --trials 8 --seed 5 --autopilot ground_truth --duration 6}"
shards=${TEST_SLURM_SHARDS:-4}

work=$(mktemp -d -t aperture-slurm.XXXXXX)
chmod 755 "$work"
pids=()
teardown() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if ((status != 0)); then
    echo "test-slurm: failed; daemon logs:" >&2
    tail -n 20 "$work"/*.log >&2 2>/dev/null || true
    tail -n 20 "$work"/runs/*/slurm-*.out >&2 2>/dev/null || true
  fi
  if [[ -n "${TEST_SLURM_KEEP:-}" && -d "$work/runs" ]]; then
    mkdir -p "$TEST_SLURM_KEEP" && cp -r "$work/runs/." "$TEST_SLURM_KEEP/"
  fi
  rm -rf "$work"
  exit "$status"
}
trap teardown EXIT

# munge: its own key, socket and files.
mkdir -p "$work/munge"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munged.log" \
  --seed-file="$work/munge/munged.seed" >>"$work/munged.log" 2>&1 &
pids+=($!)

# Two free ports in 20000-29999 (the defaults 6817/6818 may belong to a real Slurm).
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port=$((20000 + RANDOM % 9998))
until port_free "$ctld_port" && port_free $((ctld_port + 1)); do ctld_port=$((20000 + RANDOM % 9998)); done
node_line=$(slurmd -C | head -n 1)  # NodeName=<host> CPUs=... RealMemory=...
host=$(hostname -s)
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<CONF
ClusterName=aperture-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$((ctld_port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
MinJobAge=600
SchedulerParameters=sched_interval=1
$node_line State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"

for ((i = 0; i < 50; ++i)); do [[ -S "$socket" ]] && break; sleep 0.2; done
[[ -S "$socket" ]] || { echo "test-slurm: munged did not start" >&2; exit 1; }
slurmctld -D -c -f "$SLURM_CONF" >>"$work/slurmctld.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >>"$work/slurmd.log" 2>&1 &
pids+=($!)
state=""
for ((i = 0; i < 120; ++i)); do
  state=$(sinfo -h -o %T 2>/dev/null | head -n 1 || true)
  [[ "$state" == idle ]] && break
  sleep 0.5
done
[[ "$state" == idle ]] || { echo "test-slurm: the node did not come up (state '$state')" >&2; exit 1; }
echo "test-slurm: one-node Slurm up on $host (ports $ctld_port, $((ctld_port + 1)))"

# The sharded bench through the script users run, from a submission folder like theirs.
mkdir -p "$work/runs"
start_ms=$(($(date +%s%N) / 1000000))
(cd "$work/runs" && APERTURE="$aperture" "$here/bench.sbatch" sharded "$shards" "${bench_args[@]}")
read -r array_job merge_job <"$work/runs/sharded/slurm-jobs"
for ((i = 0; i < 600; ++i)); do
  [[ -z "$(squeue -h -j "$array_job,$merge_job" 2>/dev/null)" ]] && break
  sleep 0.5
done
sharded_ms=$(($(date +%s%N) / 1000000 - start_ms))
merge_state=$(scontrol show job "$merge_job" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
[[ "$merge_state" == COMPLETED ]] || { echo "test-slurm: merge job $merge_job ended $merge_state" >&2; exit 1; }

start_ms=$(($(date +%s%N) / 1000000))
"$aperture" bench "${bench_args[@]}" --out "$work/runs/whole"
whole_ms=$(($(date +%s%N) / 1000000 - start_ms))

python3 "$here/compare_bench_outputs.py" "$work/runs/whole" "$work/runs/sharded/merged"
costs=$(python3 -c 'import json,sys
m = json.load(open(sys.argv[1]))["cost"]; w = json.load(open(sys.argv[2]))["cost"]
print("sharded: hosts %s, %.2f CPU s/trial; unsharded: %s threads, %.2f CPU s/trial" % (
    sorted({s["host"] for s in m["shards"]}), m["cpu_s_per_trial"], w["threads"], w["cpu_s_per_trial"]))' \
  "$work/runs/sharded/merged/summary.json" "$work/runs/whole/summary.json")
echo "test-slurm: passed: $shards shards on Slurm + merge ($sharded_ms ms wall from submission) equal the unsharded run ($whole_ms ms wall); $costs"
