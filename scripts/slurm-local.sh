#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for the render-farm tests (docs/farm.md):
#   scripts/slurm-local.sh start   munged, slurmctld and slurmd on localhost; prints `export SLURM_CONF=...`
#   scripts/slurm-local.sh stop    stops the daemons it started (munged only if it started it)
# Its configuration and state live in $RIMU_SLURM_DIR (default /tmp/rimu-slurm), never in /etc/slurm, so it does
# not touch a machine's real cluster: clients find it through SLURM_CONF. One node (this host) with this machine's
# cores, one partition "rimu", no accounting database (sacct then reports that accounting is off).
# Needs root (slurmd runs jobs as their users) and the packages in scripts/install-deps.sh.
# Exit codes: 0 running, 1 usage, 2 a daemon could not start (the caller decides whether that is a skip).
set -u
dir=${RIMU_SLURM_DIR:-/tmp/rimu-slurm}
conf=$dir/slurm.conf
node=$(hostname -s)

stop() {
  for daemon in slurmd slurmctld; do
    if [ -f "$dir/$daemon.pid" ]; then
      kill "$(cat "$dir/$daemon.pid")" 2>/dev/null
      rm -f "$dir/$daemon.pid"
    fi
  done
}

stop_all() {
  stop
  # munged only if this script started it (a machine's own munged is left alone).
  if [ -f "$dir/munged.started" ] && [ -f /run/munge/munged.pid ]; then
    kill "$(cat /run/munge/munged.pid)" 2>/dev/null
    rm -f "$dir/munged.started"
  fi
}

start() {
  for tool in munged slurmctld slurmd sinfo; do
    command -v "$tool" >/dev/null || [ -x "/usr/sbin/$tool" ] || { echo "slurm-local: $tool is not installed (scripts/install-deps.sh)"; exit 2; }
  done
  [ "$(id -u)" = 0 ] || { echo "slurm-local: must run as root (slurmd starts jobs as their users)"; exit 2; }
  mkdir -p "$dir/state" "$dir/spool"

  # munge: the credentials Slurm's daemons and clients exchange. Reuse a running munged.
  if ! (munge -n | unmunge) >/dev/null 2>&1; then
    [ -s /etc/munge/munge.key ] || /usr/sbin/mungekey --create >/dev/null 2>&1 || {
      dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null; }
    chown munge:munge /etc/munge/munge.key 2>/dev/null; chmod 400 /etc/munge/munge.key
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null
    runuser -u munge -- /usr/sbin/munged || /usr/sbin/munged --force || { echo "slurm-local: munged did not start"; exit 2; }
    touch "$dir/munged.started"
    sleep 1
    (munge -n | unmunge) >/dev/null 2>&1 || { echo "slurm-local: munge credentials do not round-trip"; exit 2; }
  fi

  local memory_mb
  memory_mb=$(awk '/MemTotal/ { print int($2 / 1024 * 0.8) }' /proc/meminfo)
  cat > "$conf" <<CONF
# Written by scripts/slurm-local.sh: a one-node cluster on $node for Rimu's render-farm tests.
ClusterName=rimulocal
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=${RIMU_SLURMCTLD_PORT:-6817}
SlurmdPort=${RIMU_SLURMD_PORT:-6818}
# No cgroups (containers and CI runners often lack them): processes are tracked by parent id.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
KillWait=30
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory_mb State=UNKNOWN
PartitionName=rimu Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
  stop
  /usr/sbin/slurmctld -f "$conf" -i || { echo "slurm-local: slurmctld did not start; see $dir/slurmctld.log"; exit 2; }
  /usr/sbin/slurmd -f "$conf" -N "$node" || { echo "slurm-local: slurmd did not start; see $dir/slurmd.log"; exit 2; }
  for _ in $(seq 1 30); do
    state=$(SLURM_CONF=$conf sinfo -h -n "$node" -o %t 2>/dev/null)
    case "$state" in idle*|mix*|alloc*) echo "export SLURM_CONF=$conf"; return 0 ;; esac
    sleep 1
  done
  echo "slurm-local: the node is not idle after 30 s (state '${state:-none}'); see $dir/slurmctld.log and $dir/slurmd.log"
  tail -5 "$dir/slurmctld.log" "$dir/slurmd.log" 2>/dev/null
  exit 2
}

case "${1:-}" in
  start) start ;;
  stop) stop_all ;;
  *) echo "usage: scripts/slurm-local.sh start|stop"; exit 1 ;;
esac
