#!/usr/bin/env python3
"""Groups libFuzzer artifacts by what went wrong and where: runs each input once through a fuzz target and
prints one line per group (count, kind, site in native/vesselmesh, smallest input).
  native/fuzz/classify.py build/fuzz/bin/fuzz_pipeline build/fuzz/artifacts/pipeline/*
With --minimize OUT, shrinks one input to OUT keeping its kind and site (libFuzzer's -minimize_crash
keeps only "some crash", and on the pipeline drifts to the commonest one):
  native/fuzz/classify.py --minimize small.bin build/fuzz/bin/fuzz_pipeline crash-..."""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def classify(binary, path):
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1", UBSAN_OPTIONS="print_stacktrace=1")
    try:
        out = subprocess.run([binary, "-timeout=10", "-rss_limit_mb=2048", path], capture_output=True,
                             text=True, errors="replace", timeout=300, env=env).stderr
    except subprocess.TimeoutExpired:
        return "hang (no report within 300 s)", "?"
    frames = re.findall(r"#\d+ 0x[0-9a-f]+ in (\S+).*?(native/vesselmesh/[\w/]+\.[ch]pp):(\d+)", out)
    site = f"{frames[0][1]}:{frames[0][2]} {frames[0][0]}" if frames else "?"
    m = re.search(r"(native/vesselmesh/\S+?):(\d+):\d+: runtime error: (.*)", out)
    if m:
        what = re.sub(r"-?[\d.]+e[+-]?\d+|-?\b\d[\d.]*\b|-?inf|-?nan", "N", m.group(3))
        return "UBSan: " + what, f"{m.group(1)}:{m.group(2)}"
    m = re.search(r"ERROR: AddressSanitizer: ([\w-]+)", out)
    if m:
        return "ASan: " + m.group(1), site
    if "libFuzzer: timeout" in out:
        return "timeout (> 10 s)", site
    m = re.search(r"libFuzzer: out-of-memory \((malloc\(\d+\)|used: \d+Mb)", out)
    if m:
        return "out of memory: " + re.sub(r"\d+", "N", m.group(1)), site
    m = re.search(r"terminate called after throwing an instance of '([^']+)'\s*what\(\):\s*(.*)", out)
    if m:
        return f"uncaught {m.group(1)}: {re.sub(r'[0-9.e+-]{2,}', 'N', m.group(2))[:80]}", site
    if "non-finite vertex" in out:
        return "non-finite vertex in the output", site
    if "deadly signal" in out:
        return "deadly signal", site
    return "no finding (flaky or fixed)", "-"


def minimize(binary, path, out):
    """Greedy: drop runs of 16, 8, 4, 2, 1 bytes, then lower bytes to 0, while the finding stays the same."""
    data = open(path, "rb").read()
    want = classify(binary, path)
    print(f"{want[0]} at {want[1]}: {len(data)} bytes", file=sys.stderr)
    if want[0].startswith("no finding"):
        sys.exit("the input does not reproduce")

    def same(candidate):
        with open(out, "wb") as f:
            f.write(candidate)
        return classify(binary, out) == want

    for size in (16, 8, 4, 2, 1):
        i = 0
        while i < len(data):
            candidate = data[:i] + data[i + size:]
            if candidate and same(candidate):
                data = candidate
                print(f"  {len(data)} bytes", file=sys.stderr)
            else:
                i += size
    for i in range(len(data)):
        if data[i] != 0:
            candidate = data[:i] + b"\0" + data[i + 1:]
            if same(candidate):
                data = candidate
    with open(out, "wb") as f:
        f.write(data)
    print(f"{out}: {len(data)} bytes", file=sys.stderr)


def main():
    if sys.argv[1] == "--minimize":
        minimize(sys.argv[3], sys.argv[4], sys.argv[2])
        return
    binary, paths = sys.argv[1], sys.argv[2:]
    groups = {}
    for p in paths:
        key = classify(binary, p)
        groups.setdefault(key, []).append(p)
        print(f"{key[0]} | {key[1]} | {os.path.basename(p)}", file=sys.stderr, flush=True)
    for (kind, site), files in sorted(groups.items(), key=lambda g: -len(g[1])):
        smallest = min(files, key=os.path.getsize)
        print(f"{len(files):4d}  {kind}\n      at {site}\n      smallest: {smallest} ({os.path.getsize(smallest)} bytes)")


if __name__ == "__main__":
    main()
