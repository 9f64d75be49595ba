#!/usr/bin/python3
"""Tests of the benchmark report (scripts/benchmark_report.py and scripts/bench.sh).

  TestBenchmarkReport.py FixtureReport   report from the checked-in fixture JSON: every section,
                                         specific table numbers, valid small PNGs, the gallery
  TestBenchmarkReport.py BadInput        missing / corrupt / oddly shaped JSON: notes in the
                                         report, clear messages, no traceback
  TestBenchmarkReport.py QuickRun        scripts/bench.sh --quick --skip-build on the real data
                                         (needs ACCELVOLUME_BUILD_DIR with the built programs and
                                         ACCELVOLUME_DATA_DIR; exit 125 = skipped without data)

The fixture's numbers are round on purpose: the expected ratios below are worked out by hand
from them (e.g. composite engine/tf2/256: base 200 ms, ERT+both 50 ms -> 4.00x).
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
REPORT = os.path.join(ROOT, "scripts", "benchmark_report.py")
BENCH = os.path.join(ROOT, "scripts", "bench.sh")
FIXTURES = os.path.join(HERE, "fixtures", "results")
SKIP = 125

SECTION_TITLES = [
    "Machine",
    "Summary",
    "Slice mapper, composite: early ray termination and empty-space skipping (Lee 2005)",
    "CPU ray casting: empty-space and semi-transparent cell leaping (Lim, Kim and Shin 2009)",
    "Min-max octree build: CPU and GPU builders (Lim and Shin 2009)",
    "Shear-warp: run-length encoding, balanced partition, threads, MPI, VolPack (Kim 1998)",
    "Slice mapper, cropped MIP: boundary re-rendering (Hong, Kye and Shin 2007)",
    "Gallery",
    "How the numbers are made",
]
CHARTS = ["speedups_by_technique.png", "ours_vs_vtk_volpack.png", "composite_speedups.png",
          "raycast_ms.png", "octree_builds.png", "shearwarp_ms.png", "cropping_time.png",
          "cropping_band_error.png"]
CHART_LIMIT = 80 * 1024


def run_report(results, markdown, assets):
    return subprocess.run([sys.executable, REPORT, "--results", results, "--markdown", markdown,
                           "--assets", assets], capture_output=True, text=True, check=False)


def square_image(path, size, grey):
    """Black image with a grey square in the middle: differences are exactly computable."""
    image = Image.new("RGB", (size, size))
    low, high = size // 4, 3 * size // 4
    for x in range(low, high):
        for y in range(low, high):
            image.putpixel((x, y), (grey, grey, grey))
    image.save(path)


def make_fixture_images(results):
    gallery = os.path.join(results, "gallery")
    square_image(os.path.join(gallery, "engine_tf2_vtk-gpu.png"), 32, 100)  # the reference
    square_image(os.path.join(gallery, "engine_tf2_slice.png"), 32, 110)  # RMS 10, max 10
    square_image(os.path.join(gallery, "engine_tf2_raycast.png"), 32, 100)  # identical
    square_image(os.path.join(gallery, "engine_tf2_vtk-fixed.png"), 32, 130)  # RMS 30
    # engine_tf2_shearwarp.png is missing: gallery.tsv says that render exited with 1.
    shearwarp = os.path.join(results, "images", "shearwarp")
    os.makedirs(shearwarp)
    for kind, grey in (("ours", 120), ("volpack", 140)):  # 300 px: must be scaled to 256
        square_image(os.path.join(shearwarp, f"cthead_tf2_shaded_256_{kind}.png"), 300, grey)
    cropping = os.path.join(results, "images", "cropping")
    os.makedirs(cropping)
    for config in ("a", "b", "c", "d", "e", "ref"):
        square_image(os.path.join(cropping, f"cthead_view1_az30_el25_{config}.png"), 40, 90)


def table_rows(markdown, first_cell):
    """The cells of the Markdown table rows whose first cell is `first_cell`."""
    rows = []
    for line in markdown.splitlines():
        if line.startswith("| "):
            cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
            if cells[0] == first_cell:
                rows.append(cells)
    return rows


def section_text(markdown, title):
    """The text of the '## title' section, up to the next '## '."""
    start = markdown.index(f"\n## {title}\n")
    end = markdown.find("\n## ", start + 1)
    return markdown[start: end if end >= 0 else len(markdown)]


class PngChecks:
    def assertValidPng(self, path, max_bytes=None, max_side=None):
        self.assertTrue(os.path.isfile(path), f"{path} missing")
        with open(path, "rb") as stream:
            self.assertEqual(stream.read(8), b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG")
        with Image.open(path) as image:
            image.verify()  # checks the chunks' CRCs
        with Image.open(path) as image:
            self.assertEqual(image.format, "PNG")
            width, height = image.size
        self.assertGreater(width * height, 0)
        if max_bytes:
            self.assertLess(os.path.getsize(path), max_bytes, f"{path} is too large")
        if max_side:
            self.assertLessEqual(max(width, height), max_side, f"{path} is too large")
        return width, height


class FixtureReport(unittest.TestCase, PngChecks):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="accelvolume-report-")
        cls.assets = os.path.join(cls.tmp, "report")
        cls.results = os.path.join(cls.assets, "results")
        shutil.copytree(FIXTURES, cls.results)
        make_fixture_images(cls.results)
        cls.markdown_path = os.path.join(cls.tmp, "BENCHMARKS.md")
        cls.process = run_report(cls.results, cls.markdown_path, cls.assets)
        with open(cls.markdown_path, encoding="utf-8") as stream:
            cls.md = stream.read()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_exit_and_messages(self):
        self.assertEqual(self.process.returncode, 0, self.process.stderr)
        self.assertEqual(self.process.stderr, "")
        self.assertIn("wrote", self.process.stdout)
        self.assertNotIn("Missing or unreadable results", self.md)

    def test_every_section(self):
        for title in SECTION_TITLES:
            self.assertIn(f"\n## {title}\n", self.md)
            self.assertIn(f"- [{title}](#", self.md)

    def test_machine(self):
        self.assertEqual(table_rows(self.md, "CPU"), [["CPU", "Fixture CPU 1000"]])
        self.assertIn("`0123456789ab` (main)", self.md)
        self.assertEqual(table_rows(self.md, "OpenGL renderer"),
                         [["OpenGL renderer", "Fixture GL renderer"]])
        self.assertEqual(table_rows(self.md, "gallery")[0][1], "**1**")
        self.assertEqual(table_rows(self.md, "raycast")[0][:3], ["raycast", "0", "200"])

    def test_composite(self):
        self.assertEqual(table_rows(self.md, "engine")[0], [
            "engine", "tf2", "256", "200", "1.25x", "2.00x", "2.50x", "4.00x", "50.0", "100",
            "2.00x", "1.25", "9.50"])
        self.assertEqual(table_rows(self.md, "cthead")[0], [
            "cthead", "tf1", "512", "900", "1.50x", "2.00x", "3.00x", "4.00x", "225", "450",
            "2.00x", "0.75", "8.25"])

    def test_raycast(self):
        self.assertEqual(table_rows(self.md, "engine")[1], [
            "engine", "tf2", "400", "100 (4.00x)", "50.0 (8.00x)", "20.0% / -25.0% / 20.0%",
            "75.0", "1.50x", "yes", "10.50 / 30.25"])

    def test_octree(self):
        rows = table_rows(self.md, "engine")
        self.assertEqual(rows[2], ["engine", "256x256x128 uint8", "2.00", "300", "6.00", "4.00",
                                   "8.00", "75.00x", "2.00", "0.50x", "0.250", "50.0%"])
        self.assertEqual(table_rows(self.md, "vessels (t)")[0][7:10], ["40.00x", "2.50", "0.50x"])
        self.assertIn("the octree rebuild takes 2.43% of a frame", self.md)

    def test_shearwarp(self):
        self.assertEqual(table_rows(self.md, "cthead/tf2/256")[0], [
            "cthead/tf2/256", "100 / 60.0", "20.0 / 12.0", "18.0 / 10.0", "5.00x", "6.00x",
            "22.5", "27.0", "1.20x", "1.50x", "90%", "1.050", "18.0 / 12.0", "75%", "ok"])

    def test_cropping(self):
        text = section_text(self.md, SECTION_TITLES[6])
        self.assertIn("re-rendering costs 1.0% of the frame", text)
        self.assertEqual(table_rows(text, "(a) slice 1x (auto), re-render off")[0][1:],
                         ["100", "1.00x", "20.00", "8.00", "40.00", "10.00%"])
        self.assertEqual(table_rows(text, "(b) slice 1x (auto), re-render ON")[0][1:],
                         ["101", "1.01x", "0.50", "3.00", "1.00", "5.00%"])
        self.assertEqual(table_rows(text, "(e) vtkGPUVolumeRayCastMapper 1x")[0][1:3],
                         ["400", "4.00x"])
        self.assertNotIn("(ref)", text.split("Hong, Kye and Shin 2007")[0])  # the reference is not a row
        self.assertIn("Re-rendering vs 2x slices (time): 1.98x faster; vs VTK's GPU ray "
                      "caster: 3.96x faster", text)

    def test_summary(self):
        def row(name):
            return table_rows(self.md, name)[0][1:]
        # Median of two cases on a log scale: sqrt(1.25 * 1.5) = 1.369.
        self.assertEqual(row("slice: early ray termination"),
                         ["2", "1.37x", "1.25-1.50x", "1.01-1.66x"])
        self.assertEqual(row("slice: ERT + ESS both (default)"),
                         ["2", "4.00x", "4.00x", "2.38-4.55x"])
        self.assertEqual(row("raycast: cell leaping + distance map"),
                         ["1", "1.25x", "1.25x", "1.23-1.32x"])
        self.assertEqual(row("octree build: CPU (all threads) vs reference"),
                         ["2", "54.77x", "40.00-75.00x", "-"])
        self.assertEqual(row("shear-warp: MPI ranks vs 1"), ["1", "1.50x", "1.50x", "-"])
        self.assertEqual(row("shear-warp: RLE + balanced bands"), ["1", "6.00x", "6.00x", "5.18x"])
        self.assertEqual(row("cropping: re-rendering vs 2x slices"),
                         ["1", "1.98x", "1.98x", "2.03x"])
        self.assertEqual(row("slice (default) vs VTK GPU ray caster, composite"),
                         ["2", "2.00x", "2.00x"])
        self.assertEqual(row("raycast (dist. map) vs VTK fixed-point ray caster"),
                         ["1", "1.50x", "1.50x"])
        self.assertEqual(row("shear-warp (3), 1 thread vs VolPack"), ["1", "1.20x", "1.20x"])
        self.assertEqual(row("slice (re-render) vs VTK GPU ray caster, cropped MIP"),
                         ["1", "3.96x", "3.96x"])

    def test_charts(self):
        for name in CHARTS:
            path = os.path.join(self.assets, "charts", name)
            width, _ = self.assertValidPng(path, max_bytes=CHART_LIMIT)
            self.assertGreater(width, 300)
            self.assertIn(f"](report/charts/{name})", self.md)

    def test_gallery(self):
        text = section_text(self.md, "Gallery")
        row = table_rows(text, "**engine**<br>tf2")[0]
        self.assertIn("<br>RMS 10.0, max 10, 12.5 ms", row[1])  # slice (its stats: 12.5 ms)
        self.assertIn("<br>RMS 0.0, max 0", row[2])  # raycast, identical
        self.assertEqual(row[3], "failed (exit 1)")  # shearwarp
        self.assertIn("<br>reference", row[4])  # vtk-gpu
        self.assertIn("<br>RMS 30.0, max 30", row[5])  # vtk-fixed
        self.assertIn("VolPack, RMS 12.5 vs ours", text)  # the benchmark's own number
        self.assertIn("(b) 1x + re-render, band RMS 0.5", text)
        gallery = os.path.join(self.assets, "gallery")
        for name in os.listdir(gallery):
            self.assertValidPng(os.path.join(gallery, name), max_side=256)
        for image in re.findall(r"\]\((report/gallery/[^)]+\.png)\)", text):
            self.assertTrue(os.path.isfile(os.path.join(self.tmp, image)), image)
        with Image.open(os.path.join(gallery, "volpack_cthead_tf2_shaded_256_ours.png")) as im:
            self.assertEqual(im.size, (256, 256))  # 300 px scaled down

    def test_rerun_replaces_outputs(self):
        stale = os.path.join(self.assets, "charts", "stale.png")
        shutil.copy(os.path.join(self.assets, "charts", CHARTS[0]), stale)
        again = run_report(self.results, os.path.join(self.tmp, "again.md"), self.assets)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertFalse(os.path.exists(stale), "old charts must not survive a rerun")


class BadInput(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="accelvolume-report-bad-")
        self.assets = os.path.join(self.tmp, "report")
        self.results = os.path.join(self.assets, "results")
        shutil.copytree(FIXTURES, self.results)
        self.markdown = os.path.join(self.tmp, "BENCHMARKS.md")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def write(self, name, text):
        with open(os.path.join(self.results, name), "w", encoding="utf-8") as stream:
            stream.write(text)

    def run_and_read(self):
        process = run_report(self.results, self.markdown, self.assets)
        for stream in (process.stdout, process.stderr):
            self.assertNotIn("Traceback", stream)
        with open(self.markdown, encoding="utf-8") as stream:
            return process, stream.read()

    def test_missing_and_corrupt(self):
        os.remove(os.path.join(self.results, "octree.json"))
        with open(os.path.join(FIXTURES, "composite.json"), encoding="utf-8") as stream:
            self.write("composite.json", stream.read()[:500])  # truncated mid-file
        self.write("raycast.json", '{"benchmark": "raycast", "cases": 5}')
        self.write("cropping.json", "[1, 2, 3]")
        process, md = self.run_and_read()
        self.assertEqual(process.returncode, 1)
        self.assertRegex(process.stderr, r"error: .*composite\.json is not valid JSON \(line \d+")
        self.assertIn("raycast.json: field 'cases' must be a list of objects", process.stderr)
        self.assertIn("cropping.json holds a JSON list, not an object", process.stderr)
        self.assertNotIn("octree.json", process.stderr)  # missing is not an error
        self.assertIn("not run: `results/octree.json` is missing", md)
        self.assertEqual(md.count("could not read the results"), 2 * 3)  # list + section
        # The intact benchmark still has its table.
        self.assertEqual(table_rows(md, "cthead/tf2/256")[0][4], "5.00x")
        for title in SECTION_TITLES:
            self.assertIn(f"\n## {title}\n", md)

    def test_failed_benchmark_is_named(self):
        os.remove(os.path.join(self.results, "octree.json"))
        runs = os.path.join(self.results, "runs.tsv")
        with open(runs, encoding="utf-8") as stream:
            text = stream.read()
        with open(runs, "w", encoding="utf-8") as stream:
            stream.write(text.replace("octree\t0\t", "octree\t1\t")
                         .replace("shearwarp\t0\t", "shearwarp\t3\t"))
        process, md = self.run_and_read()
        self.assertEqual(process.returncode, 0, process.stderr)
        self.assertIn("accelvolume_benchmark_octree exited with status 1; see "
                      "`results/octree.log`", md)
        self.assertIn("accelvolume_benchmark_shearwarp exited with status 3", md)

    def test_unexpected_shape(self):
        # Valid JSON, right top-level fields, wrong types inside: still a message, no traceback.
        self.write("shearwarp.json", '{"cases": [{"runs": [{"id": "dense", "threads": "x"}], '
                   '"threads": "two", "mpi": 7}]}')
        process, md = self.run_and_read()
        self.assertEqual(process.returncode, 1)
        self.assertIn("shearwarp.json", process.stderr)
        self.assertIn("could not read the results", section_text(md, SECTION_TITLES[5]))

    def test_no_machine_and_no_gallery(self):
        os.remove(os.path.join(self.results, "machine.json"))
        shutil.rmtree(os.path.join(self.results, "gallery"))
        process, md = self.run_and_read()
        self.assertEqual(process.returncode, 0, process.stderr)
        self.assertIn("machine.json missing", md)
        self.assertIn("not rendered (results/gallery/gallery.tsv missing)", md)

    def test_no_results_folder(self):
        process = run_report(os.path.join(self.tmp, "nowhere"), self.markdown, self.assets)
        self.assertEqual(process.returncode, 2)
        self.assertIn("does not exist", process.stderr)
        self.assertNotIn("Traceback", process.stderr)


class QuickRun(unittest.TestCase, PngChecks):
    def test_bench_quick(self):
        build = os.environ.get("ACCELVOLUME_BUILD_DIR", "")
        data = os.environ.get("ACCELVOLUME_DATA_DIR", "")
        self.assertTrue(os.access(os.path.join(build, "bin", "accelvolume"), os.X_OK),
                        f"ACCELVOLUME_BUILD_DIR={build!r} has no bin/accelvolume")
        tmp = tempfile.mkdtemp(prefix="accelvolume-bench-quick-")
        try:
            process = subprocess.run(["bash", BENCH, "--quick", "--skip-build", "--out", tmp],
                                     capture_output=True, text=True, check=False)
            self.assertEqual(process.returncode, 0, process.stdout[-3000:] + process.stderr)
            with open(os.path.join(tmp, "BENCHMARKS.md"), encoding="utf-8") as stream:
                md = stream.read()
            self.assertIn("this is a **quick** run", md)
            self.assertNotIn("Missing or unreadable results", md)
            for title in SECTION_TITLES:
                self.assertIn(f"\n## {title}\n", md)
            for name in ("composite", "raycast", "octree", "shearwarp", "cropping", "gallery"):
                self.assertEqual(table_rows(md, name)[0][1], "0", f"{name} failed")
            row = table_rows(section_text(md, "Gallery"), "**engine**<br>tf2")[0]
            self.assertEqual(len(row), 6)
            self.assertEqual(sum("![" in cell for cell in row), 5, row)
            for name in CHARTS:
                self.assertValidPng(os.path.join(tmp, "report", "charts", name),
                                    max_bytes=CHART_LIMIT)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


def quick_run_data_missing(argv):
    """The quick run needs the real volumes; ctest counts exit 125 as skipped (unittest would
    turn an exit inside a test into an error)."""
    data = os.environ.get("ACCELVOLUME_DATA_DIR", "")
    if "QuickRun" in argv and not os.path.isfile(
            os.path.join(data, "engine_256x256x128_uint8.raw.gz")):
        print(f"skipped: no real volumes in ACCELVOLUME_DATA_DIR={data!r}")
        return True
    return False


if __name__ == "__main__":
    if quick_run_data_missing(sys.argv[1:]):
        sys.exit(SKIP)
    unittest.main(argv=[sys.argv[0], "-v"] + sys.argv[1:])
