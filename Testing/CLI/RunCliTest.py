#!/usr/bin/env python3
"""One driver for the accelvolume CLI tests (Testing/CLI/CMakeLists.txt registers them).

    RunCliTest.py KEY=VALUE ...

Runs EXE with ARGS (words separated by '|', @WORK@ replaced by the work folder) and checks the
exit code, the error line, stdout / stderr, the PNG and the --stats JSON. Keys:
  EXE, ARGS, WORK          the program, its arguments, a fresh work folder
  EXPECT                   expected exit code (default 0); non-zero: exactly one line
                           'accelvolume: error: ...' on stderr, matching ERROR_REGEX if given
  MAKE_RAW                 writes WORK/<name> (10 bytes) first
  MAKE_TF                  writes WORK/tf.json first: good, malformed, nocolor, unsorted, nonnumeric
  PNG, STATS               files under WORK that must be a PNG / a --stats JSON object
  STDOUT_REGEX, STDOUT_LINES, STDERR_REGEX (else stderr must be empty), ALLOW_TBB_WARNING=ON
  EXTRA_RUN_1..4           further runs (arguments as ARGS) that must exit 0 with no stderr
  IDENTICAL                files under WORK, separated by ',', that must be byte-identical
  LAUNCHER                 words ('|') that run the first command (mpiexec); its dashed banners
                           on stderr are ignored
  PTY, PTY_REGEX, PTY_NOT_REGEX   run the first command under `script` (a pseudo-terminal)
  MAPPER BLEND WIDTH INPUT TF SHADE CROP THREADS PARALLEL   expected --stats values
  RAYCAST / SHEARWARP / SLICE / SMART = OBJECT or NULL, with RAYCAST_POSITIVE, RAYCAST_ZERO,
  LEAP, CELL_LEAP, SHEARWARP_POSITIVE, SHEARWARP_EXPECT (key=value,...), SHEARWARP_SAME_AS,
  SMART_MODE                 the mappers' --stats objects
  MODE=octree, BUILDER     `accelvolume octree` with that builder and its --stats keys
Values are compared as CMake's string(JSON) gave them (true/false as ON/OFF), so the test
definitions read as before.
"""

import json
import os
import re
import shutil
import subprocess
import sys

TIMEOUT = 240

TF_FILES = {
    "good": """{
  "name": "test ramp",
  "scalarOpacity": [[0, 0], [0.2, 0], [1.0, 0.6]],
  "color": [[0, 0.1, 0.1, 0.3], [0.5, 0.2, 0.8, 0.4], [1.0, 1, 1, 0.9]],
  "gradientOpacity": [[0, 0.2], [2.5e-1, 1]],
  "shade": true,
  "ambient": 0.3, "diffuse": 0.6, "specular": 0.2, "specularPower": 20
}
""",
    "malformed": '{"scalarOpacity": [[0, 0], [1, 1]], "color": [[0, 0, 0, 0] [1, 1, 1, 1]]}',
    "nocolor": '{"scalarOpacity": [[0, 0], [1, 1]]}',
    "unsorted": '{"scalarOpacity": [[0, 0], [1, 1], [0.5, 0.5]], "color": [[0, 0, 0, 0]]}',
    "nonnumeric": '{"scalarOpacity": [[0, "zero"]], "color": [[0, 0, 0, 0]]}',
}

STATS_KEYS = ("mapper blend width height frames first_frame_ms gl_renderer gl_backend dims type "
              "spacing input sample_distance slices boundary_rerender tf shade gradient_opacity "
              "lighting crop camera threads image_sample_distance raycast shearwarp slice "
              "smart").split()


class Failure(Exception):
    pass


class Run:
    """One command's outcome; `describe` goes into every failure message."""

    def __init__(self, command, code, out, err):
        self.command, self.code, self.out, self.err = command, code, out, err

    def describe(self):
        return "command: %s\nexit: %s\nstdout:\n%s\nstderr:\n%s" % (
            " ".join(self.command), self.code, self.out, self.err)


def run(command, **kwargs):
    try:
        done = subprocess.run(command, capture_output=True, timeout=TIMEOUT, **kwargs)
    except subprocess.TimeoutExpired as expired:
        return Run(command, "timeout", (expired.stdout or b"").decode(errors="replace"),
                   (expired.stderr or b"").decode(errors="replace"))
    return Run(command, str(done.returncode), done.stdout.decode(errors="replace"),
               done.stderr.decode(errors="replace"))


def words(value, work):
    return [w for w in value.replace("@WORK@", work).split("|")] if value else []


def cmake_text(value):
    """A JSON value as CMake's string(JSON ... GET) prints it."""
    if value is True:
        return "ON"
    if value is False:
        return "OFF"
    if value is None:
        return ""
    if isinstance(value, (dict, list)):
        return json.dumps(value)
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return repr(value)  # CMake prints 1.0 as 1.0 too
    return str(value)


def cmake_type(value):
    return {dict: "OBJECT", list: "ARRAY", str: "STRING", bool: "BOOLEAN",
            type(None): "NULL"}.get(type(value), "NUMBER")


def number(value):
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) \
        else float("nan")


def strip_banners(text):
    """mpiexec's own notes (a rank exited non-zero, ...) come between lines of dashes."""
    kept, inside = [], False
    for line in text.split("\n"):
        if re.fullmatch(r"-----+", line):
            inside = not inside
        elif not inside and line:
            kept.append(line + "\n")
    return "".join(kept)


class Checker:
    def __init__(self, options):
        self.o = options
        self.work = options["WORK"]
        self.first = None

    def fail(self, message, current=None):
        raise Failure(message + "\n" + (current or self.first).describe())

    def check_stderr(self, current):
        text = current.err
        if self.o.get("ALLOW_TBB_WARNING"):
            text = re.sub(r"TBB Warning: The number of workers is currently limited[^\n]*\n\n?",
                          "", text)
        if text:
            self.fail("expected no stderr output (VTK messages must not reach the terminal)",
                      current)

    def section(self, stats, name, keys, counters, positive):
        part = stats.get(name)
        for key in keys + counters:
            if not isinstance(part, dict) or key not in part:
                self.fail("--stats lacks %s.%s\n%s" % (name, key, json.dumps(stats)))
        for key in counters:
            value = part[key]
            if isinstance(value, bool) or not isinstance(value, int) or value < 0:
                self.fail("--stats %s.%s is '%s', expected an integer >= 0" % (name, key, value))
        for key in [k for k in positive.split(",") if k]:
            if not number(part.get(key)) > 0:
                self.fail("--stats %s.%s is '%s', expected > 0" % (name, key, part.get(key)))

    def expect_values(self, stats, pairs, where=""):
        for key, wanted in pairs:
            value = cmake_text(stats.get(key))
            if value != wanted:
                self.fail("--stats %s%s is '%s', expected '%s'" % (where, key, value, wanted))

    def read_stats(self, name):
        try:
            with open(os.path.join(self.work, name)) as stream:
                stats = json.load(stream)
        except (OSError, ValueError) as error:
            self.fail("--stats is not a JSON object: %s" % error)
        if not isinstance(stats, dict):
            self.fail("--stats is not a JSON object")
        return stats

    def check_stats(self):
        o = self.o
        stats = self.read_stats(o["STATS"])
        for key in STATS_KEYS:
            if key not in stats:
                self.fail("--stats lacks '%s'" % key)
        for key in ("median", "min", "max", "mean"):
            if not number(stats["ms_per_frame"].get(key)) > 0:
                self.fail("--stats ms_per_frame.%s missing or not positive" % key)
        if not number(stats.get("mapper_render_ms")) > 0:
            self.fail("--stats mapper_render_ms missing or not positive")
        for name in ("SLICE", "SMART", "SHEARWARP", "RAYCAST"):
            if name in o and cmake_type(stats.get(name.lower())) != o[name]:
                self.fail("--stats %s is %s, expected %s" % (
                    name.lower(), cmake_type(stats.get(name.lower())), o[name]))
        if o.get("SLICE") == "OBJECT":
            self.section(stats, "slice", ["render_ms"],
                         ["slices", "proxy_polygons", "boundary_faces", "termination_passes"],
                         "slices,render_ms")
        if o.get("SMART") == "OBJECT":
            self.section(stats, "smart", ["mode", "reason", "render_ms"], [], "render_ms")
            if o.get("SMART_MODE"):
                self.expect_values(stats["smart"], [("mode", o["SMART_MODE"])], "smart.")
        for key in ("azimuth", "elevation", "roll", "zoom", "parallel"):
            if key not in stats["camera"]:
                self.fail("--stats lacks camera.%s" % key)
        if not isinstance(stats["dims"], list) or len(stats["dims"]) != 3:
            self.fail("--stats dims is not a 3-array")
        self.expect_values(stats, [(k.lower(), o[k]) for k in
                                   ("MAPPER", "BLEND", "WIDTH", "INPUT", "TF", "SHADE")
                                   if o.get(k)])
        if "CROP" in o and cmake_type(stats["crop"]) != o["CROP"]:
            self.fail("--stats crop is %s, expected %s" % (cmake_type(stats["crop"]), o["CROP"]))
        if "THREADS" in o:
            self.expect_values(stats, [("threads", o["THREADS"])])
        if "PARALLEL" in o:
            self.expect_values(stats["camera"], [("parallel", o["PARALLEL"])], "camera.")
        if o.get("SHEARWARP") == "OBJECT":
            self.check_shearwarp(stats)
        if o.get("RAYCAST") == "OBJECT":
            self.check_raycast(stats)

    def check_shearwarp(self, stats):
        o = self.o
        self.section(stats, "shearwarp",
                     "rle ert balance shading render_ms encode_ms first_encode_ms table_ms "
                     "composite_ms gather_ms warp_ms imbalance band_ms principal_axis".split(),
                     "voxels samples skipped_pixels stored_voxels encoded_bytes bands ranks "
                     "threads".split(), o.get("SHEARWARP_POSITIVE", ""))
        part = stats["shearwarp"]
        if not part["bands"] > 0 or len(part["band_ms"]) != part["bands"]:
            self.fail("--stats shearwarp has %s bands and %d band_ms values" % (
                part["bands"], len(part["band_ms"])))
        if part["principal_axis"] not in ("x", "y", "z"):
            self.fail("--stats shearwarp.principal_axis is '%s', expected x, y or z"
                      % part["principal_axis"])
        if o.get("SHEARWARP_SAME_AS"):
            other = self.read_stats(o["SHEARWARP_SAME_AS"]).get("shearwarp") or {}
            for key in ("samples", "skipped_pixels"):
                if part[key] != other.get(key):
                    self.fail("--stats shearwarp.%s is '%s', %s has '%s'" % (
                        key, part[key], o["SHEARWARP_SAME_AS"], other.get(key)))
        pairs = [p.split("=", 1) for p in o.get("SHEARWARP_EXPECT", "").split(",") if p]
        self.expect_values(part, pairs, "shearwarp.")

    def check_raycast(self, stats):
        o = self.o
        # rays are always positive: a raycast render that casts none drew nothing.
        self.section(stats, "raycast",
                     "leap cell_leap threads octree_leaf_size image_sample_distance cast_ms "
                     "prepare_ms".split(),
                     "rays samples leaped_octree leaped_distance_map leaped_cell_table "
                     "transparent_cell_samples terminated_rays octree_leaps distance_map_leaps "
                     "culled_pixels packet_rays acceleration_bytes".split(),
                     "rays," + o.get("RAYCAST_POSITIVE", ""))
        part = stats["raycast"]
        for key in [k for k in o.get("RAYCAST_ZERO", "").split(",") if k]:
            if part[key] != 0:
                self.fail("--stats raycast.%s is '%s', expected 0" % (key, part[key]))
        self.expect_values(part, [(k.lower(), o[k]) for k in ("LEAP", "CELL_LEAP", "THREADS")
                                  if o.get(k)], "raycast.")

    def first_run(self):
        o = self.o
        exe, arguments = o["EXE"], words(o.get("ARGS", ""), self.work)
        if o.get("PTY"):
            line = " ".join("'" + a.replace("'", "'\\''") + "'" for a in [exe] + arguments)
            current = run([o["PTY"], "-qec", line, "/dev/null"])
            current.pty, current.out = current.out, ""
            return current
        launcher = words(o.get("LAUNCHER", ""), self.work)
        current = run(launcher + [exe] + arguments)
        if launcher:
            current.err = strip_banners(current.err)
        return current

    def run_render(self):
        o = self.o
        self.first = current = self.first_run()
        expect = o.get("EXPECT", "0")
        if current.code != expect:
            self.fail("expected exit code %s" % expect)
        if expect != "0":
            if not re.fullmatch(r"accelvolume: error: [^\n]+\n", current.err):
                self.fail("expected exactly one line 'accelvolume: error: ...' on stderr")
            if o.get("ERROR_REGEX") and not re.search(o["ERROR_REGEX"], current.err):
                self.fail("the error line does not match '%s'" % o["ERROR_REGEX"])
            print("got: " + current.err, end="")
            return
        if o.get("STDERR_REGEX"):
            if not re.search(o["STDERR_REGEX"], current.err):
                self.fail("stderr does not match '%s'" % o["STDERR_REGEX"])
        else:
            self.check_stderr(current)
        if o.get("PTY"):
            if o.get("PTY_REGEX") and not re.search(o["PTY_REGEX"], current.pty):
                self.fail("the terminal output does not match '%s':\n%s" % (
                    o["PTY_REGEX"], current.pty))
            if o.get("PTY_NOT_REGEX") and re.search(o["PTY_NOT_REGEX"], current.pty):
                self.fail("the terminal output matches '%s'" % o["PTY_NOT_REGEX"])
        for index in range(1, 5):
            if "EXTRA_RUN_%d" % index in o:
                extra = run([o["EXE"]] + words(o["EXTRA_RUN_%d" % index], self.work))
                if extra.code != "0":
                    self.fail("extra run %d: expected exit code 0" % index, extra)
                self.check_stderr(extra)
        self.check_outputs(current)

    def check_outputs(self, current):
        o = self.o
        if o.get("IDENTICAL"):
            names = o["IDENTICAL"].split(",")
            paths = [os.path.join(self.work, n) for n in names]
            contents = []
            for name, path in zip(names, paths):
                try:
                    with open(path, "rb") as stream:
                        contents.append(stream.read())
                except OSError:
                    self.fail("%s is missing; %s must be byte-identical" % (name, o["IDENTICAL"]))
            for name, content in zip(names, contents):
                if content != contents[0]:
                    self.fail("%s differs from %s; they must be byte-identical" % (name, names[0]))
        if o.get("STDOUT_REGEX") and not re.search(o["STDOUT_REGEX"], current.out):
            self.fail("stdout does not match '%s'" % o["STDOUT_REGEX"])
        if "STDOUT_LINES" in o and current.out.count("\n") != int(o["STDOUT_LINES"]):
            self.fail("stdout has %d lines, expected %s" % (current.out.count("\n"),
                                                           o["STDOUT_LINES"]))
        if o.get("PNG"):
            path = os.path.join(self.work, o["PNG"])
            if not os.path.exists(path):
                self.fail("%s was not written" % o["PNG"])
            with open(path, "rb") as stream:
                if stream.read(8) != b"\x89PNG\r\n\x1a\n":
                    self.fail("%s is not a PNG" % o["PNG"])
        if o.get("STATS"):
            self.check_stats()

    def run_octree(self):
        builder = self.o["BUILDER"]
        stats_path = os.path.join(self.work, "stats.json")
        self.first = current = run([self.o["EXE"], "octree", "--phantom", "vessels",
                                    "--phantom-dims", "37", "30", "21", "--leaf", "4",
                                    "--builder", builder, "--repeat", "3", "--stats", stats_path])
        if builder == "gpu" and current.code == "1" and re.search(
                "needs OpenGL 4.3|backend is not available", current.err):
            print("OCTREE_TEST_SKIPPED: " + current.err)
            return
        if current.code != "0":
            self.fail("expected exit code 0")
        self.check_stderr(current)
        if not re.match("octree %s " % builder, current.out):
            self.fail("expected the one-line summary on stdout")
        stats = self.read_stats("stats.json")
        for key in ("builder threads leaf dims type input nodes depth bytes bytes_per_s "
                    "read_floor_ms ratio_to_floor transparent_leaf_fraction").split():
            if key not in stats:
                self.fail("--stats lacks '%s'" % key)
        for key in ("median", "min", "max"):
            if not number(stats["ms"].get(key)) > 0:
                self.fail("--stats ms.%s missing or not positive" % key)
        for key in ("median", "min"):
            if not number(stats["classify_ms"].get(key)) >= 0:
                self.fail("--stats classify_ms.%s missing or negative" % key)
        if (stats["builder"] != builder or stats["leaf"] != 4 or stats["bytes"] != 93240
                or stats["depth"] != 4 or not stats["nodes"] > 359):
            self.fail("unexpected builder/leaf/bytes/depth/nodes")
        threads = stats["threads"]
        if ((builder == "reference" and threads != 1) or (builder == "gpu" and threads != 0)
                or (builder == "cpu" and threads < 1)):
            self.fail("unexpected threads %s for %s" % (threads, builder))
        if not 0 <= stats["transparent_leaf_fraction"] <= 1:
            self.fail("transparent_leaf_fraction outside [0, 1]")


def main():
    options = dict(argument.split("=", 1) for argument in sys.argv[1:])
    work = options["WORK"]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    if options.get("MAKE_RAW"):
        with open(os.path.join(work, options["MAKE_RAW"]), "w") as stream:
            stream.write("0123456789")
    if options.get("MAKE_TF"):
        with open(os.path.join(work, "tf.json"), "w") as stream:
            stream.write(TF_FILES[options["MAKE_TF"]])
    for key in ("ARGS", "TF"):
        if key in options:
            options[key] = options[key].replace("@WORK@", work)
    checker = Checker(options)
    try:
        if options.get("MODE") == "octree":
            checker.run_octree()
        else:
            checker.run_render()
    except Failure as failure:
        print("FAILED: %s" % failure, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
