#!/usr/bin/env python3
"""The benchmark suite: `bash scripts/dev.sh bench [quick]` builds, then runs this with /usr/bin/python3.

    /usr/bin/python3 scripts/bench.py [--quick] [--repeat N] [--sizes N ...] [--no-blender]

Core: the whole command `vesselmesh mesh FILE -o OUT.ply --stats-json STATS` at its default settings
(octagonal sections, level 1, fit onto, crossings separate, caps flat, verify auto: crossings
checked up to a million triangles, near the joints up to 16 million), under /usr/bin/time, on each
shared data set (../shared/data, skipped with a note when absent), on each of the 42 brava-records
trees (summarised: median and largest over the trees) and on synthetic networks (`vesselmesh synth
--sections N --binary`, written once into build/bench/). For each: the median wall time of N runs
(reading and writing the files included), the median seconds of each stage (from --stats-json), the
largest peak resident memory, the sections placed, the triangles and microseconds per triangle (wall
time / triangles). The synthetic
networks get --max-triangles 10^9: the default limit (5·10^7) refuses the million-section network before
any work; the limit changes nothing else. Every run has a time limit and an address-space limit; one
that passes either is recorded as such instead of the figures.

Blender: addon/benchmarks/import_vs_skin.py, in one Blender session: the add-on's import against Skin +
Subdivision Surface level 2 on the same centerline, and Regenerate after a small edit.

Prints one Markdown table, then the speed targets and whether each holds; the figures also go to
build/bench/results.json. --quick: one run each, synthetic networks up to 100 k sections, Blender on
brava-bg0003 only.
"""
import argparse
import json
import os
import platform
import resource
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BUILD = ROOT / "build"
BENCH = BUILD / "bench"
VESSELMESH = BUILD / "bin" / "vesselmesh"
SHARED = ROOT.parent / "shared" / "data"
SHARED_FILES = ["brava-bg0003/BG0003_ColorCoded.CNG.swc", "human-brain-arteries/arteries_smooth.vtk",
                "vmtk-aorta-centerline/aorta-centerline.vtp", "vascpy-mouse-vessels/penetrating_artery.vtk",
                "vascpy-mouse-vessels/test_smaller_vasculature.vtk", "neuron-hemibrain-da1/1734350788.swc",
                "secomb-rat-cortex-50/network.vtk", "secomb-rat-mesentery/network.vtk", "vesselgraph-demo/vertices.csv"]
BLENDER_FILES = SHARED_FILES[:2]
STAGES = ("separate", "tile", "triangulate", "subdivide", "round", "fit", "verify")
SYNTH_LIMIT = ["--max-triangles", str(10**9)]
MiB = 1024 * 1024


def say(line):
    print(line, file=sys.stderr, flush=True)


def run_limited(command, timeout, memory):
    """Runs command under /usr/bin/time with an address-space limit (bytes) and a time limit (seconds):
    (wall seconds, peak resident KiB, exit status, stderr), or None when it ran past the time limit (its
    whole process group is killed)."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))

    with tempfile.NamedTemporaryFile("r") as peak:
        start = time.perf_counter()
        process = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", peak.name, *map(str, command)],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                   start_new_session=True, preexec_fn=limit)
        try:
            _, err = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            return None
        seconds = time.perf_counter() - start
        kib = peak.read().strip().splitlines()
    return seconds, int(kib[-1]) if kib and kib[-1].isdigit() else 0, process.returncode, err


def mesh_runs(name, path, repeat, args, extra=()):
    """The core's figures for one input: a dict for the table, with `failure` set when it did not run."""
    stats_path, out_path = BENCH / "stats.json", BENCH / "out.ply"
    runs = []
    for _ in range(repeat):
        result = run_limited([VESSELMESH, "mesh", path, "-o", out_path, "--stats-json", stats_path, *extra],
                             args.timeout, args.memory_gb * 1024 * MiB)
        if result is None:
            return {"name": name, "failure": f"not done in {args.timeout} s (stopped)"}
        seconds, kib, status, err = result
        if status not in (0, 2):  # 2: written, but fails its own check (noted below)
            lines = err.strip().splitlines()
            reason = lines[-1] if lines else f"exit status {status}"
            if "bad_alloc" in reason or status < 0 or status == 137:
                reason = f"out of memory (address space limited to {args.memory_gb} GiB): {reason}"
            return {"name": name, "failure": reason}
        runs.append((seconds, kib, json.loads(stats_path.read_text())))
    out_path.unlink(missing_ok=True)
    stats = runs[-1][2]
    seconds = statistics.median(r[0] for r in runs)
    stage_seconds = {s: statistics.median(
        sum(x["seconds"] for x in r[2]["stages"] if x["stage"] == s) for r in runs) for s in STAGES}
    problem = stats["verified"]["problem"]
    note = [f"fails its own check: {problem}"] if problem else []
    verified = stats["verified"]
    note += ([] if verified["crossings_checked"] else
             ["verify: crossings checked near the joints only (over 1 M triangles)"]
             if verified["crossings_checked_near_joints"] else
             ["verify: crossings not checked (over 16 M triangles)"])
    return {"name": name, "seconds": seconds, "peak_mib": max(r[1] for r in runs) / 1024,
            "sections": stats["sections"], "triangles": stats["triangles"],
            "core_seconds": statistics.median(r[2]["seconds"] for r in runs),
            "us_per_triangle": 1e6 * seconds / stats["triangles"], "stages": stage_seconds, "runs": len(runs),
            "problem": problem, "note": "; ".join(note)}


def summary_rows(name, rows):
    """Two rows for a cohort: the median and the largest of each column over its inputs (each column on
    its own); the first says how many did not run or failed their own check (results.json names them)."""
    done = [r for r in rows if "failure" not in r]
    failed = [r for r in done if r["problem"]]
    note = [f"{len(rows) - len(done)} did not run"] if len(done) < len(rows) else []
    note += [f"{len(failed)} of {len(done)} fail their own check"] if failed else []
    result = []
    for label, pick in (("median", statistics.median), ("largest", max)):
        row = {"name": f"{name}, {label} of {len(done)}", "note": "; ".join(note) if not result else ""}
        for key in ("seconds", "peak_mib", "sections", "triangles", "core_seconds", "us_per_triangle"):
            row[key] = pick(r[key] for r in done)
        row["stages"] = {s: pick(r["stages"][s] for r in done) for s in STAGES}
        result.append(row)
    return result


def synthetic(sections, args):
    """build/bench/synth-N.vtk, written by `vesselmesh synth` unless it is there and newer than the tool."""
    path = BENCH / f"synth-{sections}.vtk"
    if not path.exists() or path.stat().st_mtime < VESSELMESH.stat().st_mtime:
        say(f"== writing {path.relative_to(ROOT)}")
        subprocess.run([VESSELMESH, "synth", "-o", path, "--sections", str(sections), "--binary"], check=True,
                       stderr=subprocess.DEVNULL, timeout=args.timeout)
    return path


def label(name):
    """A shared file's row name: its set, and the file where the set has two."""
    folder, file = name.split("/")
    return f"{folder} ({file})" if sum(f.startswith(folder + "/") for f in SHARED_FILES) > 1 else folder


def core_benchmarks(args):
    rows, notes = [], []
    if SHARED.is_dir():
        for name in SHARED_FILES:
            say(f"== core: {name}")
            rows.append(mesh_runs(label(name), SHARED / name, args.repeat, args))
        records = sorted((SHARED / "brava-records").glob("*.swc"))
        say(f"== core: brava-records, {len(records)} trees")
        cohort = [mesh_runs(p.stem, p, min(args.repeat, 3), args) for p in records]
        rows += summary_rows("brava-records", cohort)
    else:
        notes.append(f"{SHARED} is absent: the shared data sets were skipped.")
        cohort = []
    for sections in args.sizes:
        path = synthetic(sections, args)
        say(f"== core: synthetic network of {sections:,} sections")
        repeat = args.repeat if sections < 1_000_000 else 1
        row = mesh_runs(f"synthetic, {sections:,} sections", path, repeat, args, SYNTH_LIMIT)
        row["synthetic"] = sections
        rows.append(row)
    return rows, cohort, notes


def blender_benchmarks(args):
    files = [SHARED / f for f in (BLENDER_FILES[:1] if args.quick else BLENDER_FILES)]
    if not SHARED.is_dir():
        return None, f"{SHARED} is absent: the Blender part was skipped."
    say("== Blender: import vs Skin + Subdivision Surface 2, regenerate")
    out = BENCH / "blender.json"
    out.unlink(missing_ok=True)
    command = ["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
               ROOT / "addon" / "benchmarks" / "import_vs_skin.py", "--", BUILD / "vesselmesh.zip", *files,
               "--repeat", str(args.repeat), "--json", out]
    done = subprocess.run(list(map(str, command)), capture_output=True, text=True, timeout=30 * 60)
    if done.returncode != 0:
        say(done.stdout[-3000:] + done.stderr[-3000:])
        return None, f"the Blender part failed (exit status {done.returncode})."
    return json.loads(out.read_text()), ""


def fmt(value, digits=3):
    return "" if value is None else f"{value:,.{digits}f}"


def table(rows, blender):
    head = ["benchmark", "sections", "triangles", "wall s", "peak MiB", "µs / triangle", *STAGES, "other", "note"]
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 2) + "---|"]
    for r in rows:
        if "failure" in r:
            lines.append(f"| {r['name']} |" + " |" * (len(head) - 2) + f" {r['failure']} |")
            continue
        stages = [fmt(r["stages"][s]) for s in STAGES] + [fmt(r["seconds"] - r["core_seconds"])]
        lines.append(f"| {r['name']} | {r['sections']:,.0f} | {r['triangles']:,.0f} | {fmt(r['seconds'])} | "
                     f"{r['peak_mib']:,.0f} | {fmt(r['us_per_triangle'], 2)} | " + " | ".join(stages) +
                     f" | {r['note']} |")
    for f in (blender or {}).get("files", []):
        name = Path(f["file"]).parent.name
        cases = [("import (add-on, defaults)", f["import_seconds"], f["import_triangles"], ""),
                 ("Skin + Subdivision Surface 2", f["skin_seconds"], f["skin_triangles"],
                  f"{f['skin_quads']:,} quads; {f['skin_seconds'] / f['import_seconds']:.2f}× the import"),
                 ("regenerate after moving a point", f["regenerate_seconds"], f["regenerate_triangles"], ""),
                 ("regenerate, Quick Preview", f["preview_seconds"], f["preview_triangles"], "")]
        for what, seconds, triangles, note in cases:
            lines.append(f"| Blender: {name}, {what} | | {triangles:,} | {fmt(seconds)} | | "
                         f"{fmt(1e6 * seconds / triangles, 2)} |" + " |" * (len(STAGES) + 1) + f" {note} |")
    return "\n".join(lines)


def targets(rows, cohort, blender):
    """(target, measured, holds) for each speed target the suite measured; holds is None where the run did not
    cover the target (time per triangle without the million-section network)."""
    by_name = {r["name"]: r for r in rows}
    result = []
    trees = [by_name.get("brava-bg0003")] + cohort
    trees = [t for t in trees if t is not None]
    if trees and all("failure" not in t for t in trees):
        slowest = max(t["core_seconds"] for t in trees)
        largest = max(t["triangles"] for t in trees)
        result.append(("cerebral trees (brava-bg0003 and the brava-records) built by the core in ≤ 0.2 s with "
                       "≤ 250,000 triangles",
                       f"slowest {slowest:.3f} s (core stages; whole command {max(t['seconds'] for t in trees):.3f} s), "
                       f"largest {largest:,} triangles", slowest <= 0.2 and largest <= 250_000))
    synth = {r["synthetic"]: r for r in rows if "synthetic" in r}
    million = synth.get(1_000_000)
    if million is not None:
        if "failure" in million:
            result.append(("1,000,000 sections at the default level in ≤ 30 s and ≤ 6 GB", million["failure"], False))
        else:
            result.append(("1,000,000 sections at the default level in ≤ 30 s and ≤ 6 GB",
                           f"{million['seconds']:.1f} s, {million['peak_mib'] / 1024:.1f} GiB peak",
                           million["seconds"] <= 30 and million["peak_mib"] * MiB <= 6e9))
    done = [r for r in synth.values() if "failure" not in r]
    if len(done) >= 2:
        per = [r["us_per_triangle"] for r in done]
        span = f"{min(synth):,} to {max(synth):,} sections"
        result.append((f"time per triangle varies by ≤ 1.5× ({span})",
                       f"{min(per):.2f} to {max(per):.2f} µs, {max(per) / min(per):.2f}×"
                       + ("" if len(done) == len(synth) else " (of those that ran)"),
                       None if 1_000_000 not in synth else max(per) / min(per) <= 1.5 and len(done) == len(synth)))
    tree = next((f for f in (blender or {}).get("files", []) if "brava-bg0003" in f["file"]), None)
    if tree is not None:
        ratio = tree["skin_seconds"] / tree["import_seconds"]
        result.append(("Blender: brava-bg0003's import ≥ 3× faster than Skin + Subdivision Surface 2",
                       f"import {tree['import_seconds']:.2f} s, Skin + Subsurf {tree['skin_seconds']:.2f} s: {ratio:.2f}×",
                       ratio >= 3))
        result.append(("Blender: a preview regenerate ≤ 0.2 s (brava-bg0003, Quick Preview)",
                       f"{tree['preview_seconds']:.3f} s", tree["preview_seconds"] <= 0.2))
    return result


def machine():
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?")
    memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1024**3
    system = next((line.split("=", 1)[1].strip().strip('"') for line in open("/etc/os-release")
                   if line.startswith("PRETTY_NAME=")), platform.system())
    load = ", ".join(f"{x:.1f}" for x in os.getloadavg())
    return f"{system}, {os.cpu_count()} × {cpu}, {memory:.0f} GiB memory; load average at the start {load}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="one run each, synthetic networks up to 100 k sections")
    parser.add_argument("--repeat", type=int, help="runs per input (default 5, quick 1); 1 M sections run once")
    parser.add_argument("--sizes", type=int, nargs="+", help="synthetic network sections")
    parser.add_argument("--timeout", type=int, default=600, help="seconds a run may take (default 600)")
    parser.add_argument("--memory-gb", type=int, default=16, help="address space a run may use, GiB (default 16)")
    parser.add_argument("--no-blender", action="store_true", help="leave out the Blender part")
    args = parser.parse_args()
    args.repeat = args.repeat or (1 if args.quick else 5)
    args.sizes = args.sizes or ([10_000, 100_000] if args.quick else [10_000, 100_000, 1_000_000])
    BENCH.mkdir(parents=True, exist_ok=True)

    started, header = time.time(), machine()
    rows, cohort, notes = core_benchmarks(args)
    blender, note = (None, "the Blender part was left out (--no-blender).") if args.no_blender else blender_benchmarks(args)
    notes += [note] if note else []
    checks = targets(rows, cohort, blender)

    print(f"\n{'Quick' if args.quick else 'Full'} run, {time.strftime('%Y-%m-%d %H:%M')}, {time.time() - started:.0f} s: "
          f"{header}" + (f"; Blender {blender['blender']}" if blender else ""))
    print(f"Core: `vesselmesh mesh FILE -o OUT.ply` at its defaults (octagonal sections, level 1, fit onto, crossings "
          f"separate, verify auto), whole command, median of {args.repeat} runs (brava-records {min(args.repeat, 3)}, "
          f"1 M sections one); stages and other (reading, graph, writing) in seconds; synthetic networks with "
          f"{' '.join(SYNTH_LIMIT)}. Blender: medians of {args.repeat} runs in one session.\n")
    print(table(rows, blender))
    print("\n| target | measured | holds |\n|---|---|---|")
    for target, measured, holds in checks:
        print(f"| {target} | {measured} | {'not measured (no 1 M run)' if holds is None else 'yes' if holds else 'no'} |")
    for line in notes:
        print(f"\nNote: {line}")
    (BENCH / "results.json").write_text(json.dumps(
        {"machine": header, "args": vars(args), "core": rows, "brava_records": cohort, "blender": blender,
         "targets": checks}, indent=1, default=str))


if __name__ == "__main__":
    main()
