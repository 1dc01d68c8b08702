#!/usr/bin/env python3
"""Accuracy and topology table (issue 19): the shared reference meshes cut by each slicer mode at a
sparse and a dense plane count, reconstructed by our methods (Delaunay raw and with --smooth,
implicit) and by screened Poisson, side by side.

Run on demand (not in CI), with the evaluation environment of ../shared/eval (its setup.sh):

    cargo build --release
    ~/.cache/slice2solid-eval/bin/python benches/accuracy_table.py --bin target/release/slice2solid

Options: --meshes, --modes, --counts, --seed, --out (a folder for the sections and outputs,
kept between runs: existing section files are reused). Screened Poisson (MeshLab through pymeshlab,
depth 9, the baseline of issue 19) runs on the contour vertices with their in-plane outward normals
when pymeshlab is installed (`pip install pymeshlab` in that environment); its column says "n/a"
otherwise. Accuracy (Chamfer L1, Hausdorff, volumetric IoU, normalised by the reference's
bounding-box diagonal) and genus/components come from ../shared/eval/evaluate.py, not from our own
checker. One line per case and method, then the mean per method over the cases all methods ran.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared"))
EVAL = os.path.join(SHARED, "eval", "evaluate.py")
sys.path.insert(0, os.path.join(SHARED, "eval"))
from evaluate import read_csl  # noqa: E402  (the evaluator's own CSL reader)

MESHES = ["eight_15", "eight_20", "balloondog", "balloondog_box", "hand", "Elephant"]
MODES = ["parallel", "random", "fan", "sweep", "tilt", "axes"]


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip()[-300:]}")
    return r.stdout


def evaluate(what, *args):
    return json.loads(run([sys.executable, EVAL, what, *args]))


def contour_points_with_normals(csl):
    """Every contour vertex with its in-plane normal pointing out of the section's material."""
    _, planes = read_csl(csl)
    points, normals = [], []
    for p in planes:
        plane_normal = np.asarray(p["abcd"][:3], float)
        plane_normal /= np.linalg.norm(plane_normal)
        comps = p["comps"]
        for label, parent, idx in comps:
            depth, q = 0, parent
            while q >= 0 and depth < len(comps):
                depth, q = depth + 1, comps[q][1]
            ring = p["verts"][idx]
            if len(ring) < 3:
                continue
            nxt = np.roll(ring, -1, axis=0)
            area = np.cross(ring, nxt).sum(axis=0)
            # counter-clockwise about the plane normal: material on the left of the edges for an
            # outer boundary (even depth), on the right for a hole
            sign = np.sign(area @ plane_normal) * (1.0 if depth % 2 == 0 else -1.0)
            edge_normals = np.cross(nxt - ring, plane_normal) * sign
            edge_normals /= np.maximum(np.linalg.norm(edge_normals, axis=1, keepdims=True), 1e-300)
            vertex_normals = edge_normals + np.roll(edge_normals, 1, axis=0)
            vertex_normals /= np.maximum(np.linalg.norm(vertex_normals, axis=1, keepdims=True), 1e-300)
            points.append(ring)
            normals.append(vertex_normals)
    return np.vstack(points), np.vstack(normals)


def poisson(csl, out):
    import pymeshlab

    pts, nrm = contour_points_with_normals(csl)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=pts, v_normals_matrix=nrm))
    ms.generate_surface_reconstruction_screened_poisson(depth=9)
    ms.save_current_mesh(out)


def has_pymeshlab():
    try:
        import pymeshlab  # noqa: F401

        return True
    except ImportError:
        return False


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True)
    ap.add_argument("--ref-dir", default=os.path.join(SHARED, "data", "reference"))
    ap.add_argument("--meshes", default=",".join(MESHES))
    ap.add_argument("--modes", default=",".join(MODES))
    ap.add_argument("--counts", default="10,40", help="sparse,dense plane counts")
    ap.add_argument("--seed", default="5")
    ap.add_argument("--out", default="/tmp/slice2solid-accuracy")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    methods = ["delaunay", "smooth", "implicit"] + (["poisson"] if has_pymeshlab() else [])
    if "poisson" not in methods:
        print("# pymeshlab not installed: no screened Poisson column", file=sys.stderr)
    head = f"{'case':28s} {'method':9s} {'chamfer':>8s} {'hausdorff':>9s} {'iou':>6s} {'genus':>5s} {'comps':>5s} {'sec':>6s}"
    print(head)
    rows = []
    for mesh in a.meshes.split(","):
        ref = os.path.join(a.ref_dir, mesh + ".stl")
        truth = evaluate("check", ref)
        for mode in a.modes.split(","):
            for n in a.counts.split(","):
                case = f"{mesh}_{mode}{n}"
                csl = os.path.join(a.out, case + ".csl")
                if not os.path.exists(csl):
                    run([a.bin, "slice", ref, "-o", csl, "--planes", n, "--mode", mode, "--seed", a.seed])
                print(f"{case:28s} {'reference':9s} {'':>8s} {'':>9s} {'':>6s} {truth.get('genus', '?'):>5} {truth.get('components', '?'):>5}")
                for m in methods:
                    out = os.path.join(a.out, f"{case}.{m}.obj")
                    t0 = time.time()
                    try:
                        if m == "poisson":
                            poisson(csl, out)
                        elif m == "smooth":
                            run([a.bin, "reconstruct", csl, "-o", out, "--smooth", "-q"])
                        else:
                            run([a.bin, "reconstruct", csl, "-o", out, "--method", m, "-q"])
                        sec = time.time() - t0
                        acc = evaluate("accuracy", out, ref)
                        chk = evaluate("check", out)
                    except Exception as e:  # a failure is a row, not the end of the table
                        print(f"{case:28s} {m:9s} failed: {str(e)[:120]}")
                        continue
                    row = (case, m, acc.get("chamfer_l1"), acc.get("hausdorff"), acc.get("iou"), chk.get("genus"), chk.get("components"), sec)
                    rows.append(row)
                    c, h, i = (x if x is not None else float("nan") for x in row[2:5])
                    print(f"{case:28s} {m:9s} {c * 1e3:8.3f} {h:9.4f} {i:6.3f} {row[5]!s:>5} {row[6]!s:>5} {sec:6.2f}", flush=True)
    # means over the cases every method ran (Chamfer in units of 1e-3 of the diagonal)
    cases = {r[0] for r in rows}
    full = [c for c in cases if sum(r[0] == c for r in rows) == len(methods)]
    print(f"\nmeans over {len(full)} cases that every method ran (Chamfer x1e-3):")
    for m in methods:
        sel = [r for r in rows if r[1] == m and r[0] in full and None not in r[2:5]]
        if sel:
            mean = lambda k: sum(r[k] for r in sel) / len(sel)  # noqa: E731
            print(f"  {m:9s} chamfer {mean(2) * 1e3:.3f} hausdorff {mean(3):.4f} iou {mean(4):.3f}")


if __name__ == "__main__":
    main()
