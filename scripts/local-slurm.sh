#!/usr/bin/env bash
# A single-node Slurm on this machine, for tests (.ci/run, tests/slurm.rs): installs Debian's slurm-wlm and munge if absent,
# writes a minimal config for the local host into a state folder, and starts munged, slurmctld
# and slurmd. Needs root (as on CI and the development machines). Tested with Slurm 22.05.
#
#   local-slurm.sh start [STATE_DIR]   # prints: export SLURM_CONF=STATE_DIR/slurm.conf
#   local-slurm.sh stop  [STATE_DIR]   # stops the daemons it started (by their pid files)
#
# After `start`, export SLURM_CONF as printed; sbatch/squeue/sinfo then talk to this cluster.
set -euo pipefail
cmd=${1:-start}
S=${2:-/tmp/tribo-slurm}
conf=$S/slurm.conf

start() {
  if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq slurm-wlm munge >/dev/null
  fi
  mkdir -p "$S"/{spool,state,log}
  local host cpus mem
  host=$(hostname)
  cpus=$(nproc)
  mem=$(( $(awk '/MemTotal/{print $2}' /proc/meminfo) / 1024 * 8 / 10 ))
  cat >"$conf" <<CONF
ClusterName=local
SlurmctldHost=$host
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SlurmctldPidFile=$S/slurmctld.daemon.pid
SlurmdPidFile=$S/slurmd.daemon.pid
SlurmdSpoolDir=$S/spool
StateSaveLocation=$S/state
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
SlurmUser=root
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  mkdir -p /etc/munge /run/munge /var/log/munge /var/lib/munge
  [ -s /etc/munge/munge.key ] || dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null
  chown -R munge:munge /etc/munge /run/munge /var/log/munge /var/lib/munge 2>/dev/null || true
  chmod 400 /etc/munge/munge.key
  # Each daemon runs in the foreground, in the background of this shell, so that its pid is known
  # and `stop` ends exactly what `start` started.
  if ! (munge -n | unmunge) >/dev/null 2>&1; then
    munged -F --force >"$S/log/munged.log" 2>&1 &
    echo $! >"$S/munged.pid"
    for _ in $(seq 50); do (munge -n | unmunge) >/dev/null 2>&1 && break; sleep 0.2; done
  fi
  slurmctld -D -f "$conf" >/dev/null 2>&1 &
  echo $! >"$S/slurmctld.pid"
  slurmd -D -f "$conf" >/dev/null 2>&1 &
  echo $! >"$S/slurmd.pid"
  for _ in $(seq 30); do
    if SLURM_CONF=$conf sinfo -h -o %T 2>/dev/null | grep -qE 'idle|mixed|alloc'; then
      echo "export SLURM_CONF=$conf"; return 0
    fi
    sleep 1
  done
  echo "slurm did not come up; logs in $S/log" >&2
  return 1
}

stop() {
  for p in slurmd slurmctld munged; do
    if [ -f "$S/$p.pid" ]; then kill "$(cat "$S/$p.pid")" 2>/dev/null || true; rm -f "$S/$p.pid"; fi
  done
}

case $cmd in start) start ;; stop) stop ;; *) echo "usage: $0 start|stop [STATE_DIR]" >&2; exit 2 ;; esac
