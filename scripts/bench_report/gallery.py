"""The image gallery: the same volume, transfer function and camera rendered by our mappers and by
VTK's, side by side, with grey-level differences against a reference mapper; plus the shear-warp
benchmark's VolPack pictures and the cropping benchmark's cut-face comparison.

Inputs (under the results folder, written by scripts/bench.sh):
  gallery/gallery.tsv   "# args: ..." then one line per render: dataset, tf, mapper, exit code,
                        PNG and stats JSON (names relative to gallery/)
  images/shearwarp/     NAME_TF_shaded_SIZE_{ours,volpack}.png of accelvolume_benchmark_shearwarp
  images/cropping/      NAME_VIEW_CONFIG.png of accelvolume_benchmark_cropping
Thumbnails (at most THUMBNAIL px) are written to the report's gallery/ folder.
"""

import glob
import json
import os
import re

import numpy
from PIL import Image

from .common import fmt_ms, fmt_num, table

THUMBNAIL = 256
MAPPERS = ["slice", "raycast", "shearwarp", "vtk-gpu", "vtk-fixed"]
# The reference of the difference numbers: VTK's GPU ray caster, the mapper most VTK users know.
REFERENCE = "vtk-gpu"
CROPPING_CONFIGS = [("a", "(a) 1x slices"), ("b", "(b) 1x + re-render"), ("d", "(d) 2x slices"),
                    ("e", "(e) VTK GPU"), ("ref", "reference (8x)")]


def read_rgb(path):
    with Image.open(path) as image:
        return numpy.asarray(image.convert("RGB"), dtype=numpy.float64)


def difference(path, reference_path):
    """(RMS, max, pixels) of grey levels (mean of R, G, B; 0..255) over the pixels that are not
    black in either image, as the benchmarks measure; None when the sizes differ."""
    image, reference = read_rgb(path), read_rgb(reference_path)
    if image.shape != reference.shape:
        return None
    mask = (image.max(axis=2) > 0) | (reference.max(axis=2) > 0)
    pixels = int(mask.sum())
    if pixels == 0:
        return 0.0, 0.0, 0
    delta = (image.mean(axis=2) - reference.mean(axis=2))[mask]
    return float(numpy.sqrt(numpy.mean(delta * delta))), float(numpy.abs(delta).max()), pixels


def thumbnail(source, target):
    """A copy of `source` at most THUMBNAIL px on its longer side, as an optimized RGB PNG."""
    with Image.open(source) as image:
        image = image.convert("RGB")
        if max(image.size) > THUMBNAIL:
            scale = THUMBNAIL / max(image.size)
            image = image.resize((max(1, round(image.size[0] * scale)),
                                  max(1, round(image.size[1] * scale))), Image.LANCZOS)
        image.save(target, optimize=True)


def _read_tsv(path):
    args, entries = "", []
    with open(path, encoding="utf-8") as stream:
        for line in stream:
            line = line.rstrip("\n")
            if line.startswith("# args:"):
                args = line[len("# args:"):].strip()
            elif line and not line.startswith("#"):
                parts = line.split("\t")
                if len(parts) >= 6:
                    entries.append(dict(zip(["dataset", "tf", "mapper", "exit", "png", "stats"],
                                            parts)))
    return args, entries


def _cell(ctx, out_dir, stem, source, caption):
    target = os.path.join(out_dir, stem + ".png")
    thumbnail(source, target)
    return f"![{stem}]({ctx.link(target)})<br>{caption}"


def _mappers_table(ctx, gallery_dir, out_dir):
    tsv = os.path.join(gallery_dir, "gallery.tsv")
    if not os.path.exists(tsv):
        return "", "not rendered (results/gallery/gallery.tsv missing)"
    args, entries = _read_tsv(tsv)
    if not entries:
        return "", "gallery.tsv lists no renders"
    groups = []
    for entry in entries:
        key = (entry["dataset"], entry["tf"])
        if key not in groups:
            groups.append(key)
    rows = []
    for dataset, tf in groups:
        found = {e["mapper"]: e for e in entries if (e["dataset"], e["tf"]) == (dataset, tf)}
        reference = found.get(REFERENCE)
        reference_png = os.path.join(gallery_dir, reference["png"]) if reference else None
        have_reference = reference_png and os.path.exists(reference_png)
        row = [f"**{dataset}**<br>{tf}"]
        for mapper in MAPPERS:
            entry = found.get(mapper)
            png = os.path.join(gallery_dir, entry["png"]) if entry else None
            if not entry:
                row.append("not rendered")
                continue
            if entry["exit"] != "0":
                row.append(f"failed (exit {entry['exit']})")
                continue
            if not os.path.exists(png):
                row.append("image missing (rerun `bench.sh --only gallery`)")
                continue
            caption = _stats_caption(os.path.join(gallery_dir, entry["stats"]))
            if mapper == REFERENCE:
                caption = "reference" + caption
            elif have_reference:
                diff = difference(png, reference_png)
                caption = (f"RMS {fmt_num(diff[0], 1)}, max {diff[1]:.0f}" if diff
                           else "size differs") + caption
            row.append(_cell(ctx, out_dir, f"{dataset}_{tf}_{mapper}", png, caption))
        rows.append(row)
    text = (f"Rendered by `accelvolume render {args}` (one frame after a warm-up; the times are "
            "for orientation, not benchmarks). Differences are grey levels (0..255) against "
            f"`{REFERENCE}` over the pixels not black in either image.\n\n")
    return text + table(["Volume"] + [f"`{m}`" for m in MAPPERS], rows, "l" + "c" * 5), ""


def _stats_caption(path):
    try:
        with open(path, encoding="utf-8") as stream:
            stats = json.load(stream)
        return f", {fmt_ms(stats['ms_per_frame']['median'])} ms"
    except (OSError, ValueError, KeyError, TypeError):
        return ""


def _volpack_table(ctx, images_dir, out_dir, shearwarp):
    """Our shear-warp next to VolPack at the shear-warp benchmark's fixed view (smallest size)."""
    pairs = {}
    for ours in sorted(glob.glob(os.path.join(images_dir, "*_ours.png"))):
        match = re.match(r"(.+)_(tf\d)_(shaded|unshaded)_(\d+)_ours\.png$", os.path.basename(ours))
        volpack = ours[: -len("_ours.png")] + "_volpack.png"
        if match and os.path.exists(volpack):
            key = (match.group(1), match.group(2), match.group(3))
            size = int(match.group(4))
            if key not in pairs or size < pairs[key][0]:
                pairs[key] = (size, ours, volpack)
    if not pairs:
        return ""
    measured = {}
    for case in (shearwarp or {}).get("cases", []) if isinstance(shearwarp, dict) else []:
        if isinstance(case, dict) and isinstance(case.get("volpack"), dict):
            measured[case.get("key")] = case["volpack"].get("vs_ours", {}).get("rms")
    rows = []
    for (dataset, tf, shade), (size, ours, volpack) in sorted(pairs.items()):
        rms = measured.get(f"{dataset}/{tf}/{shade}/{size}")
        if rms is None:
            diff = difference(volpack, ours)
            rms = diff[0] if diff else None
        stem = f"volpack_{dataset}_{tf}_{shade}_{size}"
        rows.append([f"**{dataset}**<br>{tf}, {shade}, {size}^2",
                     _cell(ctx, out_dir, stem + "_ours", ours, "ours, (3) RLE + balance"),
                     _cell(ctx, out_dir, stem + "_volpack", volpack,
                           f"VolPack, RMS {fmt_num(rms, 1)} vs ours")])
    return ("\n#### Shear-warp: ours and VolPack\n\nThe shear-warp benchmark's fixed view "
            "(parallel camera, azimuth 30, elevation 20), same classified volume and transfer "
            "function; VolPack shades the volume's border voxels differently.\n\n" +
            table(["Case", "AccelVolume shear-warp", "VolPack"], rows, "lcc"))


def _cropping_table(ctx, images_dir, out_dir, cropping):
    datasets = (cropping or {}).get("datasets", []) if isinstance(cropping, dict) else []
    for dataset in datasets if isinstance(datasets, list) else []:
        name = dataset.get("name") if isinstance(dataset, dict) else None
        views = sorted(glob.glob(os.path.join(images_dir, f"{name}_view1_*_ref.png")))
        if not name or not views:
            continue
        prefix = views[0][: -len("_ref.png")]
        configs = {c.get("id"): c for c in dataset.get("configs", []) if isinstance(c, dict)}
        row = [f"**{name}**<br>view 1"]
        for cid, label in CROPPING_CONFIGS:
            path = f"{prefix}_{cid}.png"
            if not os.path.exists(path):
                row.append("-")
                continue
            band = configs.get(cid, {}).get("band_rms_error")
            caption = label + ("" if cid == "ref" else f", band RMS {fmt_num(band, 1)}")
            row.append(_cell(ctx, out_dir, f"cropping_{name}_{cid}", path, caption))
        return ("\n#### Cropped MIP: cut faces re-rendered or not\n\nThe cropping benchmark's "
                "first view; band RMS = error along the projected crop-box outline (both views) "
                "against the 8x reference.\n\n" +
                table(["Volume"] + [label for _, label in CROPPING_CONFIGS], [row], "lccccc"))
    return ""


def build(ctx, results_dir, out_dir, shearwarp=None, cropping=None):
    """Markdown of the gallery section, and a list of problems to mention."""
    os.makedirs(out_dir, exist_ok=True)
    text, problem = _mappers_table(ctx, os.path.join(results_dir, "gallery"), out_dir)
    problems = [problem] if problem else []
    text += _volpack_table(ctx, os.path.join(results_dir, "images", "shearwarp"), out_dir,
                           shearwarp)
    text += _cropping_table(ctx, os.path.join(results_dir, "images", "cropping"), out_dir,
                            cropping)
    return text, problems
