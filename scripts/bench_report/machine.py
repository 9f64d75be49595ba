"""Facts about the machine and the source revision a benchmark run used.

bench.sh records them at run time (`benchmark_report.py --collect-machine`) into machine.json, so
that a report regenerated later (--skip-run) still describes the machine that ran the benchmarks.
The revision is read from .git directly (HEAD, loose refs, packed-refs): no git process runs.
"""

import datetime
import json
import os
import platform

from .common import table


def _read(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as stream:
            return stream.read()
    except OSError:
        return ""


def cpu_model():
    for line in _read("/proc/cpuinfo").splitlines():
        if line.lower().startswith("model name") and ":" in line:
            return line.split(":", 1)[1].strip()
    return platform.processor() or platform.machine() or "unknown"


def memory_gib():
    for line in _read("/proc/meminfo").splitlines():
        if line.startswith("MemTotal:"):
            return round(int(line.split()[1]) / 1024 / 1024, 1)
    return None


def os_name():
    for line in _read("/etc/os-release").splitlines():
        if line.startswith("PRETTY_NAME="):
            return line.split("=", 1)[1].strip().strip('"')
    return platform.platform()


def git_revision(repo):
    """(commit, ref name) of the checkout at `repo`, ('', '') when it is not a git checkout."""
    git_dir = os.path.join(repo, ".git")
    if os.path.isfile(git_dir):  # a worktree or submodule: "gitdir: <path>"
        text = _read(git_dir).strip()
        if text.startswith("gitdir:"):
            git_dir = os.path.normpath(os.path.join(repo, text[len("gitdir:"):].strip()))
    head = _read(os.path.join(git_dir, "HEAD")).strip()
    if not head:
        return "", ""
    if not head.startswith("ref:"):
        return head, "(detached)"
    ref = head[4:].strip()
    # Linked worktrees keep refs in the common directory.
    common = _read(os.path.join(git_dir, "commondir")).strip()
    dirs = [git_dir] + ([os.path.normpath(os.path.join(git_dir, common))] if common else [])
    for directory in dirs:
        commit = _read(os.path.join(directory, ref)).strip()
        if commit:
            return commit, ref
        for line in _read(os.path.join(directory, "packed-refs")).splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[1] == ref:
                return parts[0], ref
    return "", ref  # a branch without commits yet


def collect(repo, mode):
    commit, ref = git_revision(repo)
    return {
        "cpu": cpu_model(),
        "cores": os.cpu_count(),
        "memory_gib": memory_gib(),
        "os": os_name(),
        "kernel": platform.release(),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "git_commit": commit,
        "git_ref": ref,
        "mode": mode,
    }


def write(path, repo, mode):
    with open(path, "w", encoding="utf-8") as stream:
        json.dump(collect(repo, mode), stream, indent=2)
        stream.write("\n")


def section(machine, gl_renderers, runs):
    """Markdown of the machine table and the list of benchmark runs (command, exit, seconds)."""
    rows = []
    if machine:
        cores = machine.get("cores")
        memory = machine.get("memory_gib")
        rows += [("CPU", machine.get("cpu", "?")),
                 ("Cores (hardware threads)", cores if cores is not None else "?"),
                 ("Memory", f"{memory} GiB" if memory else "?"),
                 ("OS / kernel", f"{machine.get('os', '?')} / {machine.get('kernel', '?')}"),
                 ("Date of the run", machine.get("date", "?")),
                 ("Revision", _revision_text(machine))]
    else:
        rows.append(("Machine", "machine.json missing: run scripts/bench.sh (not --skip-run)"))
    rows.append(("OpenGL renderer", "; ".join(sorted(gl_renderers)) or "not recorded"))
    text = table(["", ""], rows, "ll")
    if runs:
        text += "\nRuns (commands relative to the build's `bin/`; logs in `results/`):\n\n"
        text += table(["Benchmark", "Exit", "Seconds", "Command"],
                      [(r["name"], r["exit"] if r["exit"] == "0" else f"**{r['exit']}**",
                        r["seconds"], f"`{r['command']}`") for r in runs], "lrrl")
    return text


def _revision_text(machine):
    commit = machine.get("git_commit") or ""
    ref = machine.get("git_ref") or ""
    if not commit:
        return f"unknown ({ref})" if ref else "unknown (not a git checkout)"
    name = ref.rsplit("/", 1)[-1] if ref else ""
    return f"`{commit[:12]}`" + (f" ({name})" if name else "") + \
        " - uncommitted changes are not detected"
