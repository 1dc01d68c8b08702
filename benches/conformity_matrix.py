#!/usr/bin/env python3
"""The done-when matrix of issue 14: every shared reference mesh cut by every slicer mode at 16, 40,
100 and 200 planes (random: 10, 20, 30, 50), reconstructed and judged by the exact `check`
(closed, oriented 2-manifold, no crossing, no double sheet, every section within 2%), with the
worst case of each kind.

Run on demand (not in CI; the 200-plane axis grids take a minute each), Python 3 standard library
only:

    cargo build --release
    python3 benches/conformity_matrix.py --bin target/release/slice2solid --jobs 2

Options: --meshes, --modes, --counts, --random-counts, --seed, --out (a folder for the sections and
outputs, kept between runs: existing section files are reused), --jobs. One line per case, then
the clean count and the worst case per kind (non-manifold simplices, crossings, double sheets,
section difference, seconds). Exit status 1 when a case is not clean.
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "data", "reference"))
MESHES = ["Elephant", "balloondog", "balloondog_box", "eight_15", "eight_20", "hand"]
MODES = ["parallel", "fan", "sweep", "tilt", "axes"]
SECTION_BOUND = 0.02


def cases(args):
    for mesh in args.meshes:
        for mode in args.modes:
            for n in args.counts:
                yield mesh, mode, n
        for n in args.random_counts:
            yield mesh, "random", n


def run_case(args, case):
    mesh, mode, n = case
    name = f"{mesh}_{mode}_{n}"
    csl = os.path.join(args.out, name + ".csl")
    obj = os.path.join(args.out, name + ".obj")
    if not os.path.exists(csl):
        ref = os.path.join(REFERENCE, mesh + ".stl")
        cmd = [args.bin, "slice", ref, "-o", csl, "--planes", str(n), "--mode", mode,
               "--seed", str(args.seed)]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return name, {"error": "slice: " + r.stderr.strip()[-200:]}
    t0 = time.time()
    r = subprocess.run([args.bin, "reconstruct", csl, "-o", obj, "-q"], capture_output=True,
                       text=True)
    seconds = time.time() - t0
    if r.returncode != 0:
        return name, {"error": "reconstruct: " + r.stderr.strip()[-200:], "seconds": seconds}
    r = subprocess.run([args.bin, "check", obj, "--sections", csl, "--json"], capture_output=True,
                       text=True)
    try:
        c = json.loads(r.stdout)
    except json.JSONDecodeError:
        return name, {"error": "check: " + r.stderr.strip()[-200:], "seconds": seconds}
    worst = (c.get("worst_section") or {}).get("relative", 1.0)
    row = {
        "seconds": round(seconds, 2),
        "closed": c["closed"],
        "manifold": c["manifold"],
        "oriented": c["oriented"],
        "singular": c["nonmanifold_edges"] + c["nonmanifold_vertices"],
        "crossings": c["self_intersections"],
        "double_sheets": c["overlapping_coplanar_pairs"],
        "worst_section": worst,
        "components": c["components"],
        "genus": c["genus"],
    }
    row["clean"] = (c["closed"] and c["manifold"] and c["oriented"] and row["crossings"] == 0
                    and row["double_sheets"] == 0 and worst <= SECTION_BOUND)
    return name, row


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bin", default="target/release/slice2solid")
    p.add_argument("--meshes", nargs="+", default=MESHES)
    p.add_argument("--modes", nargs="+", default=MODES)
    p.add_argument("--counts", nargs="+", type=int, default=[16, 40, 100, 200])
    p.add_argument("--random-counts", nargs="+", type=int, default=[10, 20, 30, 50])
    p.add_argument("--seed", type=int, default=3)
    p.add_argument("--out", default="target/conformity_matrix")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = {}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for name, row in pool.map(lambda c: run_case(args, c), list(cases(args))):
            rows[name] = row
            print(name, json.dumps(row), flush=True)
    judged = {k: v for k, v in rows.items() if "error" not in v}
    clean = sum(v["clean"] for v in judged.values())
    print(f"\n{clean} of {len(rows)} clean ({len(rows) - len(judged)} failed to run)")
    for kind in ["singular", "crossings", "double_sheets", "worst_section", "seconds"]:
        if judged:
            name, row = max(judged.items(), key=lambda kv: kv[1][kind])
            print(f"worst {kind}: {row[kind]} ({name})")
    for name, row in rows.items():
        if "error" in row or not row["clean"]:
            print("not clean:", name, json.dumps(row))
    return 0 if clean == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
