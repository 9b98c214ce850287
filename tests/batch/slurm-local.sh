#!/usr/bin/env bash
# slurm-local.sh - throw-away one-node Slurm cluster on localhost for tests.
#
# Everything (config, munge key + socket, state, spool, logs, pid files)
# lives in a state folder DIR given on the command line; nothing under /etc
# is read or edited, and several clusters (different DIRs) can run at once.
#
# Usage:
#   slurm-local.sh start DIR   start munged, slurmctld and slurmd for DIR, wait
#                              until the node is idle, print the client env
#                              (export lines) on stdout, exit 0.
#                              On failure: one line "slurm-local: cannot
#                              start: REASON" + log tail on stderr, everything
#                              started is stopped again, exit 77 (= "skip" for
#                              CTest / automake).
#   slurm-local.sh stop DIR    cancel remaining jobs, stop slurmd, slurmctld
#                              and munged of DIR (by their pid files), wait
#                              for them to exit. Idempotent, exit 0.
#   slurm-local.sh env DIR     print the export lines again.
#
# Client side: `eval "$(slurm-local.sh start DIR)"` (or `env DIR`) sets
# SLURM_CONF; sbatch/squeue/scancel/sinfo/srun then talk to this cluster.
# The munge socket is named in slurm.conf (AuthInfo=socket=...), so no munge
# env variable is needed. No accounting: sacct/sreport do not work.
#
# Environment knobs (all optional):
#   SLURM_LOCAL_PORT     slurmctld port; slurmd uses PORT+1. Default: a free
#                        pair picked from 20000-59999 starting at a value
#                        derived from $$, so concurrent runs rarely clash.
#   SLURM_LOCAL_TIMEOUT  seconds to wait for the node to become idle (30).
#   SLURM_LOCAL_CPUS     CPUs to advertise (default: nproc).
#   SLURM_LOCAL_EXTRA_CONF  extra lines appended to slurm.conf (later
#                        settings override earlier ones).
#
# Requirements: root (SlurmUser=root, slurmd must switch to the job's
# user), Slurm >= 22.05 and munge installed. DIR must be a short path
# (Unix socket paths are limited to 107 bytes) without whitespace, ',', '#'
# or '='.
set -euo pipefail

readonly PROG=slurm-local
readonly EXIT_SKIP=77

usage() {
    echo "usage: $0 {start|stop|env} DIR" >&2
    exit 2
}

# ---------------------------------------------------------------- helpers

# All paths used for DIR. Called once DIR is known (absolute).
set_paths() {
    CONF="$DIR/slurm.conf"
    MUNGE_DIR="$DIR/munge"            # key (0400), socket, pid, seed, log
    MUNGE_KEY="$MUNGE_DIR/munge.key"
    MUNGE_SOCK="$MUNGE_DIR/munge.socket"
    MUNGE_PID="$MUNGE_DIR/munged.pid"
    MUNGE_LOG="$MUNGE_DIR/munged.log"
    MUNGE_SEED="$MUNGE_DIR/munged.seed"
    STATE_DIR="$DIR/state"            # slurmctld StateSaveLocation
    SPOOL_DIR="$DIR/spool"            # slurmd SlurmdSpoolDir (stepd sockets)
    LOG_DIR="$DIR/log"
    CTLD_PID="$DIR/slurmctld.pid"
    SLURMD_PID="$DIR/slurmd.pid"
    ENV_FILE="$DIR/env.sh"            # the export lines, for `env`
}

# Client commands run by this script always target DIR's cluster.
sl() { SLURM_CONF="$CONF" "$@"; }

# Print the pid from pid file $1 if that process is alive and belongs to
# DIR: the daemons are started with the marker SLURM_LOCAL_MARK=DIR in their
# environment (never exported to clients, so a test shell is never taken
# for a daemon). This guards against stale pid files whose pid was reused.
live_pid() {
    local pidfile=$1 pid
    [[ -r $pidfile ]] || return 1
    pid=$(tr -dc '0-9' <"$pidfile")
    [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null || return 1
    tr '\0' '\n' 2>/dev/null <"/proc/$pid/environ" |
        grep -qxF "SLURM_LOCAL_MARK=$DIR" || return 1
    echo "$pid"
}

# Slurm processes of DIR left over after the daemons were stopped, and the
# job processes under them. slurmstepd clears its environment (no marker),
# but it inherits slurmd's working directory, which is LOG_DIR; each step
# runs in its own session, shared with the job's processes.
leftover_pids() {
    local pid sid comm sids=""
    while read -r pid sid comm; do
        [[ $comm == slurm* ]] || continue
        [[ $(readlink "/proc/$pid/cwd" 2>/dev/null) == "$LOG_DIR" ]] || continue
        echo "$pid"
        sids+=" $sid "
    done < <(ps -e -o pid=,sid=,comm=)
    [[ -n $sids ]] || return 0
    while read -r pid sid; do
        [[ $sids == *" $sid "* && $pid != "$$" ]] && echo "$pid"
    done < <(ps -e -o pid=,sid=)
    return 0
}

# stop_pidfiles PIDFILE...: SIGTERM to the live daemons of DIR among them
# (all at once, shutdown takes ~1-2 s each), wait up to 15 s, then SIGKILL.
stop_pidfiles() {
    local f pid pids=() i
    for f in "$@"; do
        if pid=$(live_pid "$f"); then
            pids+=("$pid")
            kill -TERM "$pid" 2>/dev/null || true
        fi
    done
    for pid in ${pids[@]+"${pids[@]}"}; do
        for ((i = 0; i < 150; i++)); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.1
        done
        if kill -0 "$pid" 2>/dev/null; then
            echo "$PROG: pid $pid ignored SIGTERM, killing it" >&2
            kill -KILL "$pid" 2>/dev/null || true
        fi
    done
    rm -f "$@"
}

# port_busy PORT: true if something listens on 127.0.0.1:PORT.
port_busy() {
    (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null
}

# Print "export ..." lines for clients.
print_env() {
    cat "$ENV_FILE"
}

# ------------------------------------------------------------------ stop

do_stop() {
    local ids i
    # 1. Cancel all jobs while slurmctld still runs, so that slurmstepd and
    #    job processes are cleaned up by Slurm itself (bounded wait).
    if live_pid "$CTLD_PID" >/dev/null && [[ -r $CONF ]]; then
        ids=$(sl squeue -h -o %A 2>/dev/null || true)
        if [[ -n $ids ]]; then
            # shellcheck disable=SC2086  # word splitting of the id list
            sl scancel $ids 2>/dev/null || true
            for ((i = 0; i < 100; i++)); do
                [[ -z $(sl squeue -h -t R,CG,S -o %A 2>/dev/null) ]] && break
                sleep 0.1
            done
        fi
    fi
    # 2. Daemons. munged can go at the same time: nothing authenticates
    #    during shutdown once the jobs are gone.
    stop_pidfiles "$SLURMD_PID" "$CTLD_PID" "$MUNGE_PID"
    # 3. Leftovers: a slurmstepd whose job did not end in time, its job.
    local left
    left=$(leftover_pids | sort -u)
    if [[ -n $left ]]; then
        echo "$PROG: killing leftover processes: ${left//$'\n'/ }" >&2
        # shellcheck disable=SC2086
        kill -KILL $left 2>/dev/null || true
    fi
    rm -f "$MUNGE_SOCK" "$MUNGE_SOCK.lock" "$ENV_FILE"
    return 0
}

# ----------------------------------------------------------------- start

# fail REASON [LOGFILE...]: one-line reason + log tails on stderr, stop
# everything started so far, exit 77.
fail() {
    local reason=$1 f
    shift
    echo "$PROG: cannot start: $reason" >&2
    for f in "$@"; do
        [[ -s $f ]] || continue
        echo "--- tail of $f:" >&2
        tail -n 15 "$f" >&2
    done
    do_stop >/dev/null 2>&1 || true
    exit "$EXIT_SKIP"
}

write_conf() {
    local cpus mem_kb mem_mb
    cpus=${SLURM_LOCAL_CPUS:-$(nproc)}
    mem_kb=$(awk '/^MemTotal:/ {print $2}' /proc/meminfo)
    # Advertise ~90% of RAM: slurmd drains a node whose RealMemory is larger
    # than what it detects, so stay safely below the total.
    mem_mb=$((mem_kb * 9 / 10 / 1024))

    cat >"$CONF" <<EOF
# Generated by tests/batch/slurm-local.sh - throw-away test cluster.
ClusterName=local$CTLD_PORT
# Controller and node are this host; "localhost" is accepted by slurmctld
# as its own name, slurmd is started with -N localhost.
SlurmctldHost=localhost
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
# Daemons run as root (slurmd must be root to run jobs as their owner).
SlurmUser=root
SlurmdUser=root
# Authentication and job credentials through our private munged.
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCK
# Everything on disk stays inside DIR.
StateSaveLocation=$STATE_DIR
SlurmdSpoolDir=$SPOOL_DIR
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$LOG_DIR/slurmctld.log
SlurmdLogFile=$LOG_DIR/slurmd.log
PlugStackConfig=$DIR/plugstack.conf
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups anywhere: track processes via /proc, no task binding/limits.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
# Count single CPUs as consumable; no memory accounting, so jobs without
# --mem do not each claim the whole node (1-CPU tasks run \$CPUS at a time).
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
# No accounting / job completion database (sacct will not work).
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
# No mail program on test machines.
MailProg=/bin/true
# A node that was down comes back by itself when slurmd registers.
ReturnToService=2
# Fast cleanup for scancel/stop; short timeouts on a single host.
KillWait=5
MessageTimeout=10
SlurmdTimeout=60
# Schedule on every event (submit, job end) without the default 3 s batch
# delay: waves of 1 s array tasks start every ~2 s instead of every 3 s.
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
# Keep finished jobs visible in squeue for a while (s), then forget them.
MinJobAge=60
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
    if [[ -n ${SLURM_LOCAL_EXTRA_CONF:-} ]]; then
        printf '# From SLURM_LOCAL_EXTRA_CONF:\n%s\n' "$SLURM_LOCAL_EXTRA_CONF" >>"$CONF"
    fi
    : >"$DIR/plugstack.conf"   # empty: do not pick up /etc/slurm plugins
}

start_munged() {
    local i
    mkdir -p "$MUNGE_DIR"
    # 0755: every user must reach the socket (jobs of non-root users);
    # the key itself is 0400.
    chmod 0755 "$MUNGE_DIR"
    rm -f "$MUNGE_KEY" "$MUNGE_SOCK" "$MUNGE_SOCK.lock" "$MUNGE_PID" "$MUNGE_LOG"
    if command -v mungekey >/dev/null; then
        mungekey --create --keyfile="$MUNGE_KEY" 2>"$MUNGE_LOG" ||
            fail "mungekey failed" "$MUNGE_LOG"
    else
        dd if=/dev/urandom of="$MUNGE_KEY" bs=1024 count=1 status=none
    fi
    chmod 0400 "$MUNGE_KEY"
    # --force: tolerate "insecure" ancestor directories of DIR (e.g. a
    # group-writable build tree).
    SLURM_LOCAL_MARK="$DIR" munged --force \
        --key-file="$MUNGE_KEY" --socket="$MUNGE_SOCK" \
        --pid-file="$MUNGE_PID" --log-file="$MUNGE_LOG" \
        --seed-file="$MUNGE_SEED" \
        </dev/null >"$MUNGE_LOG.out" 2>&1 ||
        fail "munged exited with status $?" "$MUNGE_LOG.out" "$MUNGE_LOG"
    # Wait until a credential round-trips through our socket.
    for ((i = 0; i < 50; i++)); do
        if munge -n --socket="$MUNGE_SOCK" 2>/dev/null |
            unmunge --socket="$MUNGE_SOCK" >/dev/null 2>&1; then
            return 0
        fi
        sleep 0.1
    done
    fail "munged does not answer on $MUNGE_SOCK" "$MUNGE_LOG.out" "$MUNGE_LOG"
}

pick_ports() {
    local base i
    if [[ -n ${SLURM_LOCAL_PORT:-} ]]; then
        [[ $SLURM_LOCAL_PORT =~ ^[0-9]+$ ]] || fail "bad SLURM_LOCAL_PORT"
        CTLD_PORT=$SLURM_LOCAL_PORT
        SLURMD_PORT=$((CTLD_PORT + 1))
        if port_busy "$CTLD_PORT" || port_busy "$SLURMD_PORT"; then
            fail "port $CTLD_PORT or $SLURMD_PORT is already in use"
        fi
        return 0
    fi
    # Even ports in 20000..59998 starting from a pid-derived value; walk on
    # until both PORT and PORT+1 are free. (A race with another process
    # binding the port in between remains possible but unlikely.)
    base=$(( ($$ * 7919 + RANDOM) % 20000 ))
    for ((i = 0; i < 50; i++)); do
        CTLD_PORT=$((20000 + 2 * ((base + i * 97) % 20000)))
        SLURMD_PORT=$((CTLD_PORT + 1))
        if ! port_busy "$CTLD_PORT" && ! port_busy "$SLURMD_PORT"; then
            return 0
        fi
    done
    fail "no free port pair found"
}

do_start() {
    local t0 i state timeout
    t0=$SECONDS
    timeout=${SLURM_LOCAL_TIMEOUT:-30}

    [[ $(id -u) == 0 ]] || fail "must run as root (SlurmUser=root)"
    for i in munged munge unmunge slurmctld slurmd sinfo squeue scancel; do
        command -v "$i" >/dev/null || fail "$i not found (install munge, slurm-wlm)"
    done
    if live_pid "$CTLD_PID" >/dev/null || live_pid "$SLURMD_PID" >/dev/null ||
        live_pid "$MUNGE_PID" >/dev/null; then
        # Do not stop someone else's running cluster: fail without cleanup.
        echo "$PROG: cannot start: a cluster is already running in $DIR" \
            "(run '$0 stop $DIR' first)" >&2
        exit "$EXIT_SKIP"
    fi
    # 107 bytes max for a Unix socket path; slurmstepd sockets are
    # SPOOL_DIR/localhost_<job>.<step> (~30 more bytes).
    ((${#SPOOL_DIR} + 32 < 108)) || fail "DIR path too long for Unix sockets: $DIR"

    # Fresh state each time: old job state would be recovered otherwise.
    rm -rf "$STATE_DIR" "$SPOOL_DIR" "$LOG_DIR" "$ENV_FILE"
    mkdir -p "$STATE_DIR" "$SPOOL_DIR" "$LOG_DIR"
    chmod 0755 "$STATE_DIR" "$SPOOL_DIR" "$LOG_DIR"

    pick_ports
    write_conf
    start_munged

    # slurmctld: -c = do not recover old state. It daemonizes and writes
    # SlurmctldPidFile; early errors go to stderr, captured in *.out.
    SLURM_LOCAL_MARK="$DIR" slurmctld -c -f "$CONF" \
        </dev/null >"$LOG_DIR/slurmctld.out" 2>&1 ||
        fail "slurmctld exited with status $?" \
            "$LOG_DIR/slurmctld.out" "$LOG_DIR/slurmctld.log"
    SLURM_LOCAL_MARK="$DIR" slurmd -N localhost -f "$CONF" \
        </dev/null >"$LOG_DIR/slurmd.out" 2>&1 ||
        fail "slurmd exited with status $?" \
            "$LOG_DIR/slurmd.out" "$LOG_DIR/slurmd.log"

    # Wait (bounded) for the node to be idle.
    state=
    while ((SECONDS - t0 < timeout)); do
        state=$(sl sinfo -h -N -n localhost -o %T 2>/dev/null || true)
        [[ $state == idle ]] && break
        if ! live_pid "$CTLD_PID" >/dev/null && ((SECONDS - t0 > 3)); then
            fail "slurmctld died" "$LOG_DIR/slurmctld.out" "$LOG_DIR/slurmctld.log"
        fi
        if ! live_pid "$SLURMD_PID" >/dev/null && ((SECONDS - t0 > 3)); then
            fail "slurmd died" "$LOG_DIR/slurmd.out" "$LOG_DIR/slurmd.log"
        fi
        sleep 0.2
    done
    [[ $state == idle ]] ||
        fail "node not idle after ${timeout}s (state: '${state:-none}')" \
            "$LOG_DIR/slurmctld.log" "$LOG_DIR/slurmd.log" "$MUNGE_LOG"

    # Client environment. Only SLURM_CONF is required (the munge socket is
    # in slurm.conf); SLURM_LOCAL_DIR is informational.
    {
        echo "export SLURM_CONF=$CONF"
        echo "export SLURM_LOCAL_DIR=$DIR"
    } >"$ENV_FILE"
    echo "$PROG: cluster up in $((SECONDS - t0))s (ports $CTLD_PORT/$SLURMD_PORT)" >&2
    print_env
}

# ------------------------------------------------------------------ main

(($# == 2)) || usage
CMD=$1
[[ $CMD == @(start|stop|env) && -n $2 ]] || usage
check_dir_name() {
    if [[ $1 =~ [[:space:],#=] ]]; then
        echo "$PROG: DIR must not contain whitespace, ',', '#' or '=': $1" >&2
        exit 2
    fi
}
check_dir_name "$2"
if [[ $CMD == start ]]; then
    mkdir -p "$2"
fi
if [[ $CMD == start || -d $2 ]]; then
    DIR=$(cd "$2" && pwd -P)
else
    DIR=$2
fi
check_dir_name "$DIR"   # again, after resolving symlinks
set_paths

case $CMD in
start) do_start ;;
stop)
    # Nothing to do for a folder that does not exist (idempotent).
    [[ -d $DIR ]] && do_stop
    exit 0
    ;;
env)
    [[ -r $ENV_FILE ]] || { echo "$PROG: no cluster in $DIR" >&2; exit 1; }
    print_env
    ;;
esac
