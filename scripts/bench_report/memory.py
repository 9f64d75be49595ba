"""Section of accelvolume_benchmark_memory: peak resident memory of every mapper, each case in a
fresh child process (issue 8). Rendered when memory.json is in the results."""

from .common import Section, fmt_ms, fmt_num, number, records, table

FILE = "memory.json"
TITLE = "Memory: peak resident memory per mapper"


def _mib(value, digits=1):
    return fmt_num(value, digits)


def build(data, ctx):
    machine = data.get("machine", {})
    section = Section("memory", TITLE, gl_renderer=machine.get("gl_renderer", ""))
    settings = data.get("settings", {})
    rows = []
    for case in records(data, "cases", FILE):
        name = f"{case.get('volume', '?')}: {case.get('mapper', '?')}"
        if "baseline_mib" not in case:
            rows.append([name] + ["-"] * 13 + [case.get("note") or "not run"])
            continue
        notes = [case.get("note") or ""]
        if case.get("error"):
            notes.append(f"error: {str(case['error'])[:160]}")
        if case.get("peak_reset") is False:
            notes.append("peak includes loading")
        accel = number(case.get("acceleration_bytes"))
        rows.append([name, _mib(number(case.get("volume_bytes")) / 1048576),
                     _mib(case.get("baseline_mib")), _mib(case.get("peak_mib")),
                     _mib(case.get("peak_minus_baseline_mib")),
                     fmt_num(case.get("peak_minus_baseline_per_volume")),
                     _mib(case.get("retained_mib")), _mib(accel / 1048576),
                     fmt_ms(case.get("first_frame_ms")), fmt_ms(case.get("second_frame_ms")),
                     fmt_ms(case.get("tf_change_frame_ms")),
                     _mib(case.get("tf_change_peak_minus_before_mib")),
                     _mib(case.get("lifetime_peak_mib")), "yes" if case.get("ok") else "**no**",
                     "; ".join(n for n in notes if n)])
    limit = number(settings.get("memory_limit_mib"))
    text = (f"`accelvolume_benchmark_memory`: {settings.get('size', '?')}^2 "
            f"{settings.get('projection', '?')} {settings.get('blend', '?')}, "
            f"{settings.get('tf', '?')}, {settings.get('threads', '?')} threads; each case in its "
            "own process" + (f" capped at {limit / 1024:.1f} GiB of address space" if limit > 0
                             else "") +
            ". Memory in MiB: base = RSS with the GL context and the volume; peak = high-water "
            "mark of two frames; +peak = peak - base (x vol: in volume sizes); +kept = RSS after "
            "the frames - base; accel = the mapper's own count (ray caster: acceleration bytes, "
            "shear-warp: encoded bytes); tf = a third frame after a transfer-function change and "
            "its peak over the RSS before it; life = the process's peak, loading included.\n\n")
    header = ["Volume: mapper", "Volume MiB", "Base", "Peak", "+peak", "x vol", "+kept", "Accel",
              "1st ms", "2nd ms", "TF ms", "+TF peak", "Life", "Clean", "Note"]
    text += table(header, rows, "l" + "r" * 12 + "ll")
    section.markdown = text
    return section
