#!/usr/bin/env bash
# tools/slurm/mpm_lig.sbatch under a real Slurm: a one-node cluster on this machine (munged,
# slurmctld and slurmd on 127.0.0.1, configuration, key, state and logs in WORK_DIR/cluster),
# the batch script submitted as a user would, and its promises checked:
#   1. the end of the allocation (the job's time limit shortened with scontrol, so that the
#      --signal=TERM@300 of the script fires at slurmctld's next time-limit check, at most 30 s
#      later) stops mpm_lig with exit 4 and a checkpoint, and the script requeues the job;
#   2. the requeued job resumes from that checkpoint and completes (exit 0, summary.json), its
#      history.csv and results.h5 bit-identical to an uninterrupted run of the same case
#      (tools/compare_outputs.py --results-only);
#   3. a run that fails (an engine error injected with MPM_LIG_FAULT_POINT) is not requeued.
# The case: CASE.json asked for far more steps than it can make before the signal (at 200 DEM
# sub-steps per update), with checkpoints every 20 steps; once it has stopped, its end is set to 150 steps after the stop
# (`end` is a key a resume may change, tests/coupling/sigterm_checkpoint.sh) and its time limit
# put back to 30 minutes while Slurm holds the requeued job (BeginTime: AuthInfo's cred_expire
# + 1 s, 21 s here against Slurm's default 121 s; released at once, slurmd refuses to start it:
# "Job credential revoked").
# Slurm and munge are installed with tools/install_deps.sh slurm when missing; where they cannot
# be installed or the daemons cannot start, the test is skipped (exit 77) with the reason. The
# daemons are stopped on every exit path, a killed test included (a watchdog outlives it).
# usage: sbatch_requeue.sh MPM_LIG CASE.json WORK_DIR LAUNCHER...   (LAUNCHER: the reference run's)
#        sbatch_requeue.sh --stop CLUSTER_DIR [PID]   (stop that cluster, after PID has ended)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$here/../.." && pwd)

# The cluster's daemons, by their pid files: jobs cancelled first, then slurmd, slurmctld, munged.
stop_cluster() {
  local cl=$1 name pid tries
  [[ -f $cl/slurm.conf ]] || return 0
  export SLURM_CONF=$cl/slurm.conf
  if [[ -f $cl/slurmctld.pid ]] && kill -0 "$(cat "$cl/slurmctld.pid")" 2>/dev/null; then
    scancel --quiet --full --user="$(id -un)" 2>/dev/null || true
    for tries in $(seq 30); do
      [[ -z $(squeue -h -o %i 2>/dev/null) ]] && break
      sleep 1
    done
  fi
  for name in slurmd slurmctld munged; do
    [[ -f $cl/$name.pid ]] || continue
    pid=$(cat "$cl/$name.pid")
    rm -f "$cl/$name.pid"
    # Only that daemon: a pid file left behind may name another process by now.
    [[ $(cat "/proc/$pid/comm" 2>/dev/null) == "$name" ]] || continue
    kill "$pid" 2>/dev/null || continue
    for tries in $(seq 50); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.2
    done
    kill -9 "$pid" 2>/dev/null || true
  done
}

if [[ ${1:-} == --stop ]]; then
  if [[ -n ${3:-} ]]; then
    while kill -0 "$3" 2>/dev/null; do sleep 2; done
  fi
  stop_cluster "$2"
  exit 0
fi

exe=$1 case=$2 work=$3
shift 3
launcher=("$@")
skip() { echo "SKIPPED: $*"; exit 77; }
cl=$work/cluster

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null ||
  ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  if [[ $(id -u) -ne 0 ]] && ! sudo -n true 2>/dev/null; then
    skip "Slurm is not installed and this user cannot install it (bash tools/install_deps.sh slurm)"
  fi
  bash "$source_dir/tools/install_deps.sh" slurm ||
    skip "Slurm and munge could not be installed (bash tools/install_deps.sh slurm failed)"
fi
[[ $(id -u) -eq 0 ]] || skip "slurmd must run as root to start the jobs"

rm -rf "$work"
mkdir -p "$cl/state" "$cl/spool" "$cl/munge"
chmod 700 "$cl/munge"
# A killed test (CTest's timeout) must not leave the daemons behind: the watchdog waits for this
# script to end and stops them (a clean exit stops them first).
setsid -f "$0" --stop "$cl" $$ >/dev/null 2>&1 < /dev/null
trap 'kill ${reference:-} 2>/dev/null || true; stop_cluster "$cl"' EXIT
trap 'exit 1' INT TERM HUP

# munge: its own key and socket (a socket path must stay under 108 characters).
sock_dir=$cl/munge
if ((${#sock_dir} > 90)); then
  sock_dir=$(mktemp -d /tmp/mpm_lig_munge.XXXXXX)
fi
mungekey --create --keyfile="$cl/munge/munge.key"
munged --force --key-file="$cl/munge/munge.key" --socket="$sock_dir/munge.socket" \
  --pid-file="$cl/munged.pid" --log-file="$cl/munged.log" --seed-file="$cl/munge/seed" ||
  skip "munged did not start: $(tail -n 3 "$cl/munged.log" 2>/dev/null)"

read -r ctl_port node_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s:
    x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
# One node of 4 CPUs whatever the machine has (config_overrides): the test's two jobs of two
# tasks fit side by side. No cgroups: processes are tracked through /proc (proctrack/linuxproc).
cat > "$cl/slurm.conf" <<EOF
ClusterName=mpmlig
SlurmctldHost=$(hostname -s)(127.0.0.1)
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
SlurmctldPort=$ctl_port
SlurmdPort=$node_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock_dir/munge.socket,cred_expire=20
StateSaveLocation=$cl/state
SlurmdSpoolDir=$cl/spool
SlurmctldPidFile=$cl/slurmctld.pid
SlurmdPidFile=$cl/slurmd.pid
SlurmctldLogFile=$cl/slurmctld.log
SlurmdLogFile=$cl/slurmd.log
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
KillWait=10
MinJobAge=3600
NodeName=mpmlig0 NodeAddr=127.0.0.1 CPUs=4 RealMemory=2000 State=UNKNOWN
PartitionName=local Nodes=mpmlig0 Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$cl/slurm.conf
slurmctld -i || skip "slurmctld did not start: $(tail -n 5 "$cl/slurmctld.log" 2>/dev/null)"
slurmd -N mpmlig0 || skip "slurmd did not start: $(tail -n 5 "$cl/slurmd.log" 2>/dev/null)"
for tries in $(seq 60); do
  [[ $(sinfo -h -o %T 2>/dev/null) == idle ]] && break
  sleep 1
done
[[ $(sinfo -h -o %T 2>/dev/null) == idle ]] ||
  skip "the Slurm node did not come up: $(sinfo -h 2>&1); $(tail -n 5 "$cl/slurmd.log")"
echo "cluster up: slurmctld on 127.0.0.1:$ctl_port, slurmd on 127.0.0.1:$node_port"

fail() {
  echo "FAILED: $*"
  for f in "$work"/*.out; do
    [[ -f $f ]] && { echo "--- $f"; tail -n 40 "$f"; }
  done
  exit 1
}
# job_field JOB KEY: one field of `scontrol show job` (JobState, Restarts, ExitCode, ...).
job_field() {
  scontrol -o show job "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"
}
# wait_for SECONDS WHAT COMMAND...: poll until COMMAND succeeds.
wait_for() {
  local limit=$1 what=$2 t
  shift 2
  for ((t = 0; t < limit * 2; t++)); do
    "$@" && return 0
    sleep 0.5
  done
  fail "$what (not within $limit s)"
}

/usr/bin/python3 - "$case" "$work/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 100000}
c.setdefault("output", {}).update({"every": 20, "checkpoint_every": 20})
# As given, its points leave the mesh after about 2300 steps, which a loaded machine reached
# before slurmctld's time-limit check sent the signal. Loaded 20 times slower and stepped at 200
# DEM sub-steps (each step about 7 times the cost), it runs for minutes before that can happen.
c["materials"][0]["rve"]["substeps"] = {"fixed": 200}
for bc in c["boundary_conditions"]:
    if bc["type"] == "velocity":
        bc["velocity"] *= 0.05
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
submit() {  # submit OUTPUT_DIR [ENV=VALUE]: the batch script on 2 tasks, its log WORK_DIR/NAME.out
  local out=$1 export=ALL
  [[ -n ${2:-} ]] && export=ALL,$2
  (cd "$work" && MPM_LIG=$exe sbatch --parsable --nodes=1 --ntasks=2 --ntasks-per-node=2 \
    --time=30 --export="$export" --output="$work/$(basename "$out").out" \
    "$source_dir/tools/slurm/mpm_lig.sbatch" "$work/case.json" "$out")
}
job=$(submit "$work/run")
failing=$(submit "$work/failing" MPM_LIG_FAULT_POINT=1)
echo "submitted job $job (the run) and job $failing (an engine failure at point 1)"

# 1. The end of the allocation: once the run steps, its time limit is cut to 5 minutes from now
# or less, inside the 300 s of --signal=TERM@300.
history_rows() {
  [[ $(job_field "$job" JobState) =~ ^(PENDING|RUNNING)$ ]] ||
    fail "the job ended before it stepped: $(job_field "$job" JobState) $(job_field "$job" ExitCode)"
  [[ -f $work/run/history.csv ]] && (($(wc -l < "$work/run/history.csv") >= 5))
}
wait_for 180 "the run made no progress" history_rows
elapsed=$(job_field "$job" RunTime)
IFS=: read -r h m s <<< "$elapsed"
scontrol update JobId="$job" TimeLimit=$((10#$h * 60 + 10#$m + 5))
echo "run stepping after $elapsed: time limit cut to $(job_field "$job" TimeLimit)"
requeued() { [[ $(job_field "$job" JobState) == PENDING && $(job_field "$job" Restarts) == 1 ]]; }
wait_for 120 "the job was not requeued" requeued
grep -q "stopped by a signal after step" "$work/run.out" || fail "no stop message from mpm_lig"
grep -q "starting 2 ranks: srun --mpi=pmix" "$work/run.out" ||
  fail "the batch script did not pick srun --mpi=pmix (offered: $(srun --mpi=list 2>&1 | tr '\n' ' '))"
grep -q "mpm_lig stopped (exit 4) before the end: requeueing" "$work/run.out" ||
  fail "the batch script did not see exit 4"
[[ -f $work/run/summary.json ]] && fail "the stopped run wrote summary.json"
latest=$(cat "$work/run/checkpoints/latest") || fail "no checkpoint"
stop=${latest#step_}
rows=$(($(wc -l < "$work/run/history.csv") - 1))
((rows == stop + 1)) || fail "history.csv has $rows rows, the checkpoint is at step $stop"
echo "allocation 1: exit 4 after step $stop, checkpoint $latest, job requeued"

# 2. Resume and completion, then the uninterrupted run of the same case.
end=$((stop + 150))
/usr/bin/python3 - "$work/case.json" "$end" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": int(sys.argv[2])}
json.dump(c, open(sys.argv[1], "w"), indent=1)
PY
scontrol update JobId="$job" TimeLimit=30
[[ $(job_field "$job" JobState) == PENDING ]] ||
  fail "the requeued job started before its time limit was put back"
# The uninterrupted run meanwhile (the requeued job waits for its BeginTime).
"${launcher[@]}" "$exe" "$work/case.json" --output "$work/uninterrupted" \
  > "$work/uninterrupted.log" 2>&1 &
reference=$!
finished() { [[ $(job_field "$1" JobState) =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT)$ ]]; }
wait_for 300 "the requeued job did not finish" finished "$job"
[[ $(job_field "$job" JobState) == COMPLETED && $(job_field "$job" ExitCode) == 0:0 ]] ||
  fail "the requeued job ended $(job_field "$job" JobState) $(job_field "$job" ExitCode)"
grep -q "resuming from $work/run/checkpoints/$latest" "$work/run.out" ||
  fail "the requeued job did not resume from $latest"
[[ -f $work/run/summary.json ]] || fail "no summary.json after the requeued job"
echo "allocation 2: resumed from $latest, completed to step $end (exit 0)"
wait "$reference" || fail "the uninterrupted run failed: $(tail -n 5 "$work/uninterrupted.log")"
/usr/bin/python3 "$source_dir/tools/compare_outputs.py" --results-only "$work/uninterrupted" "$work/run" ||
  fail "the requeued run differs from the uninterrupted one"

# 3. The failed run: exit 3, not requeued.
wait_for 120 "the failing job did not end" finished "$failing"
[[ $(job_field "$failing" JobState) == FAILED && $(job_field "$failing" ExitCode) == 3:0 &&
  $(job_field "$failing" Restarts) == 0 ]] ||
  fail "the failing job: $(job_field "$failing" JobState) $(job_field "$failing" ExitCode), \
restarts $(job_field "$failing" Restarts)"
grep -q "not requeued" "$work/failing.out" || fail "the batch script did not say 'not requeued'"
echo "failing job: exit 3, not requeued"
