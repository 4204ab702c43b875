#!/usr/bin/env bash
# A one-node Slurm on this machine, for testing `mixmesh batch --slurm` against the
# real scheduler rather than a mock:
#
#   scripts/slurm-cluster.sh install   # Debian's slurm-wlm, munge, slurmdbd, mariadb-server (apt-get, idempotent)
#   scripts/slurm-cluster.sh start     # configs for this host, then the daemons
#   scripts/slurm-cluster.sh stop      # stops the daemons that `start` started
#
# It works in a container without systemd or cgroups: the daemons are started by
# hand, processes are tracked through /proc (proctrack/linuxproc) and tasks are not
# confined (task/none). Jobs are accounted through slurmdbd and MariaDB, because
# that is what `sacct` reads: the text-file alternatives do not know job arrays. A
# machine whose Slurm answers already is left alone, and so are configs this script
# did not write.
set -euo pipefail

marker="# Written by mixmesh scripts/slurm-cluster.sh"
config=/etc/slurm/slurm.conf
database_config=/etc/slurm/slurmdbd.conf
state=/var/lib/slurm
logs=/var/log/slurm
# Pid files of the daemons this script started, one a line, so `stop` ends those
# and nothing else.
started=/run/mixmesh-slurm-started

sudo_prefix=()
[ "$(id -u)" -eq 0 ] || sudo_prefix=(sudo)
as_root() { "${sudo_prefix[@]}" "$@"; }

install_packages() {
  local missing=()
  for package in slurm-wlm munge slurmdbd mariadb-server; do
    dpkg-query -W -f='${Status}' "$package" 2> /dev/null | grep -q "install ok installed" || missing+=("$package")
  done
  [ "${#missing[@]}" -eq 0 ] && return 0
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -q
  as_root apt-get install -y -q --no-install-recommends "${missing[@]}"
}

ours() { [ ! -f "$1" ] || grep -qF "$marker" "$1"; }

# The node line comes from `slurmd -C`, so CPUs and memory match what slurmd will
# find; a node configured with more than it has would be drained.
write_configs() {
  if ! ours "$config" || ! ours "$database_config"; then
    echo "slurm-cluster: $config or $database_config was not written by this script; using them as they are" >&2
    return 0
  fi
  local host node
  host=$(hostname -s)
  node=$(/usr/sbin/slurmd -C | head -n 1)
  as_root mkdir -p "$(dirname "$config")" "$state/slurmctld" "$state/slurmd" "$logs"
  as_root tee "$config" > /dev/null << END
$marker: one node on this machine.
ClusterName=mixmesh
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=localhost
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
StateSaveLocation=$state/slurmctld
SlurmdSpoolDir=$state/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$logs/slurmctld.log
SlurmdLogFile=$logs/slurmd.log
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
END
  # MariaDB lets root in through its socket, so slurmdbd needs no password.
  as_root tee "$database_config" > /dev/null << END
$marker: accounting for the one-node Slurm.
AuthType=auth/munge
DbdHost=localhost
SlurmUser=root
StorageType=accounting_storage/mysql
StorageHost=localhost
StorageUser=root
StorageLoc=slurm_acct_db
PidFile=/run/slurmdbd.pid
LogFile=$logs/slurmdbd.log
END
  as_root chmod 600 "$database_config"
}

running() { [ -f "$1" ] && as_root kill -0 "$(cat "$1")" 2> /dev/null; }

# Starts a daemon unless its pid file names a live process, and remembers it. The
# daemons write their own logs; their standard streams must not hold a caller's
# pipe open (ctest would wait for them).
start_daemon() {
  local pid_file=$1
  shift
  running "$pid_file" && return 0
  as_root "$@" < /dev/null > /dev/null 2>&1
  echo "$pid_file" | as_root tee -a "$started" > /dev/null
}

# Runs a check once a second, for up to $1 seconds, until it succeeds.
wait_for() {
  local seconds=$1
  shift
  for _ in $(seq "$seconds"); do
    "$@" > /dev/null 2>&1 && return 0
    sleep 1
  done
  return 1
}

# True when the controller answers and a node is ready for jobs.
node_ready() {
  scontrol ping 2> /dev/null | grep -q "is UP" \
    && sinfo --noheader --format=%T 2> /dev/null | grep -Eq "^(idle|mixed|allocated)"
}

resume_node() {
  # A node that was down when slurmctld last saved its state stays down until told.
  as_root scontrol update nodename="$(hostname -s)" state=resume > /dev/null 2>&1 || true
  node_ready
}

fail() {
  echo "slurm-cluster: $1; see the logs in $logs" >&2
  return 1
}

start() {
  if node_ready; then
    echo "slurm-cluster: Slurm is already up"
    return 0
  fi
  # By path: /usr/sbin is not on every user's PATH.
  if [ ! -x /usr/sbin/slurmctld ] || [ ! -x /usr/sbin/slurmdbd ] || [ ! -x /usr/sbin/mariadbd ]; then
    echo "slurm-cluster: Slurm is not installed (run: $0 install)" >&2
    return 1
  fi
  write_configs
  as_root install -d -o munge -g munge -m 0755 /run/munge
  # Debian's munge creates its key when installed; an older or stripped install may not.
  as_root test -f /etc/munge/munge.key || as_root /usr/sbin/runuser -u munge -- /usr/sbin/mungekey --create
  as_root install -d -o mysql -g mysql -m 0755 /run/mysqld
  as_root mkdir -p "$logs"
  as_root touch "$logs/mariadb.log"
  as_root chown mysql:mysql "$logs/mariadb.log"
  start_daemon /run/munge/munged.pid /usr/sbin/runuser -u munge -- /usr/sbin/munged
  start_daemon /run/mysqld/mysqld.pid setsid --fork /usr/sbin/mariadbd --user=mysql --skip-networking \
    --pid-file=/run/mysqld/mysqld.pid --socket=/run/mysqld/mysqld.sock --log-error="$logs/mariadb.log"
  wait_for 60 as_root mysqladmin --socket=/run/mysqld/mysqld.sock ping || fail "MariaDB did not start" || return 1
  start_daemon /run/slurmdbd.pid /usr/sbin/slurmdbd
  wait_for 60 sacctmgr --noheader show cluster || fail "slurmdbd did not start" || return 1
  start_daemon /run/slurmctld.pid /usr/sbin/slurmctld
  start_daemon /run/slurmd.pid /usr/sbin/slurmd
  wait_for 60 resume_node || fail "the Slurm node did not come up within 60 s" || return 1
  echo "slurm-cluster: Slurm is up ($(sinfo --noheader --format='partition %P, %D node, %c CPUs, %T'))"
}

# The daemons this script started, last started first, by the ids in their pid files.
stop() {
  [ -f "$started" ] || {
    echo "slurm-cluster: nothing to stop"
    return 0
  }
  local pid_file pid
  for pid_file in $(tac "$started"); do
    running "$pid_file" || continue
    pid=$(cat "$pid_file")
    as_root kill "$pid"
    for _ in $(seq 100); do
      as_root kill -0 "$pid" 2> /dev/null || break
      sleep 0.2
    done
  done
  as_root rm -f "$started"
  echo "slurm-cluster: stopped"
}

case ${1:-} in
  install) install_packages ;;
  start) start ;;
  stop) stop ;;
  *)
    echo "usage: $0 install|start|stop" >&2
    exit 2
    ;;
esac
