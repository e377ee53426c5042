#!/usr/bin/env bash
# A one-node Slurm on localhost, for tests and for trying the job-array scripts:
#
#   scripts/slurm/local-cluster.sh start DIR    # munged, slurmctld, slurmd; waits for the node
#   export SLURM_CONF=DIR/slurm.conf              # then sbatch, squeue, sinfo, scontrol talk to it
#   scripts/slurm/local-cluster.sh status DIR
#   scripts/slurm/local-cluster.sh stop DIR     # cancels its jobs, stops each daemon by its pid
#
# Everything lives in DIR: slurm.conf, a fresh munge key, state, spool, logs and pid files. No
# file under /etc is read or written and no system service is used, so it runs as root in a
# container without systemd, beside (not instead of) any Slurm or munge the machine has. The
# daemons run as the current user (SlurmUser), with proctrack/linuxproc and task/none, which need
# no cgroups, and select/cons_tres with one CPU per job. The ports are picked free at start.
#
# Exit status of start: 0 the node is idle; 1 bad use, missing programs or DIR unusable;
# 77 a daemon could not start (why and its log are printed; a test may skip on this status);
# 4 the daemons run but the node did not become idle in time. status: 0 all three daemons run,
# 1 otherwise. stop: 0 when no daemon of DIR is left, 1 otherwise.
#
# Needs Debian's munge, slurmctld, slurmd and slurm-client (scripts/setup.sh installs them).
# LOCAL_CLUSTER_TIMEOUT (seconds, default 30) bounds each wait.
set -euo pipefail

readonly status_cannot_start=77
readonly status_not_idle=4
readonly node_name=localnode
timeout_s="${LOCAL_CLUSTER_TIMEOUT:-30}"

usage() {
  echo "usage: $0 start|stop|status DIR" >&2
  exit 1
}

# The daemons in start order; stop goes the other way.
daemons=(munged slurmctld slurmd)

pid_file() { echo "$dir/run/$1.pid"; }

# True while the process with this pid exists and is not a zombie: a killed daemon lingers as a
# zombie until its parent (init, for a daemon) reaps it, which may take a while.
is_alive() {
  local stat
  [[ "$1" =~ ^[0-9]+$ ]] || return 1
  stat="$(cat "/proc/$1/stat" 2>/dev/null)" || return 1
  [[ "${stat##*) }" != Z* ]]
}

# True while is_alive and the process runs the named program: a pid file may outlive its
# process and its pid be reused.
is_running() {
  is_alive "$1" && [[ "$(cat "/proc/$1/comm" 2>/dev/null)" == "$2" ]]
}

daemon_pid() {
  local f
  f="$(pid_file "$1")"
  [[ -s "$f" ]] || return 1
  local pid
  pid="$(<"$f")"
  is_running "$pid" "$1" || return 1
  echo "$pid"
}

# A TCP port nobody listens on, between 20000 and 39999 (below Linux's ephemeral range).
# Listening sockets (state 0A) are read from /proc so that no network tool is needed.
free_port() {
  local taken=" " local_address st port
  for f in /proc/net/tcp /proc/net/tcp6; do
    [[ -r "$f" ]] || continue
    while read -r _ local_address _ st _; do
      [[ "$st" == 0A ]] && taken+="$((16#${local_address##*:})) "
    done < <(tail -n +2 "$f")
  done
  for _ in $(seq 1 100); do
    port=$((20000 + RANDOM % 20000))
    if [[ "$taken" != *" $port "* && "$port" != "${1:-}" ]]; then
      echo "$port"
      return 0
    fi
  done
  echo "local-cluster: no free TCP port found in 20000-39999" >&2
  return 1
}

write_slurm_conf() {
  local ctld_port="$1" slurmd_port="$2" user cpus
  user="$(id -un)"
  cpus="$(nproc)"
  # SlurmctldHost=localhost is accepted by slurmctld whatever the machine's hostname is; the node
  # is named on slurmd's command line (-N) and reached at 127.0.0.1, so no name resolution of the
  # container's hostname is needed. config_overrides makes slurmd report the configured CPUs
  # instead of draining the node when its hardware probe (sockets, cores) differs from them.
  # MailProg=/bin/true silences slurmctld's error about a missing mail program. The scheduler
  # parameters start a job at the next event instead of batching submissions for 3 s, which is
  # what a cluster running a few short jobs wants (the test's jobs: about 4 s instead of 9 s).
  cat >"$dir/slurm.conf" <<EOF
# Written by scripts/slurm/local-cluster.sh: a one-node test cluster, everything under $dir.
ClusterName=gearimpact-local
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$(pid_file slurmctld)
SlurmdPidFile=$(pid_file slurmd)
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
SlurmdParameters=config_overrides
NodeName=$node_name NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$node_name Default=YES MaxTime=INFINITE State=UP
EOF
}

# Prints why a daemon is not up, with the end of its logs, and stops whatever was started.
cannot_start() {
  local name="$1" why="$2"
  echo "local-cluster: $name could not start: $why" >&2
  for f in "$dir/log/$name.out" "$dir/log/$name.log"; do
    if [[ -s "$f" ]]; then
      echo "--- last lines of $f" >&2
      tail -n 15 "$f" >&2
    fi
  done
  stop_cluster >/dev/null 2>&1 || true
  exit "$status_cannot_start"
}

# Starts one daemon in the foreground mode of its own, in a session of its own (so that a
# terminal's signals and the caller's exit do not reach it), with its standard streams on a log
# file (so that a caller reading our output, such as ctest, does not wait for the daemon), then
# waits until it has written its pid file.
launch() {
  local name="$1"
  shift
  setsid "$@" </dev/null >>"$dir/log/$name.out" 2>&1 &
  local launched=$! waited=0
  until daemon_pid "$name" >/dev/null; do
    if ! is_alive "$launched"; then
      cannot_start "$name" "it exited during start-up"
    fi
    if ((waited >= timeout_s * 10)); then
      cannot_start "$name" "no pid file $(pid_file "$name") after ${timeout_s} s"
    fi
    sleep 0.1
    waited=$((waited + 1))
  done
}

start_cluster() {
  local prog
  for prog in munged mungekey slurmctld slurmd sinfo squeue scancel; do
    if ! command -v "$prog" >/dev/null; then
      echo "local-cluster: $prog is not installed (scripts/setup.sh installs munge," \
        "slurmctld, slurmd and slurm-client)" >&2
      exit 1
    fi
  done
  local name
  for name in "${daemons[@]}"; do
    if daemon_pid "$name" >/dev/null; then
      echo "local-cluster: $name of $dir is already running (stop it first)" >&2
      exit 1
    fi
  done
  # Unix socket paths (munged's, slurmd's per-step sockets in the spool) are limited to 107
  # bytes; the longest one the cluster makes is about DIR + 40.
  if ((${#dir} > 60)); then
    echo "local-cluster: DIR is ${#dir} characters long, at most 60 are allowed (unix socket" \
      "paths under it are limited to 107 bytes): $dir" >&2
    exit 1
  fi
  # A fresh start every time: no state, spool or key of an earlier run is reused.
  rm -rf "$dir/state" "$dir/spool" "$dir/munge" "$dir/run"
  mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/run" "$dir/munge"
  # munged requires the socket's folder to be searchable by everyone and the key readable only by
  # its owner.
  chmod 0755 "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key"
  chmod 0600 "$dir/munge/munge.key"

  local ctld_port slurmd_port
  ctld_port="$(free_port)"
  slurmd_port="$(free_port "$ctld_port")"
  write_slurm_conf "$ctld_port" "$slurmd_port"
  export SLURM_CONF="$dir/slurm.conf"

  # --force: munged refuses to run when a folder above DIR is writable by a group or others (a
  # checkout made with umask 002, say); this key protects nothing but this scratch cluster.
  launch munged munged --foreground --force --socket="$dir/munge/munge.socket" \
    --key-file="$dir/munge/munge.key" --pid-file="$(pid_file munged)" \
    --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munged.seed"
  # slurmctld -c: start with no jobs, whatever the state folder held.
  launch slurmctld slurmctld -D -c -f "$SLURM_CONF"
  launch slurmd slurmd -D -N "$node_name" -f "$SLURM_CONF"

  local waited=0 state=""
  while :; do
    for name in "${daemons[@]}"; do
      daemon_pid "$name" >/dev/null || cannot_start "$name" "it exited after start-up"
    done
    state="$(sinfo -h -n "$node_name" -o %T 2>/dev/null || true)"
    [[ "$state" == idle ]] && break
    if ((waited >= timeout_s * 5)); then
      echo "local-cluster: node $node_name is '${state:-unknown}', not idle, after ${timeout_s} s;" \
        "logs in $dir/log" >&2
      sinfo -N -l >&2 || true
      stop_cluster >/dev/null 2>&1 || true
      exit "$status_not_idle"
    fi
    sleep 0.2
    waited=$((waited + 1))
  done
  echo "local-cluster: node $node_name idle (slurmctld port $ctld_port, slurmd port $slurmd_port)"
  echo "export SLURM_CONF=$SLURM_CONF"
}

# Kills one process by its pid and waits until it is gone: TERM first, KILL after timeout_s.
kill_and_wait() {
  local pid="$1" name="$2" waited=0
  is_running "$pid" "$name" || return 0
  kill -TERM "$pid" 2>/dev/null || true
  while is_running "$pid" "$name"; do
    if ((waited == timeout_s * 10)); then
      echo "local-cluster: $name (pid $pid) ignored SIGTERM for ${timeout_s} s, sending SIGKILL" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
    if ((waited > timeout_s * 20)); then
      echo "local-cluster: $name (pid $pid) is still running" >&2
      return 1
    fi
    sleep 0.1
    waited=$((waited + 1))
  done
}

# The job-step daemons slurmd started for this cluster: they inherit slurmd's environment, which
# names this cluster's slurm.conf.
step_daemons() {
  local p
  for p in /proc/[0-9]*; do
    is_running "${p#/proc/}" slurmstepd || continue
    if tr '\0' '\n' 2>/dev/null <"$p/environ" | grep -qxF "SLURM_CONF=$dir/slurm.conf"; then
      echo "${p#/proc/}"
    fi
  done
}

stop_cluster() {
  export SLURM_CONF="$dir/slurm.conf"
  local failed=0 pid name i
  # Jobs first, while slurmctld and slurmd can still end them cleanly.
  if daemon_pid slurmctld >/dev/null && [[ -n "$(squeue -h -o %A 2>/dev/null)" ]]; then
    squeue -h -o %A | xargs -r scancel || true
    for ((i = 0; i < timeout_s * 5; i++)); do
      [[ -z "$(squeue -h -o %A 2>/dev/null)" ]] && break
      sleep 0.2
    done
  fi
  for ((i = ${#daemons[@]} - 1; i >= 0; i--)); do
    name="${daemons[i]}"
    if pid="$(daemon_pid "$name")"; then
      kill_and_wait "$pid" "$name" || failed=1
    fi
    rm -f "$(pid_file "$name")"
  done
  for pid in $(step_daemons); do
    kill_and_wait "$pid" slurmstepd || failed=1
  done
  if ((failed)); then
    return 1
  fi
  echo "local-cluster: stopped"
}

status_cluster() {
  local all=0 pid name
  for name in "${daemons[@]}"; do
    if pid="$(daemon_pid "$name")"; then
      echo "$name: running (pid $pid)"
    else
      echo "$name: not running"
      all=1
    fi
  done
  if ((all == 0)); then
    SLURM_CONF="$dir/slurm.conf" sinfo -N -l || true
  fi
  return "$all"
}

(($# == 2)) || usage
command="$1"
case "$command" in
  start)
    mkdir -p "$2"
    dir="$(cd "$2" && pwd -P)"
    start_cluster
    ;;
  stop | status)
    if [[ ! -d "$2" ]]; then
      echo "local-cluster: no cluster in $2 (no such folder)"
      # Nothing to stop is a successful stop; nothing running is a failed status.
      if [[ "$command" == stop ]]; then exit 0; else exit 1; fi
    fi
    dir="$(cd "$2" && pwd -P)"
    "${command}_cluster"
    ;;
  *) usage ;;
esac
