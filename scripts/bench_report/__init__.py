"""Benchmark report of AccelVolume: reads the benchmark programs' JSON and writes BENCHMARKS.md.

Modules: common (loading, formatting, Markdown tables), machine (machine facts), one module per
benchmark (composite, cropping, octree, raycast, shearwarp), charts (matplotlib, Agg), gallery
(side-by-side images and their differences) and report (puts the document together).
The entry point is scripts/benchmark_report.py.
"""
