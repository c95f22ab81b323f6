#!/bin/bash
# Runs a client command against a pvserver on RANKS MPI ranks at PORT, started here and stopped
# after the client: run-with-pvserver.sh RANKS PORT MPIEXEC-COMMAND PVSERVER CLIENT-COMMAND...
set -u
ranks=$1 port=$2 mpiexec=$3 pvserver=$4
shift 4
log=$(mktemp)
$mpiexec -n "$ranks" "$pvserver" --server-port="$port" --timeout=5 >"$log" 2>&1 &
server=$!
for _ in $(seq 100); do
  grep -q "Accepting connection" "$log" && break
  sleep 0.2
done
"$@"
status=$?
wait $server || { echo "pvserver failed:"; cat "$log"; status=1; }
rm -f "$log"
exit $status
