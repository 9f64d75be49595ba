#!/usr/bin/python3
"""Writes BENCHMARKS.md (tables, charts, gallery) from the JSON results of AccelVolume's benchmark
programs, as collected by scripts/bench.sh.

  benchmark_report.py --results DIR [--markdown FILE] [--assets DIR]
  benchmark_report.py --collect-machine FILE [--mode quick|full]

--results DIR     the folder bench.sh filled: composite.json, raycast.json, octree.json,
                  shearwarp.json, cropping.json, machine.json, runs.tsv, gallery/, images/
--markdown FILE   the report (default: BENCHMARKS.md beside the results' parent folder)
--assets DIR      where charts/ and gallery/ go (default: the results' parent folder)
--collect-machine FILE  record CPU, cores, memory, OS, date and the git revision of this
                  checkout as JSON (bench.sh does this before running the benchmarks)

Run with the Python that has Debian's python3-matplotlib (/usr/bin/python3). Exit status: 0 the
report was written; 1 it was written but some result file could not be read (said on stderr);
2 bad arguments or no matplotlib.
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def parse(argv):
    parser = argparse.ArgumentParser(
        description="Write BENCHMARKS.md from AccelVolume's benchmark JSON results.")
    parser.add_argument("--results", help="folder of the benchmark results (bench.sh's results/)")
    parser.add_argument("--markdown", help="the Markdown file to write")
    parser.add_argument("--assets", help="folder for charts/ and gallery/")
    parser.add_argument("--collect-machine", metavar="FILE",
                        help="write the machine description JSON and exit")
    parser.add_argument("--mode", choices=["quick", "full"], default="full",
                        help="recorded with --collect-machine (default full)")
    args = parser.parse_args(argv)
    if not args.collect_machine and not args.results:
        parser.error("--results DIR (or --collect-machine FILE) is required")
    return args


def main(argv):
    args = parse(argv)
    sys.path.insert(0, HERE)
    if args.collect_machine:
        from bench_report import machine
        machine.write(args.collect_machine, os.path.dirname(HERE), args.mode)
        return 0
    if not os.path.isdir(args.results):
        print(f"benchmark_report: error: results folder {args.results} does not exist "
              "(run scripts/bench.sh first)", file=sys.stderr)
        return 2
    try:
        from bench_report import report
    except ImportError as error:
        print(f"benchmark_report: error: {error}; install Debian's python3-matplotlib "
              "(scripts/setup.sh) and run with /usr/bin/python3", file=sys.stderr)
        return 2
    results = os.path.abspath(args.results)
    assets = os.path.abspath(args.assets or os.path.dirname(results))
    markdown = os.path.abspath(args.markdown or os.path.join(os.path.dirname(assets),
                                                             "BENCHMARKS.md"))
    os.makedirs(os.path.dirname(markdown), exist_ok=True)
    return report.main(results, markdown, assets)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
