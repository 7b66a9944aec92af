"""The command-line pipeline on every shared data set and the brava-records cohort, measured by its own
check: the per-set table of docs/pipeline.md ("Where it stands").

    /usr/bin/python3 docs/shared_sets.py [--shared ../shared/data] [--cohort N] [--method default|uniform|both]
                                         [--sets all|cerebral] [--against moved|file] [--mesh-args "..."] [--cli EXE]

For each file: `vesselmesh mesh FILE -o out.ply --stats-json s.json --centerline-out moved.vtk [--method uniform]`
(default options otherwise, with --mesh-args added) and `vesselmesh check out.ply --centerline moved.vtk --json`:
measured against the tubes the surface follows, those of the centerline as the separate stage left it, its
crossing vessels moved apart (`--against file`: against the file's own tubes, where the moved vessels count
as off them). Columns: sections (the tile
stage's, joint squares included); triangles; topology ("ok": a closed, consistently oriented 2-manifold
with one piece per input component); genus / the input's loops; self-intersecting triangle pairs (of them,
in brackets, those outside overlapping input tubes); the share of the area whose faces lie over half a
local radius off the input's tubes; the furthest face centroid from them, in local radii; face-centroid
error median / 95th / 99th percentile (|distance to the tubes| over the local radius, area-weighted, %); vertex
radius error at the 95th percentile (%); the longest stretch of the input's axis with no surface round it
(radii); seconds for `mesh`. The cohort (the first N files in name order, all 42 by default) is given as its
median tree and its worst, with the trees that cross themselves; `--cohort-rows` lists every tree.
"""
import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLI = ROOT / "build" / "bin" / "vesselmesh"
CEREBRAL = ["brava-bg0003/BG0003_ColorCoded.CNG.swc", "human-brain-arteries/arteries_smooth.vtk"]
SETS = CEREBRAL + [
    "brava-bg0003/records.swc",
    "vmtk-aorta-centerline/aorta-centerline.vtp",
    "vascpy-mouse-vessels/penetrating_artery.vtk",
    "vascpy-mouse-vessels/test_smaller_vasculature.vtk",
    "neuron-hemibrain-da1/1734350788.swc",
    "secomb-rat-cortex-50/network.vtk",
    "secomb-rat-mesentery/network.vtk",
    "vesselgraph-demo/vertices.csv",
]
# What the table prints of a measurement: header, format, and which is worst over the cohort.
COLUMNS = [("sections", "{:,.0f}", max), ("triangles", "{:,.0f}", max), ("topology", "{}", None),
           ("genus / loops", "{}", None), ("pairs (outside)", "{}", None), ("area off %", "{:.2f}", max),
           ("furthest (radii)", "{:.2f}", max), ("centroid med / p95 / p99 %", "{}", None),
           ("radius p95 %", "{:.1f}", max), ("axis missing (radii)", "{:.1f}", max), ("s", "{:.2f}", max)]


def measure(cli, path, method, work, extra=(), against="moved"):
    out, stats, moved = work / "out.ply", work / "stats.json", work / "moved.vtk"
    command = [cli, "mesh", str(path), "-o", str(out), "--stats-json", str(stats), *extra]
    if against == "moved":
        command += ["--centerline-out", str(moved)]
    if method == "uniform":
        command += ["--method", "uniform"]
    start = time.perf_counter()
    # Exit status 2: written, but the surface fails its own check (counted below).
    if subprocess.run(command, capture_output=True).returncode not in (0, 2):
        raise RuntimeError(" ".join(command) + " failed")
    seconds = time.perf_counter() - start
    s = json.loads(stats.read_text())
    tubes = moved if against == "moved" else path
    checked = subprocess.run([cli, "check", str(out), "--centerline", str(tubes), "--json"],
                             capture_output=True, text=True)
    if checked.returncode not in (0, 2):  # 2: the surface fails the check (its figures say where)
        raise RuntimeError(f"vesselmesh check {out} failed: {checked.stderr}")
    c = json.loads(checked.stdout)
    t, f, x = c["topology"], c["fidelity"], c["intersections"]
    v = s["verified"]
    ok = c["closed_manifold"] and t["components"] == v["expected_components"]
    e = f["centroid_error"]
    return {"sections": s["sections"], "triangles": t["faces"], "topology": "ok" if ok else "NOT",
            "genus / loops": f"{t['genus']} / {v['loops']}",
            "pairs (outside)": f"{x['pairs']} ({x['pairs'] - x['pairs_in_overlapping_tubes']})",
            "area off %": 100 * f["area_off_tubes"], "furthest (radii)": f["largest_centroid_offset"]["relative"],
            "centroid med / p95 / p99 %": f"{100 * e['median']:.1f} / {100 * e['p95']:.1f} / {100 * e['p99']:.1f}",
            "radius p95 %": 100 * f["abs_relative_error"]["p95"],
            "axis missing (radii)": f["missing_axis"]["relative"], "s": seconds,
            "_pairs": x["pairs"], "_ok": ok, "_c": [100 * e[q] for q in ("median", "p95", "p99")]}


def row(name, m):
    return "| " + " | ".join([name] + [fmt.format(m[key]) for key, fmt, _ in COLUMNS]) + " |"


def cohort_rows(name, rows):
    median = {key: statistics.median(r[key] for r in rows) for key, _, worst in COLUMNS if worst}
    worst = {key: worst(r[key] for r in rows) for key, _, worst in COLUMNS if worst}
    crossing = [r for r in rows if r["_pairs"] > 0]
    for m, what in ((median, "median"), (worst, "worst")):
        m["topology"] = f"ok {sum(r['_ok'] for r in rows)} of {len(rows)}"
        m["genus / loops"] = "—"
        m["pairs (outside)"] = (f"{len(crossing)} trees: " + ", ".join(r["_name"] for r in crossing)
                                if crossing else "0 in every tree")
        pick = statistics.median if what == "median" else max
        m["centroid med / p95 / p99 %"] = " / ".join(f"{pick(r['_c'][q] for r in rows):.1f}" for q in range(3))
    return [row(f"{name}, {what} tree", m) for m, what in ((median, "median"), (worst, "worst"))]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--shared", default=str(ROOT.parent / "shared" / "data"))
    parser.add_argument("--cohort", type=int, default=42)
    parser.add_argument("--cohort-rows", action="store_true", help="a row for every tree of the cohort")
    parser.add_argument("--method", choices=["default", "uniform", "both"], default="default")
    parser.add_argument("--sets", choices=["all", "cerebral"], default="all")
    parser.add_argument("--against", choices=["moved", "file"], default="moved",
                        help="measure against the tubes as the separate stage left them, or the file's own")
    parser.add_argument("--mesh-args", default="", help="more options for `vesselmesh mesh` (\"--tolerance 0\")")
    parser.add_argument("--cli", default=str(CLI), help="the vesselmesh executable (another build's, to compare)")
    args = parser.parse_args()
    shared = Path(args.shared)
    cohort = sorted((shared / "brava-records").glob("*.swc"))[:args.cohort]
    methods = ["default", "uniform"] if args.method == "both" else [args.method]
    extra = args.mesh_args.split()
    print("| set (method) | " + " | ".join(key for key, _, _ in COLUMNS) + " |")
    print("|---" * (len(COLUMNS) + 1) + "|")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for method in methods:
            for name in SETS if args.sets == "all" else CEREBRAL:
                print(row(f"{name} ({method})", measure(args.cli, shared / name, method, work, extra, args.against)), flush=True)
            rows = []
            for path in cohort:
                rows.append(measure(args.cli, path, method, work, extra, args.against) | {"_name": path.stem.replace("records", "")})
                if args.cohort_rows:
                    print(row(f"brava-records/{path.name} ({method})", rows[-1]), flush=True)
            if rows:
                print("\n".join(cohort_rows(f"brava-records, {len(rows)} trees ({method})", rows)), flush=True)


if __name__ == "__main__":
    main()
