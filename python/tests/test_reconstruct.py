"""reconstruct with the CLI's options, its numpy results through trimesh, check and compare."""

import json
import subprocess
import sys
import threading
import time

import numpy as np
import pytest
import trimesh

import slice2solid
from conftest import EIGHT


def test_round_trip_through_trimesh(eight):
    sections, solid = eight
    assert solid.vertices.dtype == np.float64 and solid.vertices.shape[1] == 3
    assert solid.faces.dtype == np.int64 and solid.faces.shape[1] == 3
    mesh = trimesh.Trimesh(solid.vertices, solid.faces, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent and mesh.is_volume
    ours = slice2solid.check(solid.vertices, solid.faces)
    assert mesh.volume == pytest.approx(ours["volume"], rel=1e-12)
    assert mesh.euler_number == ours["euler"] == solid.report["surface"]["euler"]
    assert solid.report["surface"]["triangles"] == len(mesh.faces)
    # trimesh's mesh goes back in as an object with .vertices and .faces
    same = slice2solid.compare(mesh, solid, samples=2000)
    assert same["iou"] == pytest.approx(1.0, abs=1e-12) and same["hausdorff_surface"] < 1e-12


@pytest.mark.parametrize("options", [{}, {"no_cutting": True, "no_thicken": True}, {"label": 1, "no_branching": True}, {"smooth": True}])
def test_options_match_the_cli(tmp_path, cli, options):
    flags = []
    for k, v in options.items():
        flags += [f"--{k.replace('_', '-')}"] + ([] if v is True else [str(v)])
    obj, report = tmp_path / "e.obj", tmp_path / "e.json"
    run = subprocess.run([cli, "reconstruct", EIGHT, "-o", obj, "--report", report, "-q", *flags], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    cli_report = json.loads(report.read_text())
    solid = slice2solid.reconstruct(slice2solid.read(EIGHT), **options)
    assert solid.report["counts"] == cli_report["counts"]
    assert solid.report["surface"] == cli_report["surface"]
    assert solid.report["warnings"] == cli_report["warnings"]
    from_file = trimesh.load(obj, process=False)
    np.testing.assert_array_equal(from_file.vertices, solid.vertices)
    np.testing.assert_array_equal(from_file.faces, solid.faces)


def test_implicit_method_has_no_tetrahedra(tmp_path):
    sections = slice2solid.sections_from_arrays(
        [{"point": [0, 0, z], "normal": [0, 0, 1], "contours": [{"points": np.array([[0, 0, z], [2, 0, z], [2, 2, z], [0, 2, z]], float)}]} for z in (0, 1, 2)]
    )
    solid = slice2solid.reconstruct(sections, method="implicit", depth=5)
    assert solid.report["method"] == "implicit" and solid.tets is None and solid.tet_labels is None
    assert trimesh.Trimesh(solid.vertices, solid.faces, process=False).is_watertight
    with pytest.raises(slice2solid.UnavailableError, match="no tetrahedra"):
        solid.write_tets(tmp_path / "t.vtu")
    with pytest.raises(slice2solid.InputError, match='unknown method "marching"'):
        slice2solid.reconstruct(sections, method="marching")


def test_check_and_compare_refuse_bad_arrays(eight):
    _, solid = eight
    faces = solid.faces.copy()
    faces[7, 1] = len(solid.vertices)
    with pytest.raises(slice2solid.InputError) as e:
        slice2solid.check(solid.vertices, faces)
    assert e.value.location == "faces[7]" and "out of range" in e.value.reason
    with pytest.raises(slice2solid.InputError, match="expected an"):
        slice2solid.check(solid.vertices[:, :2], solid.faces)
    with pytest.raises(slice2solid.InputError, match="no triangles"):
        slice2solid.compare((solid.vertices, np.zeros((0, 3), int)), solid)


def test_the_engine_runs_without_the_gil(eight):
    """While another thread is inside reconstruct, this thread keeps running Python."""
    sections, _ = eight
    window = {}

    def work():
        window["start"] = time.perf_counter()
        slice2solid.reconstruct(sections)
        window["end"] = time.perf_counter()

    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-4)
    try:
        t = threading.Thread(target=work)
        stamps = []
        t.start()
        while t.is_alive():
            stamps.append(time.perf_counter())
        t.join()
    finally:
        sys.setswitchinterval(old)
    start, end = window["start"], window["end"]
    margin = 0.2 * (end - start)
    inside = [s for s in stamps if start + margin < s < end - margin]
    assert len(inside) > 100, f"{len(inside)} iterations during {end - start:.3f} s of reconstruct"


def test_all_labels_is_a_partition():
    """The shipped multi-label example through reconstruct_all_labels: a closed surface per label,
    the interfaces shared (every network triangle between the two labels is in both surfaces,
    opposite orientation), and the check of each surface closed."""
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[2] / "data" / "nested_fan.csl"
    p = slice2solid.reconstruct_all_labels(slice2solid.read(path), depth=6)
    assert p["labels"] == [1, 2]
    for label in (1, 2):
        v, f = p["surfaces"][label]
        mesh = trimesh.Trimesh(v, f, process=False)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
    v, f = p["interface"]
    pairs = p["interface_labels"]
    assert pairs.shape == (len(f), 2)
    between = f[(pairs[:, 0] == 1) & (pairs[:, 1] == 2)]
    assert len(between) > 0
    core_v, core_f = p["surfaces"][1]
    core = {tuple(sorted(map(tuple, core_v[t]))) for t in core_f}
    assert all(tuple(sorted(map(tuple, v[t]))) in core for t in between)
    assert p["report"]["method"] == "implicit"


def test_all_labels_with_the_delaunay_method_has_labelled_tetrahedra():
    """The Delaunay partition of the shipped multi-label example: one surface per label, and the
    tetrahedra with a label each, positive volume, both labels present."""
    import pathlib

    import numpy as np

    path = pathlib.Path(__file__).resolve().parents[2] / "data" / "nested_fan.csl"
    p = slice2solid.reconstruct_all_labels(slice2solid.read(path), method="delaunay")
    assert p["labels"] == [1, 2]
    assert p["report"]["method"] == "delaunay"
    v, t = p["tets"]
    labels = p["tet_labels"]
    assert labels.shape == (len(t),) and set(labels.tolist()) == {1, 2}
    a, b, c, d = (v[t[:, k]] for k in range(4))
    volumes = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0
    assert (volumes > 0).all()
    with pytest.raises(Exception):
        slice2solid.reconstruct_all_labels(slice2solid.read(path), method="voxels")
