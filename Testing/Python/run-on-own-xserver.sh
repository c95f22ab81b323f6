#!/bin/sh
# Runs a command on an X server of its own (Xvfb on a free display, as the shared test server):
# for the GUI tests that drive the real pointer and keyboard (xinput.py), whose events would land
# in another test's window on the shared server. The server stops with the command.
dir=$(mktemp -d)
Xvfb -displayfd 3 -screen 0 1600x1200x24 -nolisten tcp -noreset 3>"$dir/display" >"$dir/log" 2>&1 &
server=$!
for i in $(seq 300); do
  [ -s "$dir/display" ] && xdpyinfo -display ":$(cat "$dir/display")" >/dev/null 2>&1 && break
  sleep 0.1
done
[ -s "$dir/display" ] || { cat "$dir/log"; kill $server; rm -rf "$dir"; exit 1; }
DISPLAY=":$(cat "$dir/display")" "$@"
status=$?
kill $server
wait $server 2>/dev/null
rm -rf "$dir"
exit $status
