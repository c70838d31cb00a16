#!/usr/bin/env bash
# A throw-away single-node Slurm cluster (munged, slurmctld, slurmd) whose every file is under
# one directory: sourced by slurm_cluster_test.sh, usable by hand for measurements:
#   source tests/cluster/slurm_lib.sh; cluster_start /tmp/c; ...; cluster_stop
# Needs root (Slurm runs jobs as their submitter, munged drops to user munge). Debian 12:
# apt-get install slurmctld slurmd slurm-client munge (22.05). Nothing is written to
# /etc/slurm, /run/munge, /var/spool/slurm* or /var/log: every path is set below.

cluster_pids=()

cluster_log() { echo "cluster: $*" >&2; }

# cluster_install: installs the Debian packages if a daemon is missing; returns 77 (ctest SKIP)
# when they are missing and this is not root.
cluster_install() {
  local need=0 tool
  for tool in munged mungekey slurmctld slurmd sbatch sinfo scontrol; do
    command -v "$tool" >/dev/null 2>&1 || PATH="$PATH:/usr/sbin" command -v "$tool" \
      >/dev/null 2>&1 || need=1
  done
  [ "$need" -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    cluster_log "SKIP: slurmctld/slurmd/slurm-client/munge are not installed and this is not root"
    return 77
  fi
  cluster_log "installing slurmctld slurmd slurm-client munge (apt-get)"
  local pkgs=(slurmctld slurmd slurm-client munge)
  # A fresh machine may have no package lists yet: update once and retry.
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${pkgs[@]}" \
    >/dev/null 2>&1 || {
    apt-get update >/dev/null 2>&1
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${pkgs[@]}" \
      >/dev/null
  } || {
    cluster_log "apt-get install ${pkgs[*]} failed"
    return 1
  }
}

# cluster_start DIR: writes DIR/slurm.conf and a munge key, starts the three daemons in the
# foreground (their pids are remembered for cluster_stop), exports SLURM_CONF and waits until
# the node is idle (60 s at most, then prints the daemons' logs and returns 1).
cluster_start() {
  local dir="$1" host cpus mem line pid
  export PATH="$PATH:/usr/sbin"
  host="$(hostname -s)"
  mkdir -p "$dir"/{state,spool,munge,log}
  # munged runs as user munge: the directories above its socket must let it through.
  chmod 755 "$dir"
  if ! setpriv --reuid=munge --regid=munge --clear-groups test -x "$dir"; then
    cluster_log "munged (user munge) cannot reach $dir: a directory above it is closed"
    return 1
  fi
  line="$(slurmd -C | head -n 1)"
  cpus="$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$line")"
  mem="$(sed -n 's/.* RealMemory=\([0-9]*\).*/\1/p' <<<"$line")"
  # Sockets, cores and threads as slurmd sees them, so slurmd registers without a mismatch.
  local topo
  topo="$(grep -oE '(Boards|SocketsPerBoard|CoresPerSocket|ThreadsPerCore)=[0-9]+' <<<"$line" |
    tr '\n' ' ')"

  # munged wants its socket directory traversable by all (clients connect as any user).
  chown munge:munge "$dir/munge"
  chmod 755 "$dir/munge"
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chown munge:munge "$dir/munge/munge.key"
  chmod 400 "$dir/munge/munge.key"

  cat >"$dir/slurm.conf" <<CONF
# Written by tests/cluster/slurm_lib.sh: one node, everything under $dir.
ClusterName=kasumi-test
# Addresses given, so no name lookup of the host is needed.
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=${CLUSTER_PORT:-16817}
SlurmdPort=$(( ${CLUSTER_PORT:-16817} + 1 ))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
# A requeued job waits cred_expire + 1 s before it may start again (default 120 s).
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=5
CredType=cred/munge
MpiDefault=none
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
SchedulerType=sched/backfill
# Start the next array task as soon as one ends (the test runs hundreds of one-second tasks).
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0,default_queue_depth=200
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# Finished jobs stay visible to scontrol for 10 minutes (there is no accounting database).
MinJobAge=600
KillWait=10
# Smaller than the default 1001, so the test sees submit_sequence.sh refuse a too-large array.
MaxArraySize=100
MessageTimeout=20
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus $topo RealMemory=$mem State=UNKNOWN
# Up to 4 jobs a core: the test's tasks are short and mostly wait on Slurm, not on the CPU.
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=FORCE:4
CONF
  export SLURM_CONF="$dir/slurm.conf"
  cluster_dir="$dir"

  setpriv --reuid=munge --regid=munge --clear-groups munged --foreground \
    --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" 2>>"$dir/log/munged.err" &
  cluster_pids+=($!)
  local i
  for i in $(seq 1 50); do
    [ -S "$dir/munge/munge.socket" ] && break
    sleep 0.1
  done
  if ! [ -S "$dir/munge/munge.socket" ]; then
    cluster_log "munged did not start: $(tail -n 3 "$dir/log/munged.err")"
    return 1
  fi
  # Foreground (-D) so $! is the daemon; they log to the files named in slurm.conf.
  slurmctld -D -f "$dir/slurm.conf" >/dev/null 2>>"$dir/log/slurmctld.err" &
  cluster_pids+=($!)
  slurmd -D -f "$dir/slurm.conf" >/dev/null 2>>"$dir/log/slurmd.err" &
  cluster_pids+=($!)

  local start=$SECONDS
  while [ $((SECONDS - start)) -lt 60 ]; do
    for pid in "${cluster_pids[@]}"; do
      kill -0 "$pid" 2>/dev/null && continue
      cluster_log "a daemon (pid $pid) exited while starting"
      cluster_logs
      return 1
    done
    if [ "$(sinfo -h -n "$host" -o %t 2>/dev/null)" = "idle" ]; then
      cluster_log "node $host idle after $((SECONDS - start)) s ($cpus CPUs, $mem MB)"
      return 0
    fi
    sleep 0.5
  done
  cluster_log "node $host not idle after 60 s: $(sinfo 2>&1)"
  cluster_logs
  return 1
}

# cluster_logs: prints the tail of every daemon log.
cluster_logs() {
  local f
  for f in "$cluster_dir"/log/* "$cluster_dir"/munge/munged.log; do
    [ -f "$f" ] || continue
    echo "----- $f" >&2
    tail -n 20 "$f" >&2
  done
}

# cluster_stop: cancels the cluster's jobs, then stops the daemons cluster_start started (by
# pid: TERM, then KILL after 10 s), then any job step process of this cluster left behind.
cluster_stop() {
  local pid i left
  [ "${#cluster_pids[@]}" -eq 0 ] && return 0
  left="$(squeue -h -o %i 2>/dev/null)"
  if [ -n "$left" ]; then
    # shellcheck disable=SC2086
    scancel $left 2>/dev/null
    for _ in $(seq 1 40); do
      [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.5
    done
  fi
  # Reverse order: slurmd, slurmctld, then munged (they authenticate through it while stopping).
  for ((i = ${#cluster_pids[@]} - 1; i >= 0; i--)); do
    pid="${cluster_pids[$i]}"
    kill -TERM "$pid" 2>/dev/null || continue
    for _ in $(seq 1 100); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -0 "$pid" 2>/dev/null && kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
  done
  cluster_pids=()
  # slurmstepd of this cluster (it holds files under $cluster_dir open) outliving slurmd.
  local fd
  for pid in $(pgrep -x slurmstepd 2>/dev/null); do
    for fd in /proc/"$pid"/fd/*; do
      if [[ "$(readlink "$fd" 2>/dev/null)" == "$cluster_dir"/* ]]; then
        kill -KILL "$pid" 2>/dev/null || true
        break
      fi
    done
  done
}
