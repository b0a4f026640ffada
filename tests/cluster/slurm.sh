#!/usr/bin/env bash
# A throwaway single-node Slurm cluster on 127.0.0.1 for the tests (tests/cluster/*.sh).
#
# Source this file, then:
#     slurm_start DIR || exit 77     # a skip: SLURM_SKIP_REASON says why
#     sbatch ...                     # SLURM_CONF is exported: the client commands find the cluster
#     slurm_stop                     # also run by the EXIT trap slurm_start installs
#
# Everything lives in DIR: a fresh MUNGE key, munged with its own socket, pid and seed files,
# slurm.conf, slurmctld's state, slurmd's spool, the pid and log files. Nothing is read from or
# written to /etc/slurm, /etc/munge, /run or /var. The daemons run in the foreground (-D) as
# background jobs of the test shell and are stopped by pid (TERM, then KILL after a bounded
# wait), so a test never leaves a daemon behind, even when it fails half-way.
#
# The cluster: one node "localhost" (NodeAddr and NodeHostname 127.0.0.1, CPUs=2, trusted over
# what the hardware reports, so it comes up on a one-core machine too), one default partition
# "sim", no accounting, no cgroups (proctrack/linuxproc, task/none), so it runs as root in a
# container without systemd. The daemons use two ports that were free a moment before.
#
# No host-name resolution is needed: every address in slurm.conf is 127.0.0.1 and slurmd is
# told its node name (-N). Slurm resolves the machine's own host name only to bind its
# listening sockets to one address (CommunicationParameters=NoCtldInAddrAny,NoInAddrAny), so
# the daemons listen on 127.0.0.1 only when the host name resolves to loopback addresses only;
# otherwise (a name that does not resolve, as on a fresh chroot, or one that resolves to another
# interface, where slurmd would bind there and slurmctld could not reach it at 127.0.0.1) they
# listen on every address, still answering only requests signed with this cluster's fresh MUNGE
# key. SLURM_LOOPBACK_ONLY says which (1 or 0).
#
# slurm_start returns non-zero with SLURM_SKIP_REASON set when the machine cannot run Slurm
# (the packages are missing, we are not root, a daemon dies at start-up or the node never
# becomes idle): the caller prints it and exits 77, the ctest skip status. Each wait is bounded.

SLURM_PIDS=()       # the daemons we started, stopped in reverse order
SLURM_WATCHDOG=""   # the process that stops them if this shell is killed (see slurm_watchdog)
SLURM_DIR=""        # the cluster directory given to slurm_start
SLURM_SKIP_REASON=""
SLURM_PREV_TRAP=""  # the caller's EXIT trap, run after slurm_stop
SLURM_LOOPBACK_ONLY=0  # 1: the daemons listen on 127.0.0.1 only (see above)

# slurm_log_tail: the end of every daemon log, for a failure or skip message.
slurm_log_tail() {
  local f
  for f in "$SLURM_DIR"/log/*.log; do
    [[ -s "$f" ]] || continue
    printf -- '--- %s (last 15 lines)\n' "$(basename "$f")"
    tail -n 15 "$f"
  done
}

# slurm_skip REASON: record why the cluster cannot run, stop what started, return 1.
slurm_skip() {
  SLURM_SKIP_REASON="$1"
  if [[ -n "$SLURM_DIR" && -d "$SLURM_DIR/log" ]]; then
    SLURM_SKIP_REASON+=$'\n'"$(slurm_log_tail)"
  fi
  slurm_stop
  return 1
}

# slurm_free_ports: prints two TCP ports that 127.0.0.1 can bind right now.
slurm_free_ports() {
  python3 - <<'PY'
import socket
socks = []
for _ in range(2):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    socks.append(s)
print(" ".join(str(s.getsockname()[1]) for s in socks))
PY
}

# slurm_wait SECONDS WHAT CMD...: polls CMD every 0.2 s until it succeeds; 1 if time runs out.
slurm_wait() {
  local limit=$1 what=$2 start=$SECONDS
  shift 2
  until "$@" >/dev/null 2>&1; do
    if ((SECONDS - start >= limit)); then
      printf 'slurm: gave up after %ss waiting for %s\n' "$limit" "$what" >&2
      return 1
    fi
    sleep 0.2
  done
}

# slurm_host_is_loopback: this machine's host name resolves, and only to 127.0.0.0/8 addresses
# (then the daemons can bind to it and still be reached at 127.0.0.1).
slurm_host_is_loopback() {
  local addrs
  addrs=$(getent ahostsv4 "$(hostname)" 2>/dev/null | awk '{print $1}' | sort -u) || return 1
  [[ -n "$addrs" ]] && ! grep -qv '^127\.' <<<"$addrs"
}

# slurm_alive PID: the daemon is still running (a background job of this shell).
slurm_alive() { kill -0 "$1" 2>/dev/null; }

# slurm_node_idle: sinfo reports the node idle (not idle* or idle~: those are not responding).
slurm_node_idle() { [[ "$(sinfo -h -N -n localhost -o '%T' 2>/dev/null)" == "idle" ]]; }

# slurm_started PID: remember a daemon (for slurm_stop and for the watchdog's list).
slurm_started() {
  SLURM_PIDS+=("$1")
  printf '%s\n' "$1" >>"$SLURM_DIR/run/daemons"
}

# slurm_steps: the slurmstepd processes of this cluster (their environment names SLURM_DIR).
slurm_steps() {
  local pid
  for pid in $(pgrep -x slurmstepd 2>/dev/null); do
    grep -qs "$SLURM_DIR" "/proc/$pid/environ" && printf '%s\n' "$pid"
  done
  return 0
}

# slurm_watchdog PARENT: runs in the background; if the test shell PARENT disappears without
# slurm_stop (SIGKILL from a ctest timeout, say), it kills the daemons and job steps itself.
# It keeps its own copy of the daemon list, in case the directory is gone by then.
slurm_watchdog() {
  local parent=$1 pid daemons=""
  while kill -0 "$parent" 2>/dev/null; do
    [[ -f "$SLURM_DIR/run/daemons" ]] && daemons=$(cat "$SLURM_DIR/run/daemons")
    sleep 1
  done
  for pid in $(slurm_steps) $daemons; do
    kill -KILL "$pid" 2>/dev/null
  done
}

# slurm_start DIR: brings the cluster up in DIR (created if missing). 0 when the node is idle.
slurm_start() {
  if [[ ${#SLURM_PIDS[@]} -gt 0 ]]; then
    SLURM_SKIP_REASON="slurm_start: a cluster is running already (in $SLURM_DIR); slurm_stop it first"
    printf '%s\n' "$SLURM_SKIP_REASON" >&2
    return 1
  fi
  SLURM_DIR=$(mkdir -p "$1" && cd "$1" && pwd)
  SLURM_PIDS=()
  # Keep the caller's EXIT trap (e.g. the removal of its work directory) and stop the
  # cluster before it. TERM, INT and HUP exit through the EXIT trap as well.
  local prev
  prev=$(trap -p EXIT)
  prev=${prev#"trap -- '"}
  prev=${prev%"' EXIT"}
  # A second slurm_start keeps the first one's saved trap rather than saving its own.
  [[ "$prev" == *slurm_stop* ]] || SLURM_PREV_TRAP=${prev//"'\\''"/"'"}
  trap 'slurm_stop; eval "$SLURM_PREV_TRAP"' EXIT
  trap 'exit 143' TERM
  trap 'exit 130' INT
  trap 'exit 129' HUP
  local c
  PATH="$PATH:/usr/sbin:/sbin"  # the daemons live in sbin, which a normal user's PATH may lack
  for c in munged slurmctld slurmd sinfo sbatch scancel scontrol python3; do
    command -v "$c" >/dev/null ||
      { slurm_skip "$c is not installed (scripts/deps.sh test installs slurmctld slurmd slurm-client munge)"; return 1; }
  done
  [[ "$(id -u)" -eq 0 ]] || { slurm_skip "the test cluster runs its daemons as root; this is uid $(id -u)"; return 1; }

  local d=$SLURM_DIR
  mkdir -p "$d/munge" "$d/state" "$d/spool" "$d/log" "$d/run"
  : >"$d/run/daemons"
  # munged refuses a key or socket directory that others may write to.
  chmod 0700 "$d/munge" "$d/state" "$d/spool"
  chmod 0755 "$d" "$d/log" "$d/run"
  # A fresh key for this cluster only (munged wants at least 32 bytes, mode 0400 or 0600).
  head -c 1024 /dev/urandom >"$d/munge/munge.key"
  chmod 0400 "$d/munge/munge.key"

  slurm_watchdog "$$" </dev/null >/dev/null 2>&1 &
  SLURM_WATCHDOG=$!

  munged --foreground --force --socket="$d/munge/munge.socket" --key-file="$d/munge/munge.key" \
    --pid-file="$d/munge/munged.pid" --seed-file="$d/munge/munged.seed" \
    --log-file="$d/log/munged.log" >>"$d/log/munged.log" 2>&1 &
  slurm_started $!
  slurm_wait 20 "munged's socket" test -S "$d/munge/munge.socket" ||
    { slurm_skip "munged did not start"; return 1; }

  local ports ctld_port slurmd_port
  ports=$(slurm_free_ports) || { slurm_skip "cannot find free ports on 127.0.0.1"; return 1; }
  read -r ctld_port slurmd_port <<<"$ports"

  local comm="# CommunicationParameters: none (the host name does not resolve to loopback only)"
  SLURM_LOOPBACK_ONLY=0
  if slurm_host_is_loopback; then
    comm="CommunicationParameters=NoCtldInAddrAny,NoInAddrAny"
    SLURM_LOOPBACK_ONLY=1
  fi
  cat >"$d/slurm.conf" <<EOF
# Written by tests/cluster/slurm.sh for one test run.
ClusterName=simbobtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
$comm
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$d/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/run/slurmctld.pid
SlurmdPidFile=$d/run/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
ReturnToService=2
MinJobAge=300
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
Waittime=0
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=sim Nodes=localhost Default=YES MaxTime=60 State=UP
EOF
  # No cgroups are used (proctrack/linuxproc, task/none), but slurmd 22.05 initialises a cgroup
  # plugin anyway, and its autodetection fails where /sys/fs/cgroup is not mounted (a chroot):
  # name the plugin, with a mount point of our own that nothing reads.
  mkdir -p "$d/cgroup"
  printf 'CgroupPlugin=cgroup/v1\nCgroupMountpoint=%s/cgroup\n' "$d" >"$d/cgroup.conf"
  # An empty plugstack: the host's /etc/slurm/plugstack.conf is none of this cluster's business.
  : >"$d/plugstack.conf"
  printf 'PlugStackConfig=%s/plugstack.conf\n' "$d" >>"$d/slurm.conf"
  export SLURM_CONF="$d/slurm.conf"

  # -i: ignore state from an earlier run (there is none in a fresh directory anyway).
  slurmctld -D -i -f "$SLURM_CONF" >>"$d/log/slurmctld.stdout" 2>&1 &
  slurm_started $!
  slurm_wait 30 "slurmctld to answer" scontrol ping ||
    { slurm_skip "slurmctld did not start"; return 1; }
  slurmd -D -N localhost -f "$SLURM_CONF" >>"$d/log/slurmd.stdout" 2>&1 &
  slurm_started $!
  slurm_wait 60 "the node to become idle" slurm_node_idle ||
    { slurm_skip "the node did not become idle: $(sinfo -h -N -o '%N %T %E' 2>&1 | head -n 3)"; return 1; }
  local pid
  for pid in "${SLURM_PIDS[@]}"; do
    slurm_alive "$pid" || { slurm_skip "a daemon (pid $pid) exited during start-up"; return 1; }
  done
  return 0
}

# slurm_stop: cancels every job, stops the daemons (TERM, then KILL after 10 s) and the
# watchdog, forgets them. Safe to call twice and before slurm_start.
slurm_stop() {
  if [[ -n "$SLURM_WATCHDOG" ]]; then
    kill -TERM "$SLURM_WATCHDOG" 2>/dev/null || true
    wait "$SLURM_WATCHDOG" 2>/dev/null || true
    SLURM_WATCHDOG=""
  fi
  if [[ ${#SLURM_PIDS[@]} -gt 0 && -n "${SLURM_CONF:-}" ]]; then
    timeout 10 scancel --quiet --user=root >/dev/null 2>&1 || true
  fi
  local i pid waited
  for ((i = ${#SLURM_PIDS[@]} - 1; i >= 0; i--)); do
    pid=${SLURM_PIDS[$i]}
    slurm_alive "$pid" || continue
    kill -TERM "$pid" 2>/dev/null || true
    waited=0
    while slurm_alive "$pid" && ((waited < 50)); do
      sleep 0.2
      waited=$((waited + 1))
    done
    if slurm_alive "$pid"; then
      printf 'slurm: pid %s ignored TERM for 10 s; killing it\n' "$pid" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
    wait "$pid" 2>/dev/null || true
  done
  SLURM_PIDS=()
  # Job steps still running when slurmd stopped.
  if [[ -n "$SLURM_DIR" ]]; then
    for pid in $(slurm_steps); do kill -KILL "$pid" 2>/dev/null || true; done
  fi
  return 0
}
