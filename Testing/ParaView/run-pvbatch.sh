#!/bin/sh
# Runs a pvbatch script under a private X server: the ctest of the ParaView plugin.
#   run-pvbatch.sh <paraview-python root> <pvbatch> <xvfb-run> <script> [script arguments...]
# <paraview-python root> is Debian's python3-paraview unpacked with dpkg -x (scripts/setup.sh):
# pvbatch imports ParaView's Python package from <root>/usr/lib/python3/dist-packages.
# Exits 125 (ctest: skipped) with the reason when something it needs is missing. Debian's
# pvbatch aborts without an X display, hence xvfb-run; concurrent xvfb-run calls can race for
# a display number ("bad X server connection", "Xvfb failed to start"), so such a start is
# retried. A run without a result after 60 s is killed and tried again, up to three runs, saying
# so (a run takes 5-15 s). pvbatch 5.11's two MPI ranks deadlock now and then (about 1 run in 6
# here, alone or beside other tests): rank 0 renders and IceT creates its communicator
# (MPI_Comm_dup) while rank 1 still waits in the RMI loop's broadcast (MPI_Barrier); their
# stacks, printed on the kill, show it. Not our code; a hang used to cost CI 120 s.
set -u
root=$1 pvbatch=$2 xvfb_run=$3
shift 3

skip() {
  echo "SKIPPED: $*"
  exit 125
}
python_dir="$root/usr/lib/python3/dist-packages"
[ -f "$python_dir/paraview/simple.py" ] ||
  skip "ParaView's Python package is not in $python_dir: run scripts/setup.sh as root (it" \
    "unpacks python3-paraview there) or configure with -DACCELVOLUME_PARAVIEW_PYTHON_ROOT=<dir>"
[ -x "$pvbatch" ] || skip "pvbatch not found ($pvbatch): install Debian's paraview package"
[ -x "$xvfb_run" ] || skip "xvfb-run not found ($xvfb_run): install xvfb and xauth"

log=$(mktemp)
trap 'rm -f "$log"' EXIT
attempt=1
while :; do
  # A display number of our own (from the process id) makes collisions unlikely to begin with;
  # a retry takes another one (a cold CI run once failed all three tries on display :350).
  PYTHONPATH="$python_dir${PYTHONPATH:+:$PYTHONPATH}" \
    timeout -k 5 60 "$xvfb_run" -a -n $((100 + ($$ + 277 * attempt) % 800)) -s "-screen 0 1024x768x24" \
    "$pvbatch" "$@" >"$log" 2>&1
  status=$?
  cat "$log"
  if [ "$status" -eq 124 ] && [ "$attempt" -lt 3 ]; then
    echo "run-pvbatch.sh: no result after 60 s (hung); trying again"
    attempt=$((attempt + 1))
    continue
  fi
  if [ "$status" -ne 0 ] && [ "$attempt" -lt 3 ] &&
    grep -q -e "bad X server connection" -e "Xvfb failed to start" "$log"; then
    echo "run-pvbatch.sh: the X server could not be reached; trying again on another display"
    attempt=$((attempt + 1))
    sleep 5
    continue
  fi
  exit "$status"
done
