# A throwaway one-node Slurm cluster on loopback (shared/notes/slurm.md, sections 1 and 4), sourced
# by slurm_cluster_test.sh and measure_overhead.sh: cluster_start FOLDER writes the configuration
# into FOLDER/etc (state and logs beside it), exports SLURM_CONF, starts slurmctld and slurmd on
# two free ports and waits until the node is idle; cluster_stop cancels every job, waits for the
# queue to empty (a job's slurmstepd outlives slurmd) and stops both daemons by pid. Both daemons
# are children of the sourcing shell, which must call cluster_stop (e.g. from an EXIT trap).
# No munge: auth/none trusts any uid, so only on loopback and for throwaway use.

CTLD_PID= SLURMD_PID=
# Debian installs the daemons in /usr/sbin, which a user's PATH may lack.
export PATH=$PATH:/usr/sbin:/sbin

cluster_start() {
  local dir=$1 ports
  mkdir -p "$dir"/{etc,state/ctld,state/d,log,run}
  # Two free loopback ports: bound to port 0 and released (another program could take one in the
  # moment between; slurmctld then fails to start and cluster_start says so).
  ports=$(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
  read -r CTLD_PORT SLURMD_PORT <<<"$ports"
  export SLURM_CONF=$dir/etc/slurm.conf
  cat >"$SLURM_CONF" <<CONF
# One-node cluster on loopback for filmback's tests (shared/notes/slurm.md); no accounting.
# Requeued jobs may start again after cred_expire s (default 120); the scheduler passes every 1-5 s.
ClusterName=filmback-test
SlurmctldHost=localhost
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/none
CredType=cred/none
AuthInfo=cred_expire=10
StateSaveLocation=$dir/state/ctld
SlurmdSpoolDir=$dir/state/d
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.txt
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,bf_interval=5,sched_interval=5
MailProg=/bin/true
MinJobAge=3600
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=1000 State=UNKNOWN
PartitionName=filmback Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  slurmctld -D -i -f "$SLURM_CONF" >"$dir/log/slurmctld.stdout" 2>&1 &
  CTLD_PID=$!
  slurmd -D -N localhost -f "$SLURM_CONF" >"$dir/log/slurmd.stdout" 2>&1 &
  SLURMD_PID=$!
  for _ in $(seq 120); do
    [ "$(sinfo -h -n localhost -o %T 2>/dev/null)" = idle ] && return 0
    if ! kill -0 "$CTLD_PID" 2>/dev/null || ! kill -0 "$SLURMD_PID" 2>/dev/null; then
      echo "a Slurm daemon exited (logs in $dir/log)" >&2
      return 1
    fi
    sleep 0.25
  done
  echo "the node is not idle after 30 s (logs in $dir/log)" >&2
  return 1
}

stop_pid() {  # TERM, up to 10 s, then KILL: only a pid this shell started, then reaped
  local pid=$1
  [ -n "$pid" ] || return 0
  kill -TERM "$pid" 2>/dev/null || return 0
  for _ in $(seq 100); do
    kill -0 "$pid" 2>/dev/null || { wait "$pid" 2>/dev/null || true; return 0; }
    sleep 0.1
  done
  echo "pid $pid ignored SIGTERM: SIGKILL" >&2
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}

cluster_stop() {
  if [ -n "$CTLD_PID" ] && kill -0 "$CTLD_PID" 2>/dev/null; then
    scancel --quiet --partition=filmback 2>/dev/null || true
    for _ in $(seq 50); do
      [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  stop_pid "$SLURMD_PID"
  stop_pid "$CTLD_PID"
  CTLD_PID= SLURMD_PID=
}

# The final state of job JOB_ID (all its elements: "COMPLETED", or e.g. "CANCELLED,COMPLETED"),
# polled every 0.5 s until DEADLINE (seconds since the epoch): "timeout:STATE" then.
job_final_state() {
  local state
  while :; do
    state=$(squeue -h -t all -j "$1" -o %T 2>/dev/null | sort -u | paste -sd, -)
    case $state in
      COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) echo "$state"; return ;;
    esac
    [ "$(date +%s)" -lt "$2" ] || { echo "timeout:$state"; return; }
    sleep 0.5
  done
}
