#!/usr/bin/env bash
# Stops the cluster that slurm-up.sh DIR started and removes DIR. Safe to
# run twice, or after a start that failed half way: it signals only the
# processes named in DIR's pid files, waits up to 10 s, then kills.
set -uo pipefail
dir=${1:?usage: slurm-down.sh DIR}
[ -d "$dir" ] || exit 0
pids=()
for f in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -s "$f" ] && pid=$(cat "$f") && kill "$pid" 2>/dev/null && pids+=("$pid")
done
for _ in $(seq 100); do
    alive=()
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive+=("$pid"); done
    [ ${#alive[@]} -eq 0 ] && break
    sleep 0.1
done
for pid in "${alive[@]}"; do
    echo "slurm-down: process $pid did not stop in 10 s; killing it" >&2
    kill -9 "$pid" 2>/dev/null
done
rm -rf "$dir"
