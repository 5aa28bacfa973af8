#!/usr/bin/env bash
# Starts a one-node Slurm cluster on loopback for the scheduler tests:
# munged, slurmctld and slurmd (2 CPUs), every file under one folder.
#
#   eval "$(.ci/slurm-up.sh DIR)"   # exports SLURM_CONF; DIR empty or absent
#   .ci/slurm-down.sh DIR           # stops the daemons, removes DIR
#
# Needs root and Debian's slurm-wlm and munge. No cgroups: processes are
# tracked by /proc (proctrack/linuxproc) and tasks are not bound (task/none),
# so it also runs inside a container. Fails within 60 s if the node does not
# come up, after printing the daemons' logs; the caller's down script cleans.
set -euo pipefail
dir=${1:?usage: slurm-up.sh DIR}
mkdir -p "$dir"/{state,spool,munge}
dir=$(cd "$dir" && pwd)
chmod 755 "$dir/munge"
logs() {
    tail -n 30 "$dir"/slurmctld.log "$dir"/slurmd.log "$dir"/munge/munged.log >&2 2>/dev/null || true
}
trap 'echo "slurm-up: a daemon did not start" >&2; logs' ERR

# munged with its own key and socket, so a system munged is left alone.
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$dir/munge/munge.key"
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" >&2

# Ports chosen from the folder's inode so two clusters on one machine differ.
base=$(( 20000 + $(stat -c %i "$dir") % 20000 ))
cpus=2
cat > "$dir/slurm.conf" <<CONF
ClusterName=ronray
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$base
SlurmdPort=$((base + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
SchedulerParameters=sched_min_interval=100000,batch_sched_delay=0
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=4
NodeName=ronray-node NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1024 State=UNKNOWN
PartitionName=ci Nodes=ronray-node Default=YES MaxTime=30 State=UP
CONF
export SLURM_CONF=$dir/slurm.conf

slurmctld -f "$SLURM_CONF" >&2
slurmd -f "$SLURM_CONF" -N ronray-node >&2

# Up when the node is idle; 60 s at most.
for _ in $(seq 120); do
    if state=$(timeout 5 sinfo -h -N -o %t 2>/dev/null) && [ "$state" = idle ]; then
        echo "export SLURM_CONF=$SLURM_CONF"
        exit 0
    fi
    sleep 0.5
done
trap - ERR
echo "slurm-up: the node did not become idle in 60 s (state: ${state:-no answer})" >&2
logs
exit 1
