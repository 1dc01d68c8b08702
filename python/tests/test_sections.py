"""Sections from files and from numpy arrays: the library's validation, repairs and located errors."""

import json
import subprocess

import numpy as np
import pytest

import slice2solid
from conftest import EIGHT


def square(z, side=2.0, x0=0.0):
    return np.array([[x0, 0, z], [x0 + side, 0, z], [x0 + side, side, z], [x0, side, z]], float)


def box_planes(zs=(0.0, 1.0, 2.0)):
    return [{"point": [0, 0, z], "normal": [0, 0, 1], "contours": [{"points": square(z)}]} for z in zs]


def test_read_csl_gives_the_shipped_example():
    s = slice2solid.read(EIGHT)
    assert len(s) == 15
    assert s.labels == {1: 21}
    assert s.warnings == []
    assert all(a > 0 for a in s.areas)


def test_arrays_and_json_give_the_same_sections(tmp_path):
    # A clockwise outer contour (repaired, warned) with a hole, given once as arrays, once as JSON.
    outer = square(0.0, 4.0)[::-1]
    hole = np.array([[1, 1, 0], [3, 1, 0], [3, 3, 0], [1, 3, 0]], float)
    planes = [
        {"point": [0, 0, 0], "normal": [0, 0, 2], "contours": [{"points": outer, "label": 2}, {"points": hole, "hole_of": 0}]},
        {"normal": [0, 0, 1], "offset": -1.5, "contours": [{"points2d": np.array([[-3.5, 0.5], [-0.5, 0.5], [-0.5, 3.5], [-3.5, 3.5]]), "label": 2}]},
    ]
    from_arrays = slice2solid.sections_from_arrays(planes, source="t")
    doc = {"planes": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in p.items() if k != "contours"} | {"contours": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in c.items()} for c in p["contours"]]} for p in planes]}
    path = tmp_path / "t.json"
    path.write_text(json.dumps(doc))
    from_json = slice2solid.read(path)
    assert from_arrays.areas == pytest.approx([12.0, 9.0], rel=1e-12)
    assert from_arrays.areas == from_json.areas
    # The same repair, worded the same, located in each input's own terms.
    assert [w.replace("t: planes", "$.planes") for w in from_arrays.warnings] == [w.replace(f"{path}: ", "") for w in from_json.warnings]
    assert "reversed orientation" in from_arrays.warnings[0] and "t: planes[0].contours[0]" in from_arrays.warnings[0]
    for a, b in zip(from_arrays.planes, from_json.planes):
        assert a["normal"] == b["normal"] and a["offset"] == b["offset"]
        for ra, rb in zip(a["regions"], b["regions"]):
            assert ra["label"] == rb["label"] == 2
            np.testing.assert_array_equal(ra["outer"], rb["outer"])
            assert len(ra["holes"]) == len(rb["holes"])


def test_a_box_from_three_parallel_squares_has_the_box_volume():
    sections = slice2solid.sections_from_arrays(box_planes())
    solid = slice2solid.reconstruct(sections)
    report = slice2solid.check(solid.vertices, solid.faces, sections=sections)
    assert report["closed"] and report["manifold"] and report["oriented"]
    assert report["self_intersections"] == 0 and report["genus"] == 0
    assert report["volume"] == pytest.approx(8.0, rel=1e-12)
    assert max(s["relative"] for s in report["sections"]) < 1e-9


def test_a_malformed_file_raises_with_the_cli_location_text(tmp_path, cli):
    bad = tmp_path / "bad.csl"
    text = EIGHT.read_text().splitlines()
    bad.write_text("\n".join(text[:40]) + "\n")  # truncated inside the planes
    with pytest.raises(slice2solid.InputError) as e:
        slice2solid.read(bad)
    assert str(e.value).startswith(f"{bad}:")
    assert e.value.location.startswith(f"{bad}:") and e.value.reason
    assert str(e.value) == f"{e.value.location}: {e.value.reason}"
    run = subprocess.run([cli, "info", bad], capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.strip() == f"error: {e.value}"


@pytest.mark.parametrize(
    "change, location, reason",
    [
        (lambda p: p[1]["contours"][0].update(points=square(1.0)[:, :2]), "arrays: planes[1].contours[0].points", "expected an (n, 3) array"),
        (lambda p: p[2]["contours"][0]["points"].__setitem__((2, 2), 2.5), "arrays: planes[2].contours[0].points[2]", "off its plane"),
        (lambda p: p[0].update(colour=1), "arrays: planes[0]", 'unknown key "colour"'),
        (lambda p: p[0].update(normal=[0, 0, 0]), "arrays: planes[0].normal", "plane normal is zero"),
        (lambda p: p[0]["contours"].append({"points": square(0.0, 1.0, 5.0), "hole_of": 0}), "arrays: planes[0].contours[1]", "hole is not inside its parent"),
        (lambda p: p[0]["contours"][0]["points"].__setitem__((1, 0), np.nan), "arrays: planes[0].contours[0].points[1][0]", "not a finite number"),
    ],
)
def test_array_errors_are_located(change, location, reason):
    planes = box_planes()
    change(planes)
    with pytest.raises(slice2solid.InputError) as e:
        slice2solid.sections_from_arrays(planes)
    assert e.value.location == location, str(e.value)
    if reason:
        assert reason in e.value.reason


def test_bow_tie_is_repaired_unless_strict():
    bow = np.array([[0, 0, 0], [2, 2, 0], [2, 0, 0], [0, 2, 0]], float)
    planes = [{"point": [0, 0, 0], "normal": [0, 0, 1], "contours": [{"points": bow}]}]
    s = slice2solid.sections_from_arrays(planes)
    assert len(s.planes[0]["regions"]) == 2
    assert any("repaired" in w and w.startswith("arrays: planes[0].contours[0]") for w in s.warnings), s.warnings
    with pytest.raises(slice2solid.InputError) as e:
        slice2solid.sections_from_arrays(planes, strict=True)
    assert e.value.location.startswith("arrays: planes[0].contours[0]")
