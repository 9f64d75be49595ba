"""Section of accelvolume_benchmark_bricking: the slice mapper under GPU memory budgets (bricks,
uploads per frame, frame times against the unbricked frame, image difference to it). Rendered
when bricking.json is in the results."""

from .common import Section, fmt_ms, fmt_num, fmt_x, ratio, records, table

FILE = "bricking.json"
TITLE = "Slice mapper: bricking under GPU memory budgets"


def build(data, ctx):
    section = Section("bricking", TITLE, gl_renderer=data.get("renderer", ""))
    rows = []
    whole = {}
    for row in records(data, "rows", FILE):
        blend = row.get("blend", "?")
        if row.get("case") == "none":
            whole[blend] = row.get("frame_ms")
        rows.append([f"{blend}: {row.get('case', '?')}", row.get("bricks", "?"),
                     row.get("drawn", "?"), row.get("uploads_per_frame", "?"),
                     fmt_num(row.get("uploaded_mib_per_frame"), 1),
                     fmt_num(row.get("resident_mib"), 1), fmt_ms(row.get("first_ms")),
                     fmt_ms(row.get("frame_ms")), fmt_x(ratio(whole.get(blend),
                                                             row.get("frame_ms"))),
                     fmt_num(row.get("max_diff"), 0), fmt_num(row.get("mean_diff"), 4)])
    text = (f"`accelvolume_benchmark_bricking`: {data.get('dataset', '?')} "
            f"({fmt_num(data.get('volume_mib'), 1)} MiB), {data.get('size', '?')}^2; first frame "
            "and median of the next ones; \"none/cd\" is the unbricked mapper with gradients by "
            "central differences (as the bricks take them); differences in grey levels against "
            "the unbricked image.\n\n")
    header = ["Blend: budget MiB", "Bricks", "Drawn", "Uploads / frame", "MiB up / frame",
              "Resident MiB", "First ms", "Frame ms", "Unbricked / this", "Max diff",
              "Mean diff"]
    text += table(header, rows, "l" + "r" * 10)
    section.markdown = text
    return section
