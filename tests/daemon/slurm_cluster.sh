# A private single-node Slurm cluster for a test (sourced after common.sh).
#
# start_slurm DIR: munged, slurmctld and slurmd in the foreground, each with
# its state under DIR, a slurm.conf generated for this host (ports from a free
# range, a cluster and node name of their own, so that a second copy of the
# test runs beside this one), proctrack/linuxproc and task/none (no cgroups:
# it runs in a container), no accounting (no slurmdbd).  Exports SLURM_CONF;
# sets SLURM_SKIP (why it could not start) and returns 1 when it cannot start.
# SLURM_CPUS (default 8) sets the node's CPUs (more than the machine has is fine:
# SlurmdParameters=config_overrides).
# stop_slurm: cancels every job of the cluster, waits for them to end, then
# stops the daemons (SIGTERM, SIGKILL after 5 s).  Call it on every exit path
# (the test's trap).
SLURM_PIDS=""
SLURM_DIR=""
SLURM_SKIP=""

slurm_port_pair() {
    # two consecutive free ports above 20000 (slurmctld, slurmd)
    "$PY" - <<'PYEOF'
import random, socket
for _ in range(200):
    p = random.randrange(20000, 60000, 2)
    try:
        ss = []
        for q in (p, p + 1):
            s = socket.socket(); s.bind(("", q)); ss.append(s)
        print(p); break
    except OSError:
        pass
    finally:
        for s in ss: s.close()
PYEOF
}

start_slurm() {
    SLURM_DIR=$1
    local t
    for t in munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
        command -v "$t" >/dev/null 2>&1 || { SLURM_SKIP="$t missing (Debian: slurm-wlm, munge; deploy/install-deps.sh)"; return 1; }
    done
    [ "$(id -u)" = 0 ] || { SLURM_SKIP="a private slurmd needs root (it starts jobs as their user)"; return 1; }
    mkdir -p "$SLURM_DIR"/{munge,state,spool,log}
    chmod 700 "$SLURM_DIR/munge"
    chmod 755 "$SLURM_DIR"
    head -c 1024 /dev/urandom >"$SLURM_DIR/munge/munge.key"
    chmod 600 "$SLURM_DIR/munge/munge.key"
    munged --foreground --force --socket="$SLURM_DIR/munge/sock" \
        --key-file="$SLURM_DIR/munge/munge.key" --pid-file="$SLURM_DIR/munge/pid" \
        --log-file="$SLURM_DIR/log/munged.log" --seed-file="$SLURM_DIR/munge/seed" \
        >"$SLURM_DIR/log/munged.out" 2>&1 &
    SLURM_PIDS="$SLURM_PIDS $!"
    local port; port=$(slurm_port_pair)
    local host; host=$(hostname -s)
    SLURM_NODE=tl$port
    cat >"$SLURM_DIR/slurm.conf" <<EOC
ClusterName=tlsph$port
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$SLURM_DIR/munge/sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool
SlurmctldPidFile=$SLURM_DIR/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/slurmd.pid
SlurmctldLogFile=$SLURM_DIR/log/slurmctld.log
SlurmdLogFile=$SLURM_DIR/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
SlurmdParameters=config_overrides
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
KillWait=2
MinJobAge=600
InactiveLimit=0
MessageTimeout=30
NodeName=$SLURM_NODE NodeHostname=$host NodeAddr=127.0.0.1 CPUs=${SLURM_CPUS:-8} RealMemory=8000 State=UNKNOWN
PartitionName=test Nodes=$SLURM_NODE Default=YES MaxTime=INFINITE State=DOWN
EOC
    export SLURM_CONF=$SLURM_DIR/slurm.conf
    slurmctld -D -i >"$SLURM_DIR/log/slurmctld.out" 2>&1 &
    SLURM_PIDS="$SLURM_PIDS $!"
    slurmd -D -N "$SLURM_NODE" >"$SLURM_DIR/log/slurmd.out" 2>&1 &
    SLURM_PIDS="$SLURM_PIDS $!"
    # up when the node is idle (the partition is DOWN until the test opens it);
    # a hang detector: 60 s of nothing means this machine cannot run Slurm
    local i
    for i in $(seq 600); do
        [ "$(sinfo -h -n "$SLURM_NODE" -o %T 2>/dev/null)" = idle ] && return 0
        sleep 0.1
    done
    SLURM_SKIP="slurmctld/slurmd did not come up: $(tail -3 "$SLURM_DIR/log/slurmctld.out" "$SLURM_DIR/log/slurmd.out" 2>/dev/null | tr '\n' ' ')"
    return 1
}

stop_slurm() {
    [ -n "$SLURM_PIDS" ] || return 0
    # (bounded: a controller that never came up must not hold the exit)
    if [ -n "${SLURM_CONF:-}" ] && timeout 10 scancel --full --user="$(id -u)" >/dev/null 2>&1; then
        local end=$(($(date +%s) + 30))
        while [ "$(date +%s)" -le "$end" ]; do
            [ -z "$(timeout 10 squeue -h -t PD,R,CG,CF,S -o %i 2>/dev/null)" ] && break
            sleep 0.1
        done
    fi
    local p
    for p in $SLURM_PIDS; do kill -TERM "$p" 2>/dev/null; done
    for p in $SLURM_PIDS; do
        for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$p" 2>/dev/null
        wait "$p" 2>/dev/null
    done
    SLURM_PIDS=""
}
