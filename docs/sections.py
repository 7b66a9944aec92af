"""Sections, triangles, face-centroid error, crossings and time of the command-line pipeline on the shared
sets: the figures of the sample section in docs/pipeline.md.

    /usr/bin/python3 docs/sections.py [--shared ../shared/data] [--cohort N] [--method default|uniform|both] [--cli EXE]

For each file: `vesselmesh mesh FILE -o out.ply --stats-json s.json [--method uniform]` and
`vesselmesh check out.ply --centerline FILE --json`. Sections are the tile stage's (`sections`, joint squares
included); the centroid error is |distance of a face centroid to the input's tubes| over the local radius
(median / 95th / 99th percentile, %); crossings are the self-intersecting triangle pairs. The cohort rows
(brava-records, the first N files in name order, all 42 by default) are summed or given as their median.
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CLI = ROOT / "build" / "bin" / "vesselmesh"
SETS = ["brava-bg0003/BG0003_ColorCoded.CNG.swc", "human-brain-arteries/arteries_smooth.vtk"]


def measure(cli, path, method, work):
    out, stats = work / "out.ply", work / "stats.json"
    command = [cli, "mesh", str(path), "-o", str(out), "--stats-json", str(stats)]
    if method == "uniform":
        command += ["--method", "uniform"]
    start = time.perf_counter()
    # Exit status 2: written, but the surface fails its own check (crossings, counted below).
    if subprocess.run(command, capture_output=True).returncode not in (0, 2):
        raise RuntimeError(" ".join(command) + " failed")
    seconds = time.perf_counter() - start
    s = json.loads(stats.read_text())
    check = subprocess.run([cli, "check", str(out), "--centerline", str(path), "--json"],
                           capture_output=True, text=True)
    c = json.loads(check.stdout)
    e = c["fidelity"]["centroid_error"]
    return dict(sections=s["sections"], triangles=c["topology"]["faces"], median=100 * e["median"],
                p95=100 * e["p95"], p99=100 * e["p99"], crossings=c["intersections"]["pairs"],
                min_angle=c["quality"]["min_angle"]["median"], seconds=seconds)


def line(name, m):
    return (f"{name:42s} {m['sections']:>7} {m['triangles']:>9} {m['median']:6.1f} {m['p95']:6.1f} "
            f"{m['p99']:6.1f} {m['crossings']:>6} {m['min_angle']:6.1f} {m['seconds']:6.2f}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--shared", default=str(ROOT.parent / "shared" / "data"))
    parser.add_argument("--cohort", type=int, default=42)
    parser.add_argument("--method", choices=["default", "uniform", "both"], default="both")
    parser.add_argument("--cli", default=str(CLI), help="the vesselmesh executable (another build's, to compare)")
    args = parser.parse_args()
    shared = Path(args.shared)
    cohort = sorted((shared / "brava-records").glob("*.swc"))[:args.cohort]
    methods = ["default", "uniform"] if args.method == "both" else [args.method]
    print(f"{'set (method)':42s} {'sect.':>7} {'tris':>9} {'c.med':>6} {'c.p95':>6} {'c.p99':>6} {'cross':>6} "
          f"{'minang':>6} {'s':>6}")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for method in methods:
            for name in SETS:
                print(line(f"{name.split('/')[0]} ({method})", measure(args.cli, shared / name, method, work)), flush=True)
            rows = []
            for path in cohort:
                rows.append(measure(args.cli, path, method, work))
                print(line(f"  {path.stem} ({method})", rows[-1]), file=sys.stderr, flush=True)
            if rows:
                median = {k: statistics.median(r[k] for r in rows) for k in rows[0]}
                print(line(f"brava-records x{len(rows)} median ({method})", median))
                print(f"{'':42s} max triangles {max(r['triangles'] for r in rows)}, trees crossing "
                      f"{sum(r['crossings'] > 0 for r in rows)}, crossing pairs {sum(r['crossings'] for r in rows)}, "
                      f"total {sum(r['seconds'] for r in rows):.1f} s", flush=True)


if __name__ == "__main__":
    main()
