#!/usr/bin/env bash
# A one-machine Slurm cluster on localhost, from Debian's packages, for Drape's tests and for trying
# `drape --batch ... --slurm` without a cluster: munged, slurmctld and one slurmd whose node is this machine.
#
#   bash scripts/slurm-local.sh start    # install slurm-wlm and munge if missing, write the config, start, wait
#   bash scripts/slurm-local.sh status   # exit 0 when the node takes jobs
#   bash scripts/slurm-local.sh stop     # stop the daemons started by `start`
#
# Needs root (the daemons run as root; nothing listens beyond loopback). The configuration goes to
# /etc/slurm/slurm.conf, marked as this script's; a slurm.conf of a real cluster is never overwritten.
# State, logs and pid files live in $DRAPE_SLURM_DIR (default /var/lib/drape-slurm).
set -euo pipefail

DIR="${DRAPE_SLURM_DIR:-/var/lib/drape-slurm}"
CONF=/etc/slurm/slurm.conf
MARK="# written by drape scripts/slurm-local.sh"

die() { echo "slurm-local: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || die "needs root (it starts munged, slurmctld and slurmd)"

install_packages() {
  local missing=()
  for p in slurm-wlm munge; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "slurm-local: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
}

write_config() {
  if [ -f "$CONF" ] && ! head -1 "$CONF" | grep -qF "$MARK"; then
    die "$CONF belongs to another cluster; not overwriting it (use that cluster, or move the file away)"
  fi
  local host cpus mem
  host="$(hostname -s)"
  cpus="$(nproc)"
  mem="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"
  mkdir -p "$DIR/ctld" "$DIR/d" /etc/slurm
  cat > "$CONF.tmp" <<EOF
$MARK
ClusterName=drape-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$DIR/ctld
SlurmdSpoolDir=$DIR/d
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=10
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  mv "$CONF.tmp" "$CONF"
}

start_munge() {
  if pgrep -x munged >/dev/null; then return 0; fi
  if [ ! -s /etc/munge/munge.key ]; then mungekey --create --keyfile=/etc/munge/munge.key; fi
  chown munge:munge /etc/munge/munge.key
  chmod 400 /etc/munge/munge.key
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  runuser -u munge -- /usr/sbin/munged
}

node_ready() {
  local state
  state="$(sinfo -h -N -o '%T' 2>/dev/null | head -1)"
  case "$state" in idle|mixed|allocated|completing) return 0 ;; *) return 1 ;; esac
}

start() {
  install_packages
  write_config
  start_munge
  pgrep -x slurmctld >/dev/null || /usr/sbin/slurmctld
  pgrep -x slurmd >/dev/null || /usr/sbin/slurmd
  for _ in $(seq 1 60); do
    if node_ready; then
      echo "slurm-local: node $(hostname -s) up with $(nproc) CPUs in partition 'local' (config $CONF)"
      return 0
    fi
    # A node that went down (an earlier unclean stop) is put back into service.
    scontrol update nodename="$(hostname -s)" state=resume >/dev/null 2>&1 || true
    sleep 1
  done
  sinfo -N >&2 || true
  tail -5 "$DIR/slurmctld.log" "$DIR/slurmd.log" >&2 2>/dev/null || true
  die "the node did not come up in 60 s (logs in $DIR)"
}

stop() {
  for d in slurmd slurmctld; do
    if pgrep -x "$d" >/dev/null; then pkill -x "$d" || true; fi
  done
  for _ in $(seq 1 20); do
    pgrep -x slurmd >/dev/null || pgrep -x slurmctld >/dev/null || break
    sleep 0.5
  done
  pkill -x munged || true
  for _ in $(seq 1 20); do
    pgrep -x munged >/dev/null || break
    sleep 0.5
  done
  echo "slurm-local: stopped"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) node_ready ;;
  *) die "usage: $0 start|status|stop" ;;
esac
