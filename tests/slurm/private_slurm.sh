#!/usr/bin/env bash
# Start or stop a private, single-node Slurm cluster that lives entirely in a
# state folder, so tests can exercise sbatch/squeue/scancel for real without
# touching /etc/slurm, /etc/munge or any Slurm/MUNGE daemon the host runs.
#
#   private_slurm.sh start STATE_DIR   # prints "export SLURM_CONF=..." lines,
#                                      # also written to STATE_DIR/env.sh
#   private_slurm.sh stop  STATE_DIR   # idempotent
#
# Everything lives under STATE_DIR: slurm.conf, munge/ (key, socket, log),
# ctld/ (StateSaveLocation), slurmd/ (spool: job scripts run from here as
# slurmd/jobNNNNN/slurm_script), log/, run/ (pid files), env.sh.  The
# cluster has one node with nproc CPUs, MaxArraySize=1001 and KillWait=5;
# jobs run as root.
#
# Typical use:
#   eval "$(bash tests/slurm/private_slurm.sh start "$dir")" || exit $?
#   trap 'bash tests/slurm/private_slurm.sh stop "$dir"' EXIT
#
# Exit status 77 means "this host cannot run a private Slurm" (not root,
# binaries missing, a daemon died or never became ready); test drivers treat
# it as a skip.  The one-line reason goes to stderr.
#
# Environment knobs:
#   PRIVATE_SLURM_TIMEOUT    seconds to wait for the node to become idle (30)
#   PRIVATE_SLURM_MAX_ARRAY  the site's MaxArraySize (Slurm's default, 1001)

set -u

readonly SKIP=77

die_skip() {
    printf 'private Slurm cannot start here: %s\n' "$*" >&2
    exit "$SKIP"
}

usage() {
    printf 'usage: %s start|stop STATE_DIR\n' "${0##*/}" >&2
    exit 2
}

# Last lines of a log squeezed onto one line, so the skip reason stays a
# single line that test logs show in full.  Debian's Slurm logs harmless
# PMIx load errors at every start; they would crowd out the real cause.
log_tail() {
    [[ -s $1 ]] || { printf '(%s is empty)' "${1##*/}"; return; }
    grep -v -e 'pmix' -e 'MPI: Cannot create context' -- "$1" |
        tail -n 4 | tr '\n' ' ' | tr -s ' ' | cut -c1-600
}

# A pid from a pid file counts as ours only when its command line names a
# path inside this state folder, so a recycled pid never gets killed.
own_pid() {
    local pid_file=$1 pid
    [[ -r $pid_file ]] || return 1
    read -r pid <"$pid_file" 2>/dev/null || return 1
    [[ $pid =~ ^[0-9]+$ ]] || return 1
    alive "$pid" || return 1
    tr '\0' ' ' 2>/dev/null <"/proc/$pid/cmdline" | grep -qF -- "$STATE/" || return 1
    printf '%s\n' "$pid"
}

# Zombies count as gone: a daemon that forked into the background is
# reparented to pid 1, which in some containers never reaps it.
alive() {
    local stat
    stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
    stat=${stat##*) }
    [[ ${stat:0:1} != Z ]]
}

# Leftovers of jobs: slurmstepd inherits the SLURM_CONF we give slurmd, and
# job processes inherit it from sbatch along with SLURM_JOB_ID.  proctrack/
# linuxproc follows parent links only, so a job child that survives SIGTERM
# after its batch shell died is orphaned and never gets the SIGKILL; this
# scan is what catches it.  Our own ancestry is spared because a caller that
# runs inside such a job also carries these variables.
stray_pids() {
    local dir pid env spare=" " p=$BASHPID
    while [[ $p =~ ^[1-9][0-9]*$ && $p != 1 ]]; do
        spare+="$p "
        p=$(awk '{print $4}' "/proc/$p/stat" 2>/dev/null)
    done
    for dir in /proc/[0-9]*; do
        pid=${dir#/proc/}
        [[ $spare == *" $pid "* ]] && continue
        alive "$pid" || continue
        env=$(tr '\0' '\n' 2>/dev/null <"$dir/environ") || continue
        grep -qxF "SLURM_CONF=$CONF" <<<"$env" || continue
        if [[ $(cat "$dir/comm" 2>/dev/null) == slurmstepd ]] ||
            grep -q '^SLURM_JOB_ID=' <<<"$env"; then
            printf '%s\n' "$pid"
        fi
    done
}

# Bounded: the given signal first (TERM lets daemons save state and remove
# their sockets), SIGKILL after 5 s so stop never hangs.
terminate() {
    local sig=$1 pid i left
    shift
    (($#)) || return 0
    kill "-$sig" "$@" 2>/dev/null
    for ((i = 0; i < 70; i++)); do
        left=()
        for pid in "$@"; do
            alive "$pid" && left+=("$pid")
        done
        ((${#left[@]})) || return 0
        ((i == 50)) && kill -KILL "${left[@]}" 2>/dev/null
        sleep 0.1
    done
}

do_stop() {
    [[ -d $STATE ]] || return 0
    local pid name deadline

    # Cancel jobs while the controller still answers: killing slurmd alone
    # would leave slurmstepd and the job's processes running.
    if own_pid "$RUN/slurmctld.pid" >/dev/null; then
        local jobs
        jobs=$(SLURM_CONF=$CONF timeout 10 squeue -h -o %i 2>/dev/null)
        if [[ -n $jobs ]]; then
            # shellcheck disable=SC2086  # one job id per word
            SLURM_CONF=$CONF timeout 10 scancel $jobs 2>/dev/null
            deadline=$((SECONDS + 15))
            while ((SECONDS < deadline)); do
                [[ -z $(SLURM_CONF=$CONF timeout 5 squeue -h -o %i 2>/dev/null) ]] && break
                sleep 0.1
            done
        fi
    fi

    local daemons=()
    for name in slurmd slurmctld; do
        pid=$(own_pid "$RUN/$name.pid") && daemons+=("$pid")
    done
    terminate TERM "${daemons[@]}"
    mapfile -t daemons < <(stray_pids)
    terminate KILL "${daemons[@]}"
    daemons=()
    pid=$(own_pid "$MUNGE_DIR/munged.pid") && daemons+=("$pid")
    terminate TERM "${daemons[@]}"
    rm -f "$RUN/slurmctld.pid" "$RUN/slurmd.pid" "$MUNGE_DIR/munged.pid"
    return 0
}

# Ports below the ephemeral range, not listened on now; a clash with the
# system Slurm (6817/6818) is impossible by construction.
free_ports() {
    local want=$1 used port tries
    used=" $(ss -Hltn 2>/dev/null | awk '{n = split($4, a, ":"); print a[n]}' | tr '\n' ' ') "
    for ((tries = 0; tries < 200 && want > 0; tries++)); do
        port=$((20000 + RANDOM % 12000))
        [[ $used == *" $port "* ]] && continue
        used+="$port "
        printf '%s\n' "$port"
        ((want--))
    done
}

start_munged() {
    if ! mkdir -p "$MUNGE_DIR" || ! chmod 0755 "$MUNGE_DIR"; then
        die_skip "cannot create $MUNGE_DIR"
    fi
    if [[ ! -s $MUNGE_DIR/munge.key ]]; then
        (umask 077 && head -c 1024 /dev/urandom >"$MUNGE_DIR/munge.key") ||
            die_skip "cannot write the munge key"
    fi
    chmod 0400 "$MUNGE_DIR/munge.key"
    # --force: the state folder usually sits under /tmp or a build tree whose
    # ancestors munged would reject as "insecure"; that is fine for a test key.
    munged --force \
        --socket="$MUNGE_SOCKET" \
        --key-file="$MUNGE_DIR/munge.key" \
        --pid-file="$MUNGE_DIR/munged.pid" \
        --log-file="$MUNGE_DIR/munged.log" \
        --seed-file="$MUNGE_DIR/munged.seed" \
        </dev/null >>"$MUNGE_DIR/munged.stdio" 2>&1 ||
        die_skip "munged failed: $(log_tail "$MUNGE_DIR/munged.log") $(log_tail "$MUNGE_DIR/munged.stdio")"
    local i
    for ((i = 0; i < 50; i++)); do
        munge -n -S "$MUNGE_SOCKET" 2>/dev/null | unmunge -S "$MUNGE_SOCKET" >/dev/null 2>&1 &&
            return 0
        sleep 0.1
    done
    do_stop
    die_skip "munged does not answer on $MUNGE_SOCKET: $(log_tail "$MUNGE_DIR/munged.log")"
}

write_config() {
    local node=$1 cpus=$2 ctld_port=$3 slurmd_port=$4
    : >"$STATE/plugstack.conf"
    cat >"$CONF" <<EOF
# Generated by tests/slurm/private_slurm.sh; private single-node test cluster.
ClusterName=privtest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/slurmd
SlurmctldPidFile=$RUN/slurmctld.pid
SlurmdPidFile=$RUN/slurmd.pid
SlurmctldLogFile=$LOGS/slurmctld.log
SlurmdLogFile=$LOGS/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$STATE/plugstack.conf
MailProg=/bin/true
# No cgroups: sandboxes and containers rarely allow them, and tests only need
# process tracking and cancellation.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
JobContainerType=job_container/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
# Consumable CPUs so several 1-CPU array tasks share the node.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
# Slurm batches batch-job scheduling for 3 s by default, which would add
# seconds to every short test job and to every wave of array tasks.
SchedulerParameters=batch_sched_delay=0
MaxArraySize=${PRIVATE_SLURM_MAX_ARRAY:-1001}
ReturnToService=2
# Short grace between SIGTERM and SIGKILL keeps cancels and stop quick.
KillWait=5
# Trust this file over the detected hardware (CPUs only, small memory).
SlurmdParameters=config_overrides
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
EOF
}

start_daemon() {
    local name=$1
    shift
    # The daemons fork into the background themselves; stdio goes to a file
    # so no caller pipe is held open by them.
    SLURM_CONF=$CONF "$name" -f "$CONF" "$@" </dev/null >>"$LOGS/$name.stdio" 2>&1 ||
        fail_start "$name exited at start"
    local i
    for ((i = 0; i < 50; i++)); do
        own_pid "$RUN/$name.pid" >/dev/null && return 0
        sleep 0.1
    done
    fail_start "$name is not running after start (no live process behind its pid file)"
}

fail_start() {
    local daemon=${1%% *} why
    why="$1: $(log_tail "$LOGS/$daemon.log") $(log_tail "$LOGS/$daemon.stdio")"
    do_stop
    die_skip "$why"
}

do_start() {
    [[ $(id -u) == 0 ]] || die_skip "needs root (daemons run as SlurmUser=root)"
    local tool
    for tool in munged munge unmunge slurmctld slurmd sinfo squeue scancel ss; do
        command -v "$tool" >/dev/null 2>&1 || die_skip "missing $tool"
    done
    # Unix socket paths are limited to 108 bytes; slurmd puts per-step
    # sockets under its spool folder with names of about 40 bytes.
    ((${#MUNGE_SOCKET} < 100 && ${#STATE} < 60)) ||
        die_skip "state folder path too long for Unix sockets: $STATE"

    # A previous run in the same folder must not linger.
    do_stop
    mkdir -p "$STATE/ctld" "$STATE/slurmd" "$RUN" "$LOGS" ||
        die_skip "cannot create folders under $STATE"
    rm -rf "${STATE:?}/ctld/"* "${STATE:?}/slurmd/"*
    rm -f "$LOGS"/*

    start_munged
    local node ports
    node=$(hostname -s 2>/dev/null)
    [[ $node =~ ^[A-Za-z0-9][A-Za-z0-9-]*$ ]] || node=privnode
    mapfile -t ports < <(free_ports 2)
    ((${#ports[@]} == 2)) || { do_stop; die_skip "no free TCP ports"; }
    write_config "$node" "$(nproc)" "${ports[0]}" "${ports[1]}"

    start_daemon slurmctld
    start_daemon slurmd -N "$node"

    local timeout=${PRIVATE_SLURM_TIMEOUT:-30} deadline state=""
    deadline=$((SECONDS + timeout))
    while ((SECONDS < deadline)); do
        own_pid "$RUN/slurmctld.pid" >/dev/null || fail_start "slurmctld died"
        own_pid "$RUN/slurmd.pid" >/dev/null || fail_start "slurmd died"
        state=$(SLURM_CONF=$CONF timeout 5 sinfo -h -N -n "$node" -o %T 2>/dev/null)
        [[ $state == idle ]] && break
        sleep 0.2
    done
    [[ $state == idle ]] ||
        fail_start "slurmd node $node not idle after ${timeout}s (state '${state}')"

    printf 'export SLURM_CONF=%q\nexport PRIVATE_SLURM_STATE=%q\n' "$CONF" "$STATE" |
        tee "$STATE/env.sh"
}

if (($# != 2)) || [[ $1 != start && $1 != stop ]]; then usage; fi
[[ $1 == stop && ! -d $2 ]] && exit 0
[[ $1 == start ]] && mkdir -p -- "$2" 2>/dev/null
STATE=$(cd -- "$2" 2>/dev/null && pwd -P) || die_skip "cannot use state folder $2"
readonly STATE
readonly CONF=$STATE/slurm.conf
readonly RUN=$STATE/run
readonly LOGS=$STATE/log
readonly MUNGE_DIR=$STATE/munge
readonly MUNGE_SOCKET=$MUNGE_DIR/munged.sock

if [[ $1 == start ]]; then do_start; else do_stop; fi
