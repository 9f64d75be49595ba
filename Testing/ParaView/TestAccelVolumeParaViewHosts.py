"""The AccelVolume plugin in ParaView's GUI and in pvbatch on two MPI ranks.

One script for two hosts (set by the test, label "paraview"):

* GUI: ``xvfb-run paraview --script=<this file> --exit``. The client's Python shell runs it
  after start-up; the plugin is loaded into the GUI's builtin session.
* MPI: ``mpirun -np 2 pvbatch <this file>``. The Wavelet is split between the two ranks (the
  ProcessIdScalars filter must see both), each rank renders its piece with our mapper and
  IceT composites them in visibility order (ParaView's volume representations ask for ordered
  compositing; ours is one of them).

In both, the "AccelVolume" representation (slice mapper and CPU ray caster, composite) is
compared with ParaView's own "Volume" representation of the same data, colour map, opacity
and camera, as TestAccelVolumeParaViewPlugin.py does, with the same bounds (mean absolute
difference per channel, 0..255) and a "not blank" check.

Arguments come from the environment (``paraview --script`` passes none): AV_PLUGIN (the
plugin .so), AV_OUTPUT (folder for the pictures), AV_HOST ("gui" or "mpi"), AV_SCRIPT_DIR (this
file's folder, for the GUI). Prints
"FAIL: ..." per failed check and "all checks passed" at the end.
"""

import os
import sys

# The GUI's script shell defines no __file__: the test passes the folder as AV_SCRIPT_DIR.
sys.path.insert(0, os.environ.get("AV_SCRIPT_DIR") or os.path.dirname(os.path.abspath(__file__)))

from paraview import simple  # noqa: E402
import TestAccelVolumeParaViewPlugin as plugin_test  # noqa: E402

MAPPERS = ("slice", "raycast")


def partitions(view):
    """How many ranks hold a piece of the Wavelet (1 in the GUI's builtin session)."""
    source = simple.Wavelet()
    source.WholeExtent = plugin_test.EXTENT
    ids = simple.ProcessIdScalars(Input=source)
    ids.UpdatePipeline()
    info = ids.PointData["ProcessId"].GetRange()
    simple.Delete(ids)
    simple.Delete(source)
    return int(info[1]) + 1


def run(view, host, output, failures):
    ranks = partitions(view)
    expected = 2 if host == "mpi" else 1
    failures.check(ranks == expected,
        "%s: the Wavelet is split over %d rank(s), %d expected" % (host, ranks, expected))
    plugin_test.set_camera(view, False)
    background = plugin_test.render_to(view, os.path.join(output, "%s_background.png" % host))
    reference = plugin_test.render_paraview_volume(
        view, "composite", False, os.path.join(output, "%s_paraview_volume.png" % host))
    rows = []
    for mapper in MAPPERS:
        label = "%s %s composite" % (host, mapper)
        picture = plugin_test.render_accelvolume(view, mapper, "composite", False,
            os.path.join(output, "%s_accelvolume_%s.png" % (host, mapper)), failures, label)[0]
        diff = plugin_test.mean_abs_diff(picture, reference)
        covered = plugin_test.covered_fraction(picture, background)
        failures.check(covered >= plugin_test.MIN_COVERED,
            "%s: blank picture (%.1f%% of pixels differ from the background)"
            % (label, 100 * covered))
        bound = plugin_test.BOUNDS[mapper]
        failures.check(max(diff) <= bound, "%s: differs from ParaView's Volume picture by %.2f "
            "(max over RGB), bound %.1f" % (label, max(diff), bound))
        rows.append((label, covered, diff))
    print("\n%-28s %8s  %s" % ("case (%d rank(s))" % ranks, "covered",
        "mean abs diff R G B vs ParaView Volume"))
    for label, covered, diff in rows:
        print("%-28s %7.1f%%  %.2f %.2f %.2f" % (label, 100 * covered, diff[0], diff[1], diff[2]))


def main():
    plugin = os.environ.get("AV_PLUGIN", "")
    output = os.environ.get("AV_OUTPUT", ".")
    host = os.environ.get("AV_HOST", "mpi")
    os.makedirs(output, exist_ok=True)
    failures = plugin_test.Failures()
    if not failures.check(os.path.isfile(plugin), "plugin %r does not exist" % plugin):
        return 1
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    if host == "gui":
        # The GUI's own view, in its layout (a view made here would have no widget to draw in).
        view = simple.GetActiveViewOrCreate("RenderView")
        view.OrientationAxesVisibility = 0
        run(view, host, output, failures)
    else:
        view = plugin_test.make_view()
        try:
            run(view, host, output, failures)
        finally:
            simple.Delete(view)  # pvbatch 5.11 crashes at exit with a live view
    if failures.messages:
        print("\n%d check(s) failed" % len(failures.messages), flush=True)
        return 1
    print("all checks passed", flush=True)
    return 0


# No sys.exit: the GUI's script shell must not be left that way (--exit closes it), and an exit
# of rank 0 before pvbatch's own end leaves rank 1 waiting for it (mpirun then kills it). The
# test reads the result from the output.
main()
