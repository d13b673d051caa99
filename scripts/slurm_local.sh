#!/usr/bin/env bash
# slurm_local.sh - a one-node Slurm cluster on this machine, everything under DIR: its
# own munge key and socket, slurm.conf, state, spool, pid and log files. For trying
# `study submit --slurm` without a cluster, and for tests/integration/study_slurm.sh.
#
#   scripts/slurm_local.sh start DIR   # prints: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm_local.sh stop DIR    # cancels its jobs, stops its daemons by their pids
#
# Needs root (slurmd runs jobs as their users) and the Debian packages slurmctld,
# slurmd, slurm-client and munge (make deps). No systemd, no cgroups, no accounting:
# ProctrackType=proctrack/linuxproc, TaskPlugin=task/none. The node is `localhost`
# with 2 CPUs (SLURM_LOCAL_CPUS); the ports are free ones picked at start. Nothing
# outside DIR is touched, so several such clusters can run side by side.
set -u
usage() { echo "usage: $0 start|stop DIR" >&2; exit 1; }
[ $# -eq 2 ] || usage
cmd=$1
mkdir -p "$2" 2>/dev/null
DIR=$(cd "$2" 2>/dev/null && pwd) || { echo "slurm_local: $2: no such directory" >&2; exit 1; }
CONF="$DIR/slurm.conf"
export SLURM_CONF="$CONF"

# the pid in FILE, when that process is alive
alive() { local p; p=$(cat "$1" 2>/dev/null) && [ -n "$p" ] && kill -0 "$p" 2>/dev/null && echo "$p"; }

# stop the daemon whose pid is in FILE: SIGTERM, then SIGKILL after 10 s
stop_pid() {
	local p i
	p=$(alive "$1") || return 0
	kill "$p" 2>/dev/null
	for i in $(seq 100); do kill -0 "$p" 2>/dev/null || return 0; sleep 0.1; done
	kill -9 "$p" 2>/dev/null
}

# (Debian's python3, whose standard library is enough: the first python3 on PATH may be a
# pyenv shim that costs most of a second a call)
free_port() {
	/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])' 2>/dev/null ||
		echo $((20000 + RANDOM % 20000))
}

start() {
	local m
	for m in munged slurmctld slurmd sinfo; do
		command -v "$m" >/dev/null || [ -x "/usr/sbin/$m" ] ||
			{ echo "slurm_local: $m is not installed (make deps: munge, slurmctld, slurmd, slurm-client)" >&2; exit 3; }
	done
	[ "$(id -u)" -eq 0 ] || { echo "slurm_local: needs root (slurmd runs the jobs as their users)" >&2; exit 3; }
	if alive "$DIR/slurmctld.pid" >/dev/null; then
		echo "slurm_local: a cluster is already running in $DIR" >&2
		exit 1
	fi
	PATH="$PATH:/usr/sbin"
	mkdir -p "$DIR/state" "$DIR/spool" && chmod 700 "$DIR" || exit 2

	# munge: a key of our own, its own socket (AuthInfo below points Slurm at it)
	if [ ! -s "$DIR/munge.key" ]; then
		(umask 077 && dd if=/dev/urandom of="$DIR/munge.key" bs=1024 count=1 status=none) || exit 2
	fi
	chmod 400 "$DIR/munge.key"
	# --force: munged refuses a socket directory it does not own as its system dir
	munged --force --socket="$DIR/munge.sock" --key-file="$DIR/munge.key" --pid-file="$DIR/munged.pid" \
		--log-file="$DIR/munged.log" --seed-file="$DIR/munged.seed" 2>>"$DIR/munged.log" ||
		{ echo "slurm_local: munged did not start: $(tail -n 3 "$DIR/munged.log")" >&2; exit 2; }

	local cpus=${SLURM_LOCAL_CPUS:-2}
	cat >"$CONF" <<EOF
# a one-node cluster made by scripts/slurm_local.sh; everything lives in $DIR
ClusterName=shakebox
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge.sock
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
PlugStackConfig=$DIR/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# a cancelled job's processes get SIGTERM, then SIGKILL this many seconds later
KillWait=30
MinJobAge=600
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
	: >"$DIR/plugstack.conf"
	# -i: ignore (there is none) saved state
	slurmctld -f "$CONF" -i 2>>"$DIR/slurmctld.log" ||
		{ echo "slurm_local: slurmctld did not start: $(tail -n 5 "$DIR/slurmctld.log")" >&2; stop; exit 2; }
	slurmd -f "$CONF" -N localhost 2>>"$DIR/slurmd.log" ||
		{ echo "slurm_local: slurmd did not start: $(tail -n 5 "$DIR/slurmd.log")" >&2; stop; exit 2; }
	local i st=""
	for i in $(seq 300); do
		st=$(sinfo --noheader --format=%T 2>/dev/null)
		case "$st" in idle*|mixed*|allocated*) break ;; esac
		sleep 0.1
	done
	case "$st" in
	idle*|mixed*|allocated*) ;;
	*)
		echo "slurm_local: the node did not come up (state '$st'); slurmctld.log and slurmd.log in $DIR say:" >&2
		tail -n 5 "$DIR/slurmctld.log" "$DIR/slurmd.log" >&2
		stop
		exit 2
		;;
	esac
	echo "export SLURM_CONF=$CONF"
}

stop() {
	# this cluster's jobs first (SLURM_CONF points at it), so that no slurmstepd outlives
	# the daemons; then the daemons, by their pids
	if alive "$DIR/slurmctld.pid" >/dev/null; then
		scancel --full --quiet --user="$(id -un)" 2>/dev/null
		local i
		for i in $(seq 100); do
			[ -z "$(squeue --noheader --format=%i 2>/dev/null)" ] && break
			sleep 0.1
		done
	fi
	stop_pid "$DIR/slurmd.pid"
	stop_pid "$DIR/slurmctld.pid"
	stop_pid "$DIR/munged.pid"
	return 0
}

case "$cmd" in
start) start ;;
stop) stop ;;
*) usage ;;
esac
