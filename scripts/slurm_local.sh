#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for tests and trying `bsg sweep --slurm`.
#   scripts/slurm_local.sh start [DIR]   as root: munged (with a generated key), slurmctld
#                                        and slurmd with a generated slurm.conf; everything
#                                        (state, spool, logs, pid files) under DIR (default:
#                                        a new temporary directory); prints SLURM_CONF=...
#   scripts/slurm_local.sh stop DIR      stops the three daemons and removes DIR
# No cgroups, no accounting: squeue and the sweep's files tell the state.
set -euo pipefail
command="${1:-}"
die() { echo "slurm_local.sh: $*" >&2; exit 1; }

pid_of() { [ -f "$1" ] && cat "$1" 2>/dev/null || true; }

stop_cluster() {
  local dir="$1"
  [ -d "$dir" ] || die "no cluster directory $dir"
  for name in slurmd slurmctld munged; do
    local pid; pid="$(pid_of "$dir/$name.pid")"
    [ -n "$pid" ] && kill "$pid" 2>/dev/null || true
  done
  for _ in $(seq 50); do
    local alive=0
    for name in slurmd slurmctld munged; do
      local pid; pid="$(pid_of "$dir/$name.pid")"
      [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null && alive=1
    done
    [ "$alive" = 0 ] && break
    sleep 0.1
  done
  for name in slurmd slurmctld munged; do  # whatever did not end in 5 s
    local pid; pid="$(pid_of "$dir/$name.pid")"
    [ -n "$pid" ] && kill -9 "$pid" 2>/dev/null || true
  done
  rm -rf "$dir"
}

case "$command" in
  start)
    [ "$(id -u)" = 0 ] || die "start needs root (munged and slurmd run as root here)"
    for program in munged mungekey slurmctld slurmd sbatch; do
      command -v "$program" >/dev/null || die "$program not found: install slurm-wlm and munge (scripts/install_deps.sh)"
    done
    dir="${2:-$(mktemp -d /tmp/bsg-slurm.XXXXXX)}"
    mkdir -p "$dir"/{munge,state,spool,log}
    chmod 700 "$dir/munge"
    mungekey --create --keyfile="$dir/munge/munge.key" --force >/dev/null 2>&1 ||
      dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
    chmod 400 "$dir/munge/munge.key"
    munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
      --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed" --force
    host="$(hostname -s)"
    cpus="$(nproc)"
    memory_mb="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"
    port_base=$(( 20000 + RANDOM % 20000 ))
    cat > "$dir/slurm.conf" <<CONF
ClusterName=bsglocal
SlurmctldHost=$host
SlurmctldPort=$port_base
SlurmdPort=$(( port_base + 1 ))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
KillWait=30
MinJobAge=300
MaxArraySize=100001
NodeName=$host CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
    export SLURM_CONF="$dir/slurm.conf"
    slurmctld -f "$SLURM_CONF"
    slurmd -f "$SLURM_CONF"
    for _ in $(seq 100); do
      sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)' && break
      sleep 0.1
    done
    if ! sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
      echo "slurm_local.sh: the node did not come up; logs in $dir/log:" >&2
      tail -n 5 "$dir"/log/*.log >&2 || true
      stop_cluster "$dir"
      exit 1
    fi
    echo "slurm_local.sh: a one-node cluster ($host, $cpus CPUs) runs from $dir"
    echo "  use it:  export SLURM_CONF=$dir/slurm.conf"
    echo "  stop it: scripts/slurm_local.sh stop $dir"
    echo "SLURM_CONF=$dir/slurm.conf"
    ;;
  stop)
    [ -n "${2:-}" ] || die "usage: slurm_local.sh stop DIR"
    stop_cluster "$2"
    ;;
  *) die "usage: slurm_local.sh start [DIR] | stop DIR" ;;
esac
