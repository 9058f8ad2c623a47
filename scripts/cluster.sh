#!/usr/bin/env bash
# The Slurm test phase (docs/cluster.md): starts a single-node Slurm cluster of its own in a
# scratch folder (munged, slurmctld and slurmd on 127.0.0.1, nothing in /etc or systemd), runs
# the job scripts of deploy/slurm/ as array jobs and checks, byte for byte, that
#   1. a probe grid captured in 4 array tasks and merged equals the grid captured in one process;
#   2. a batch of bakes in 4 array tasks equals the batch baked in one process;
#   3. with one task failed (the scripts' IBL_FAIL_TASK hook), `ibl probe --merge` fails naming
#      the probes that task owed; resubmitting that task alone completes the same grid.
# Ends with `cluster: N passed, M failed` and exits non-zero on a failure. Needs root (the
# daemons run as root), the Debian packages slurm-wlm and munge, and a built ibl
# (IBL_BUILD, default build/). IBL_CLUSTER_KEEP=1 keeps the scratch folder. Every sbatch --wait
# and ibl run is bounded (IBL_CLUSTER_STEP_TIMEOUT, default 300 s) and so is the whole phase
# (IBL_CLUSTER_TIMEOUT, default 540 s); SIGINT and SIGTERM exit 130 and 143 after the cleanup.
set -uo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${IBL_BUILD:-$repo/build}" && pwd)"
start=$SECONDS
passed=0
failed=0
step_timeout=${IBL_CLUSTER_STEP_TIMEOUT:-300}
phase_timeout=${IBL_CLUSTER_TIMEOUT:-540}

if [ "$(id -u)" -ne 0 ]; then
  echo "cluster: needs root (slurmd and slurmctld run as root here)" >&2
  exit 1
fi
for tool in munged slurmctld slurmd sbatch sinfo squeue scancel scontrol timeout; do
  command -v "$tool" >/dev/null || { echo "cluster: $tool is missing (apt-get install slurm-wlm munge)" >&2; exit 1; }
done
[ -x "$build/ibl" ] || { echo "cluster: $build/ibl is missing: build first" >&2; exit 1; }

scratch="$(mktemp -d /tmp/ibl-cluster.XXXXXX)"
# munged wants every directory above its socket searchable by all.
chmod 711 "$scratch"
mkdir -p "$scratch/munge" "$scratch/state" "$scratch/spool" "$scratch/logs" "$scratch/work"
chmod 755 "$scratch/munge"

daemons=()  # pids, in start order
step=        # the pid of the bounded step running now (see bounded)
watchdog=
stop_cluster() {
  local status=$?
  trap - EXIT INT TERM
  cd /  # from here on, a process whose cwd is under $scratch is a leftover of a job
  [ -n "$watchdog" ] && kill -TERM "$watchdog" 2>/dev/null
  [ -n "$step" ] && kill -TERM -- "-$step" 2>/dev/null  # timeout leads its own process group
  local i pid pids=() d left
  if [ -f "$scratch/slurm.conf" ] && ((${#daemons[@]} > 1)); then
    # Jobs first (their steps are not children of slurmd), then the daemons, last started first.
    # scancel only asks: wait (10 s at most) until the queue is empty, then kill what is left of
    # the jobs: the processes slurmd still tracks and any other whose cwd is in the scratch folder.
    export SLURM_CONF="$scratch/slurm.conf"
    timeout 10 scancel --quiet --user=root 2>/dev/null || true
    for _ in $(seq 20); do
      [ -z "$(timeout 5 squeue -h 2>/dev/null)" ] && break
      sleep 0.5
    done
    pids=($(timeout 5 scontrol listpids 2>/dev/null | awk 'NR > 1 && $1 ~ /^[0-9]+$/ { print $1 }'))
  fi
  for d in /proc/[0-9]*; do
    [[ "$(readlink "$d/cwd" 2>/dev/null)" == "$scratch"/* ]] && pids+=("${d#/proc/}")
  done
  left=()
  for pid in "${pids[@]}"; do
    [[ $pid == "$$" || " ${daemons[*]} " == *" $pid "* ]] && continue
    kill -TERM "$pid" 2>/dev/null && left+=("$pid")
  done
  if ((${#left[@]})); then
    echo "cluster: killing leftover job processes: ${left[*]}" >&2
    for _ in $(seq 20); do
      kill -0 "${left[@]}" 2>/dev/null || break
      sleep 0.1
    done
    kill -KILL "${left[@]}" 2>/dev/null || true
  fi
  for ((i = ${#daemons[@]} - 1; i >= 0; i--)); do
    pid=${daemons[i]}
    kill -TERM "$pid" 2>/dev/null || continue
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  if [ "${IBL_CLUSTER_KEEP:-0}" = 1 ]; then
    echo "cluster: kept $scratch" >&2
  else
    rm -rf "$scratch"
  fi
  exit "$status"
}
interrupted() {  # interrupted SIGNAL STATUS
  echo "cluster: stopped by $1" >&2
  echo "cluster: $passed passed, $((failed + 1)) failed"
  exit "$2"
}
trap stop_cluster EXIT
trap 'interrupted SIGINT 130' INT
trap 'interrupted SIGTERM 143' TERM
# The whole phase is bounded: past $phase_timeout s, the watchdog stops it as SIGTERM would.
(
  trap 'kill "$sleeper" 2>/dev/null; exit 0' TERM
  sleep "$phase_timeout" &
  sleeper=$!
  wait "$sleeper"
  echo "cluster: the phase ran past $phase_timeout s (IBL_CLUSTER_TIMEOUT): stopping it" >&2
  kill -TERM $$
) &
watchdog=$!

print_logs() {
  local f
  for f in "$scratch"/*.log "$scratch"/logs/*; do
    [ -f "$f" ] || continue
    echo "---- $f (last 30 lines)" >&2
    tail -n 30 "$f" >&2
  done
}
die() {
  echo "cluster: $*" >&2
  print_logs
  echo "cluster: $passed passed, $((failed + 1)) failed"
  exit 1
}
# bounded COMMAND...: runs COMMAND under timeout ($step_timeout s, then SIGKILL 10 s later), in
# the background so that a SIGINT or SIGTERM to this script is handled at once (bash runs a trap
# only once the foreground command returns) and the cleanup can kill it.
bounded() {
  local status
  timeout --kill-after=10 "$step_timeout" "$@" &
  step=$!
  wait "$step"
  status=$?
  step=
  if [ "$status" = 124 ] || [ "$status" = 137 ]; then
    echo "cluster: timed out after $step_timeout s (IBL_CLUSTER_STEP_TIMEOUT): $*" >&2
  fi
  return "$status"
}

# Two free ports on 127.0.0.1 (nothing answers a connection to them).
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port=16817
while ! port_free "$ctld_port" || ! port_free "$((ctld_port + 1))"; do
  ctld_port=$((ctld_port + 2))
  ((ctld_port < 16917)) || die "no two free ports from 16817 to 16917"
done
d_port=$((ctld_port + 1))

# munge: a key of our own, a daemon with its own socket.
if command -v mungekey >/dev/null; then
  mungekey --create --keyfile="$scratch/munge/munge.key"
else
  dd if=/dev/urandom of="$scratch/munge/munge.key" bs=1024 count=1 status=none
fi
chmod 600 "$scratch/munge/munge.key"
socket="$scratch/munge/munge.socket"
munged --foreground --socket="$socket" --key-file="$scratch/munge/munge.key" \
  --pid-file="$scratch/munge/munged.pid" --log-file="$scratch/munged.log" \
  --seed-file="$scratch/munge/munged.seed" >>"$scratch/munged.out.log" 2>&1 &
daemons+=($!)
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || die "munged did not create $socket"

# Slurm: one node, this machine, as localhost; its CPUs and memory as slurmd sees them.
node="$(slurmd -C | head -n 1 | sed -E 's/^NodeName=[^ ]+/NodeName=localhost NodeAddr=127.0.0.1/')"
cat >"$scratch/slurm.conf" <<EOF
ClusterName=ibltest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/slurmctld.log
SlurmdLogFile=$scratch/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
MpiDefault=none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
# sbatch --wait polls the job 2, 10 and 42 s after the submission, then every 32 s, and reads its
# exit status then; a job record purged before that poll (MinJobAge after the job ends) makes
# sbatch print "no longer found" and exit 0, whatever the job's status. 30 s leaves margin.
MinJobAge=30
$node State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$scratch/slurm.conf"
slurmctld -D -f "$SLURM_CONF" >>"$scratch/slurmctld.out.log" 2>&1 &
daemons+=($!)
slurmd -D -f "$SLURM_CONF" -N localhost >>"$scratch/slurmd.out.log" 2>&1 &
daemons+=($!)
for _ in $(seq 60); do
  [ "$(sinfo -h -n localhost -o %t 2>/dev/null)" = idle ] && break
  sleep 0.5
done
[ "$(sinfo -h -n localhost -o %t 2>/dev/null)" = idle ] ||
  die "the node is not idle after 30 s: $(sinfo -h -n localhost -o '%t %E' 2>&1)"
echo "cluster: Slurm up on 127.0.0.1:$ctld_port/$d_port in $((SECONDS - start)) s ($node)" >&2

check() {  # check NAME COMMAND...: a test
  local name=$1
  shift
  if "$@"; then
    passed=$((passed + 1))
    echo "cluster: ok   $name" >&2
  else
    failed=$((failed + 1))
    echo "cluster: FAIL $name" >&2
    print_logs
  fi
}

# Every file of two trees, byte for byte, except the shard lists that only the sharded one has
# and, in manifest.json, a probe's capture time ("milliseconds"): the only bytes that vary.
same_tree() {
  local a=$1 b=$2 status=0 f
  local files
  files="$( (cd "$a" && find . -type f) && (cd "$b" && find . -type f))"
  files="$(grep -v '/probes\.shard-' <<<"$files" | sed 's|^\./||' | sort -u)"
  [ -n "$files" ] || { echo "cluster: $a and $b are empty" >&2; return 1; }
  while IFS= read -r f; do
    if [ ! -f "$a/$f" ] || [ ! -f "$b/$f" ]; then
      echo "cluster: $f is in only one of $a and $b" >&2
      status=1
    elif [[ $f == manifest.json || $f == */manifest.json ]]; then
      cmp -s <(grep -v '"milliseconds":' "$a/$f") <(grep -v '"milliseconds":' "$b/$f") || {
        echo "cluster: $f differs (beyond the capture time):" >&2
        diff <(grep -v '"milliseconds":' "$a/$f") <(grep -v '"milliseconds":' "$b/$f") | head -n 10 >&2
        status=1
      }
    else
      cmp -s "$a/$f" "$b/$f" || { echo "cluster: $f differs: $(cmp "$a/$f" "$b/$f" 2>&1)" >&2; status=1; }
    fi
  done <<<"$files"
  [ "$status" = 0 ] && echo "cluster: $b equals $a: $(wc -l <<<"$files") files" >&2
  return "$status"
}

# The jobs run in the scratch folder, with ibl on the PATH, one CPU per task (ibl --threads 1)
# where the one-process runs use every core: the bytes must not depend on either.
cd "$scratch/work"
ln -s "$repo/data" data
export PATH="$build:$PATH"
array=(bounded sbatch --wait --cpus-per-task=1 --output="$scratch/logs/%x-%A_%a.out")
scene=data/scenes/room.gltf
probe_options=(--grid 2,1,2 --bounds -2,0.5,-2,2,2.5,2 --size 16 --spp 8)
ls data/hdri/*.exr >hdris.txt
bake_options=(--size 16 --dfg-size 16 --dfg-samples 64 --preview-size 8)

bounded ibl probe "$scene" "${probe_options[@]}" -o one-grid -q || die "the one-process grid failed"
bounded ibl bake --list hdris.txt "${bake_options[@]}" -o one-batch -q ||
  die "the one-process batch failed"

# 1. A probe grid in 4 array tasks, merged.
check "probe grid: 4 array tasks succeed" \
  "${array[@]}" --array=0-3 "$repo/deploy/slurm/probe-grid.sh" 4 "$scene" grid "${probe_options[@]}"
check "probe grid: the shards merge" bounded ibl probe --merge grid
check "probe grid: merged grid equals the one-process grid" same_tree one-grid grid

# 2. A batch of bakes in 4 array tasks.
check "bake batch: 4 array tasks succeed" \
  "${array[@]}" --array=0-3 "$repo/deploy/slurm/bake-batch.sh" 4 hdris.txt batch "${bake_options[@]}"
check "bake batch: equals the one-process batch" same_tree one-batch batch

# 3. Task 2 fails; the merge names what it owed; task 2 alone again.
failing_array_fails() {  # with a failure status, not a timeout's
  local status=0
  IBL_FAIL_TASK=2 "${array[@]}" --array=0-3 "$repo/deploy/slurm/probe-grid.sh" 4 "$scene" \
    retry "${probe_options[@]}" || status=$?
  [ "$status" != 0 ] && [ "$status" != 124 ] && [ "$status" != 137 ]
}
check "failure: the array job with task 2 failing fails" failing_array_fails
merge_names_the_missing_probes() {
  local output
  output="$(bounded ibl probe --merge retry 2>&1)" && { echo "cluster: the merge succeeded" >&2; return 1; }
  echo "cluster: the merge says: $output" >&2
  # Of the 2x1x2 grid, the probe of linear index 2 (i, j, k = 0, 0, 1) is shard 2's.
  [[ $output == *"missing: probe_0_0_1 "* && $output == *"shard 2/4"* ]] && [ ! -e retry/probes.json ]
}
check "failure: the merge fails naming the missing probe and shard" merge_names_the_missing_probes
check "failure: task 2 resubmitted alone succeeds" \
  "${array[@]}" --array=2 "$repo/deploy/slurm/probe-grid.sh" 4 "$scene" retry "${probe_options[@]}"
check "failure: the merge completes" bounded ibl probe --merge retry
check "failure: the completed grid equals the one-process grid" same_tree one-grid retry

# 4. The Kubernetes manifest (documented, not run here) parses, when PyYAML is there.
manifest="$repo/deploy/kubernetes/probe-grid-job.yaml"
manifest_parses() {
  python3 - "$manifest" <<'PY'
import sys, yaml
docs = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d is not None]
kinds = [d.get("kind") for d in docs]
print("cluster: %s: %s" % (sys.argv[1], ", ".join(map(str, kinds))), file=sys.stderr)
sys.exit(0 if docs and all(kinds) else 1)
PY
}
if command -v python3 >/dev/null && python3 -c 'import yaml' 2>/dev/null; then
  check "kubernetes: the Indexed Job manifest parses" manifest_parses
else
  echo "cluster: skip kubernetes: the manifest parses (no python3 with yaml: apt-get install python3-yaml)" >&2
fi

echo "cluster: phase took $((SECONDS - start)) s" >&2
echo "cluster: $passed passed, $failed failed"
[ "$failed" = 0 ]
