#!/usr/bin/env bash
# Integration test on a real Slurm (not part of the CI suite; README "Running sweeps on a cluster").
#
# Starts a throw-away single-node Slurm on this machine (munged, slurmctld, slurmd, all configured in
# a temporary folder, nothing under /etc changed), submits scripts/slurm/sweep-array.sbatch as a job
# array over a small sweep, waits for it and for its merge job, and checks that the merged manifest
# is complete and identical to a single-process run of the same sweep (apart from the per-run fields
# listed in PER_RUN_FIELDS below). Then stops the daemons and removes the folder.
#
#   sudo scripts/test-slurm.sh [--shards N] [--trivial] [--keep]
#
#   --shards N   array size (default 3)
#   --trivial    submit an `echo` job array instead of dicsynth: checks the Slurm setup alone
#   --keep       keep the temporary folder (logs, outputs) for inspection
#
# Needs root (it starts the daemons as root and installs Debian's slurm-wlm and munge with apt when
# they are missing) and a built build/dicsynth (DICSYNTH=... to use another binary).
# Container-friendly settings: no cgroups anywhere (proctrack/linuxproc, task/none,
# jobacct_gather/none), no accounting database, no systemd; ports SLURMCTLD_PORT/SLURMD_PORT
# (default 6817/6818) on 127.0.0.1.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
DICSYNTH=${DICSYNTH:-$ROOT/build/dicsynth}
SHARDS=3
TRIVIAL=0
KEEP=0
CTLD_PORT=${SLURMCTLD_PORT:-6817}
SLURMD_PORT=${SLURMD_PORT:-6818}
# The sweep: a small scene, a tiny resolution, a few points.
SCENE=${SCENE:-$ROOT/scenes/rectangle.lua}
# shellcheck disable=SC2206  # SWEEP_ARGS is a list of words
SWEEP_ARGS=(${SWEEP_ARGS:---downscale 8 --spp 1 --precision fp64 --sweep shift=0:0.0006:7})

while (($#)); do
  case "$1" in
    --shards) SHARDS=$2; shift 2 ;;
    --trivial) TRIVIAL=1; shift ;;
    --keep) KEEP=1; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "unknown option $1" >&2; exit 2 ;;
  esac
done

log() { printf '[test-slurm %s] %s\n' "$(date -u +%H:%M:%S)" "$*"; }
fail() { log "FAIL: $*"; exit 1; }

[[ $(id -u) == 0 ]] || fail "run as root (starts munged/slurmctld/slurmd, may apt-get install)"
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
  log "installing slurm-wlm and munge (apt)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null
fi
((TRIVIAL)) || [[ -x $DICSYNTH ]] || fail "$DICSYNTH not built (scripts/build.sh)"

WORK=$(mktemp -d /tmp/dicsynth-slurm.XXXXXX)
chmod 755 "$WORK"   # jobs run as root here, but munged insists on sane directory permissions
cleanup() {
  local rc=$?
  log "stopping daemons"
  local pids=() pidfile pid
  for pidfile in "$WORK"/slurmd.pid "$WORK"/slurmctld.pid "$WORK"/munged.pid; do
    [[ -s $pidfile ]] && pids+=("$(cat "$pidfile")")
  done
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for _ in $(seq 20); do  # up to 10 s for them to exit before their folder goes
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.5
  done
  if ((rc != 0)); then
    for f in "$WORK"/*.log; do [[ -f $f ]] && { echo "---- $f (tail)"; tail -n 20 "$f"; }; done
  fi
  if ((KEEP)); then log "kept $WORK"; else rm -rf "$WORK"; fi
  exit $rc
}
trap cleanup EXIT

# --- munge: own key and socket, so a munged already running on the host is left alone ---------
mkdir -p "$WORK/munge"
chmod 755 "$WORK/munge"  # munged wants its socket's folder searchable by all (the key stays 0400)
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
MUNGE_SOCKET=$WORK/munge/munge.socket
munged --key-file="$WORK/munge/munge.key" --socket="$MUNGE_SOCKET" --pid-file="$WORK/munged.pid" \
  --log-file="$WORK/munged.log" --seed-file="$WORK/munge/seed" --force
munge --socket="$MUNGE_SOCKET" -n | unmunge --socket="$MUNGE_SOCKET" >/dev/null || fail "munge round trip"
log "munged up ($MUNGE_SOCKET)"

# --- slurm.conf ---------------------------------------------------------------------------------
NODE=$(hostname -s)
CPUS=$(nproc)
MEM_MB=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))
mkdir -p "$WORK/state" "$WORK/spool" "$WORK/out"
export SLURM_CONF=$WORK/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=dicsynth-test
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool/slurmd-%n
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
MailProg=/bin/true
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups (a container has none to delegate): Linux process tracking, no task binding.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SchedulerType=sched/backfill
# Finished jobs stay visible to squeue/scontrol for a while (there is no accounting database).
MinJobAge=600
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=test Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
log "slurmctld and slurmd started (node $NODE, $CPUS CPUs, ports $CTLD_PORT/$SLURMD_PORT)"
for _ in $(seq 60); do
  state=$(sinfo -h -n "$NODE" -o %t 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 1
done
[[ $state == idle ]] || fail "node $NODE not idle after 60 s (state: '${state:-none}')"
log "node $NODE idle"

# Waits for job $1 (and all its array tasks) to leave the queue; prints each task's final state.
wait_job() {
  local job=$1 deadline=$((SECONDS + ${2:-900}))
  while squeue -h -j "$job" -t PD,R,CG,CF 2>/dev/null | grep -q .; do
    ((SECONDS < deadline)) || fail "job $job still running after ${2:-900} s"
    sleep 2
  done
  scontrol -o show job "$job" | while read -r line; do
    echo "  $(grep -oE '\b(JobId|ArrayTaskId|JobName|JobState|ExitCode|RunTime)=[^ ]+' <<<"$line" | tr '\n' ' ')"
  done
}

# Fails unless every task of job $1 COMPLETED with exit code 0.
check_job_ok() {
  local bad
  bad=$(scontrol -o show job "$1" | grep -v 'JobState=COMPLETED' || true)
  [[ -z $bad ]] || fail "job $1: not every task completed: $bad"
}

if ((TRIVIAL)); then
  # shellcheck disable=SC2016  # expanded by the job, not here
  job=$(sbatch --parsable --array=0-$((SHARDS - 1)) --output="$WORK/out/echo-%A_%a.out" \
    --wrap 'echo "task $SLURM_ARRAY_TASK_ID of $SLURM_ARRAY_TASK_COUNT (min $SLURM_ARRAY_TASK_MIN) on $(hostname)"')
  log "submitted echo array $job"
  wait_job "$job" 120
  check_job_ok "$job"
  for i in $(seq 0 $((SHARDS - 1))); do
    grep -q "task $i of $SHARDS (min 0)" "$WORK/out/echo-${job}_$i.out" || fail "task $i output"
  done
  cat "$WORK"/out/echo-*.out
  log "PASS: echo job array of $SHARDS tasks ran on the single-node Slurm"
  exit 0
fi

# --- the sweep as a job array, then its merge job --------------------------------------------
unset SLURM_ARRAY_TASK_ID SLURM_ARRAY_TASK_COUNT SLURM_ARRAY_TASK_MIN  # this shell is no array task
export DICSYNTH  # the jobs inherit the environment (sbatch --export=ALL)
SLURM_OUT=$WORK/slurm-run
read -r array merge < <("$ROOT/scripts/slurm/submit-sweep.sh" "$SHARDS" "$SCENE" "$SLURM_OUT" "${SWEEP_ARGS[@]}")
log "submitted array job $array ($SHARDS tasks) and merge job $merge (afterok)"
t0=$SECONDS
wait_job "$array" 1200
check_job_ok "$array"
wait_job "$merge" 300
check_job_ok "$merge"
log "array and merge jobs completed in $((SECONDS - t0)) s"
for i in $(seq 0 $((SHARDS - 1))); do
  grep -q "task $i of $SHARDS" "$SLURM_OUT/slurm/sweep-${array}_$i.out" || fail "task $i did not run as shard $i"
done
grep -h '^sweep:' "$SLURM_OUT"/slurm/sweep-*.out | sed 's/^/  /'
sed 's/^/  merge: /' "$SLURM_OUT/slurm/merge-$merge.out"

# --- the same sweep in one process ------------------------------------------------------------
SINGLE_OUT=$WORK/single-run
t0=$SECONDS
"$DICSYNTH" sweep "$SCENE" -o "$SINGLE_OUT" "${SWEEP_ARGS[@]}" >"$WORK/single.log" 2>&1 || {
  cat "$WORK/single.log"; fail "single-process sweep"; }
log "single-process sweep done in $((SECONDS - t0)) s"

# --- identical manifests (apart from the per-run render_seconds) and identical files ---------
# Python's csv and json modules read both manifests; the per-run field render_seconds is dropped.
compare_manifests() {
  python3 - "$1" "$2" <<'PY'
import csv, json, sys
a, b = sys.argv[1], sys.argv[2]
def rows(d):
    with open(d + "/manifest.csv", newline="") as f:
        return [{k: v for k, v in r.items() if k != "render_seconds"} for r in csv.DictReader(f)]
def doc(d):
    with open(d + "/manifest.json") as f:
        j = json.load(f)
    for p in j["points"]:
        p.pop("render_seconds")
    return j
ra, rb = rows(a), rows(b)
if ra != rb:
    sys.exit("manifest.csv differs:\n%s\n%s" % (ra, rb))
ja, jb = doc(a), doc(b)
if ja != jb:
    sys.exit("manifest.json differs:\n%s\n%s" % (ja, jb))
if ja["points_complete"] != ja["points_total"] or len(ja["points"]) != ja["points_total"]:
    sys.exit("manifest.json incomplete: %d of %d" % (ja["points_complete"], ja["points_total"]))
if [int(r["index"]) for r in ra] != list(range(ja["points_total"])):
    sys.exit("manifest.csv: indices not 0..%d" % (ja["points_total"] - 1))
for p in ja["points"]:
    for f in p["files"]:
        print(f)
PY
}
expected=$("$DICSYNTH" sweep "$SCENE" -o "$WORK/list" "${SWEEP_ARGS[@]}" --list | grep -c '^[0-9]' || true)
rows=$(($(wc -l <"$SLURM_OUT/manifest.csv") - 1))
log "points listed by --list: $expected; manifest.csv rows of the Slurm run: $rows"
((expected > 0 && rows == expected)) || fail "manifest incomplete"
listed=$(compare_manifests "$SLURM_OUT" "$SINGLE_OUT") || fail "manifests differ (above)"
# Every file the manifest lists, byte for byte (same device, precision and seeds: same images).
files=0
for f in $listed; do
  cmp -s "$SLURM_OUT/$f" "$SINGLE_OUT/$f" || fail "$f differs between the Slurm and the single-process run"
  files=$((files + 1))
done
((files > 0)) || fail "no files listed in the manifest"
log "manifest.csv and manifest.json identical apart from render_seconds; $files files identical byte for byte"

# --- a lost point: the merge job fails, resubmitting the array renders only that point ----------
lost=$(printf "point_%05d" $((expected - 1)))  # the last point
rm -rf "${SLURM_OUT:?}/$lost"
merge=$(sbatch --parsable --output="$SLURM_OUT/slurm/merge-%j.out" "$ROOT/scripts/slurm/sweep-merge.sbatch" \
  "$SCENE" "$SLURM_OUT" "${SWEEP_ARGS[@]}")
wait_job "$merge" 300
scontrol -o show job "$merge" | grep -q 'JobState=FAILED' || fail "the merge job did not fail with $lost missing"
grep -q "1 of $expected points missing" "$SLURM_OUT/slurm/merge-$merge.out" || fail "merge log does not name the gap"
log "with $lost removed the merge job failed: $(grep missing "$SLURM_OUT/slurm/merge-$merge.out")"
# Resubmitted by hand (README's sbatch commands), as an array numbered from 1: the shards then come
# from SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN.
array=$(sbatch --parsable --array="1-$SHARDS" --output="$SLURM_OUT/slurm/sweep-%A_%a.out" \
  "$ROOT/scripts/slurm/sweep-array.sbatch" "$SCENE" "$SLURM_OUT" "${SWEEP_ARGS[@]}")
merge=$(sbatch --parsable --dependency="afterok:$array" --output="$SLURM_OUT/slurm/merge-%j.out" \
  "$ROOT/scripts/slurm/sweep-merge.sbatch" "$SCENE" "$SLURM_OUT" "${SWEEP_ARGS[@]}")
wait_job "$array" 1200
check_job_ok "$array"
wait_job "$merge" 300
check_job_ok "$merge"
grep -q "SLURM_ARRAY_TASK_MIN=1" "$SLURM_OUT/slurm/sweep-${array}_1.out" || fail "array 1-$SHARDS: task 1's log"
rendered=$(grep -h '^sweep:' "$SLURM_OUT"/slurm/sweep-"${array}"_*.out | grep -oE 'rendered [0-9]+' | awk '{ s += $2 } END { print s }')
((rendered == 1)) || fail "the resubmitted array rendered $rendered points, expected only the lost one"
compare_manifests "$SLURM_OUT" "$SINGLE_OUT" >/dev/null || fail "manifests differ after the resubmission"
cmp -s "$SLURM_OUT/$lost/camera.tif" "$SINGLE_OUT/$lost/camera.tif" || fail "$lost re-rendered differently"
log "resubmitted array (--array=1-$SHARDS) rendered only $lost (1 point); manifest complete and identical again"
log "PASS: $expected points in $SHARDS shards on a single-node Slurm ($(sinfo -V)), merged manifest complete"
