#!/usr/bin/env bash
# The Slurm test (ctest label `slurm`): a real Slurm on this machine, without systemd: munged,
# slurmctld and two slurmd virtual nodes (n1, n2) on 127.0.0.1, all started here as background
# processes and stopped by pid. A manifest of three stills is submitted as a job array through
# deploy/slurm/batch.sbatch; the two good tasks must give the bytes of `discreel render`, the
# third fails (its scene is missing), and after the scene appears `scontrol requeue` reruns it.
# Then one clip goes through deploy/slurm/clip.sh: five segment tasks spread over both nodes and
# a gather job after them; the joined clip must be `discreel render`'s bytes.
#
#   slurm_test.sh SOURCE_DIR WORK_DIR DISCREEL
set -euo pipefail
[[ $# -eq 3 ]] || { echo "usage: $0 SOURCE_DIR WORK_DIR DISCREEL" >&2; exit 2; }
readonly SOURCE_DIR="$1" WORK="$2" DISCREEL="$3"
MUNGE_DIR=""   # made below

fail() {
  echo "slurm test FAILED: $*" >&2
  for log in "$WORK"/log/*.log "$WORK"/log/*.out "$MUNGE_DIR"/munged.log; do
    [[ -f $log ]] && { echo "----- $log" >&2; tail -n 20 "$log" >&2; }
  done
  exit 1
}
for tool in munged slurmctld slurmd sbatch scontrol squeue runuser; do
  command -v "$tool" >/dev/null ||
    fail "$tool is missing: run 'bash setup.sh test' to install slurm-wlm and munge, or skip this test with: ctest -LE slurm"
done
[[ $EUID -eq 0 ]] || fail "needs root (slurmd runs jobs as their user); skip it with: ctest -LE slurm"

rm -rf "$WORK"
mkdir -p "$WORK"/{state,spool,log,out,scenes}
# munged runs as munge, which may not reach into WORK (a checkout under a 0700 directory, such
# as mktemp -d's): its key, socket and logs live in a directory of their own under /tmp.
MUNGE_DIR="$(mktemp -d /tmp/discreel-munge-XXXXXX)"
readonly MUNGE_DIR
chown munge:munge "$MUNGE_DIR"
chmod 711 "$MUNGE_DIR"
pids=()
stop_all() {
  scontrol shutdown >/dev/null 2>&1 || true
  local pid
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  # munged writes its seed file as it exits: the directory goes once it has.
  if [[ -f $MUNGE_DIR/munged.pid ]]; then
    pid=$(cat "$MUNGE_DIR/munged.pid")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  fi
  if [[ -n $MUNGE_DIR ]]; then
    rm -rf "$MUNGE_DIR" 2>/dev/null || { sleep 0.5; rm -rf "$MUNGE_DIR"; }
  fi
}
trap stop_all EXIT

# Ports from this process's id, so that two runs on one machine do not meet.
readonly BASE=$((20000 + ($$ % 2000) * 4))
readonly SOCKET="$MUNGE_DIR/munge.socket"
runuser -u munge -- sh -c "dd if=/dev/urandom of='$MUNGE_DIR/munge.key' bs=1024 count=1 2>/dev/null && chmod 400 '$MUNGE_DIR/munge.key'"
runuser -u munge -- munged --key-file="$MUNGE_DIR/munge.key" --socket="$SOCKET" \
  --pid-file="$MUNGE_DIR/munged.pid" --log-file="$MUNGE_DIR/munged.log" \
  --seed-file="$MUNGE_DIR/munged.seed"
cat >"$WORK/slurm.conf" <<CONF
ClusterName=discreel
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$BASE
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$SOCKET
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool/%n
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd-%n.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=600
NodeName=n[1-2] NodeAddr=127.0.0.1 Port=$((BASE + 1))-$((BASE + 2)) CPUs=1 State=UNKNOWN
PartitionName=debug Nodes=n[1-2] Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$WORK/slurm.conf"
slurmctld -D -i >"$WORK/log/slurmctld.out" 2>&1 &
pids+=($!)
for node in n1 n2; do
  slurmd -D -N "$node" >"$WORK/log/slurmd-$node.out" 2>&1 &
  pids+=($!)
done
for _ in $(seq 100); do
  [[ $(sinfo -h -o '%T' 2>/dev/null | grep -c idle) -ge 1 ]] && \
    [[ $(sinfo -h -N -o '%N %T' 2>/dev/null | grep -c idle) -eq 2 ]] && break
  sleep 0.2
done
[[ $(sinfo -h -N -o '%N %T' | grep -c idle) -eq 2 ]] || fail "the two nodes did not come up: $(sinfo -N 2>&1)"

scene="$SOURCE_DIR/tests/data/scenes/short.yaml"
cat >"$WORK/renders.txt" <<MANIFEST
# three stills; the third scene appears only after its task has failed
$scene -o $WORK/out/a.png --frame 3
$scene -o $WORK/out/b.png --size 64x36
$WORK/scenes/late.yaml -o $WORK/out/c.png
MANIFEST

# wait_done JOB: until no task of JOB is pending or running (bounded).
wait_done() {
  for _ in $(seq 300); do
    [[ -z $(squeue -h -j "$1" -t PENDING,RUNNING,CONFIGURING,COMPLETING 2>/dev/null) ]] && return 0
    sleep 0.2
  done
  fail "job $1 did not finish within 60 s: $(squeue -j "$1" 2>&1)"
}
state_of() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }

export DISCREEL   # batch.sbatch runs it; sbatch passes the environment on
job="$(cd "$WORK/out" && sbatch --parsable --array=0-2 \
  "$SOURCE_DIR/deploy/slurm/batch.sbatch" "$WORK/renders.txt")"
echo "submitted array $job"
wait_done "$job"
for task in 0 1; do
  [[ $(state_of "${job}_$task") == COMPLETED ]] || fail "task $task ended $(state_of "${job}_$task")"
done
[[ $(state_of "${job}_2") == FAILED ]] || fail "task 2 ended $(state_of "${job}_2"), expected FAILED"
"$DISCREEL" render "$scene" -o "$WORK/a.png" --frame 3 -q
"$DISCREEL" render "$scene" -o "$WORK/b.png" --size 64x36 -q
cmp "$WORK/a.png" "$WORK/out/a.png" || fail "task 0's still differs from discreel render's"
cmp "$WORK/b.png" "$WORK/out/b.png" || fail "task 1's still differs from discreel render's"

cp "$scene" "$WORK/scenes/late.yaml"
scontrol requeue "${job}_2"
# A requeued job waits (BeginTime) before it may start again; let it start now.
scontrol update JobId="${job}_2" StartTime=now
wait_done "$job"
[[ $(state_of "${job}_2") == COMPLETED ]] || fail "the requeued task ended $(state_of "${job}_2")"
cmp "$WORK/b.png" "$WORK/out/b.png" >/dev/null
"$DISCREEL" render "$scene" -o "$WORK/c.png" -q
cmp "$WORK/c.png" "$WORK/out/c.png" || fail "the requeued task's still differs"

# One clip as segments on both nodes, then the gather job (deploy/slurm/clip.sh): the same
# bytes as one render on this machine.
cat >"$WORK/scenes/clip.yaml" <<SCENE
$(sed 's/^  duration: 1.25$/  duration: 1.25\n  segment: 0.25/' "$scene")
SCENE
grep -q 'segment: 0.25' "$WORK/scenes/clip.yaml" || fail "the clip scene has no segment length"
read -r array gather < <(cd "$WORK/out" && "$SOURCE_DIR/deploy/slurm/clip.sh" \
  "$WORK/scenes/clip.yaml" "$WORK/out/clip.mp4" --crf 30)
echo "submitted segments $array and gather $gather"
wait_done "$array"
wait_done "$gather"
for task in 0 1 2 3 4; do
  [[ $(state_of "${array}_$task") == COMPLETED ]] || fail "segment task $task ended $(state_of "${array}_$task")"
done
[[ $(state_of "$gather") == COMPLETED ]] || fail "the gather job ended $(state_of "$gather")"
"$DISCREEL" render "$WORK/scenes/clip.yaml" -o "$WORK/clip.mp4" --crf 30 -q
cmp "$WORK/clip.mp4" "$WORK/out/clip.mp4" || fail "the gathered clip differs from discreel render's"
echo "slurm test passed: array $job, segments $array, gather $gather on $(sinfo -h -N -o '%N' | sort -u | tr '\n' ' ')"
