"""The .vtp/.vtu files read by readers nobody here wrote (VTK's own, meshio): same counts and volume
as the OBJ and legacy VTK outputs, cell data where the input says."""

import subprocess

import meshio
import numpy as np
import pytest
import trimesh
import vtk
from vtk.util.numpy_support import vtk_to_numpy

import slice2solid
from conftest import EIGHT


def read_vtp(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    assert r.GetErrorCode() == 0
    return r.GetOutput()


def vtk_volume(poly):
    mp = vtk.vtkMassProperties()
    mp.SetInputData(poly)
    mp.Update()
    return mp.GetVolume()


def tet_volumes(points, tets):
    p = points[tets]
    return np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6.0


@pytest.fixture(scope="module")
def outputs(tmp_path_factory, cli):
    d = tmp_path_factory.mktemp("vtk")
    for surface, tets in [("e.vtp", "e.vtu"), ("e.obj", "e.vtk")]:
        run = subprocess.run([cli, "reconstruct", EIGHT, "-o", d / surface, "--tets", d / tets, "-q"], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
    return d


def test_vtp_has_the_obj_surface_and_volume(outputs):
    poly = read_vtp(outputs / "e.vtp")
    obj = trimesh.load(outputs / "e.obj", process=False)
    assert poly.GetNumberOfPoints() == len(obj.vertices)
    assert poly.GetNumberOfPolys() == poly.GetNumberOfCells() == len(obj.faces)
    np.testing.assert_array_equal(vtk_to_numpy(poly.GetPoints().GetData()), obj.vertices)
    conn = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    np.testing.assert_array_equal(conn, obj.faces)
    assert vtk_volume(poly) == pytest.approx(obj.volume, rel=1e-9)


def test_vtp_cell_data_marks_the_end_sections(outputs):
    poly = read_vtp(outputs / "e.vtp")
    plane = vtk_to_numpy(poly.GetCellData().GetArray("plane"))
    label = vtk_to_numpy(poly.GetCellData().GetArray("label"))
    assert len(plane) == len(label) == poly.GetNumberOfCells()
    sections = slice2solid.read(EIGHT)
    planes = sections.planes
    first, last = planes[0], planes[-1]
    # the caps only: the part of the middle plane 7 between the figure eight's hole ends that
    # only one side keeps is under the collar's prism on the other side (tests/cell_data.rs)
    assert sorted(set(plane.tolist())) == [-1, first["index"], last["index"]]
    assert set(label.tolist()) == {1}
    points = vtk_to_numpy(poly.GetPoints().GetData())
    faces = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    mesh = trimesh.Trimesh(points, faces, process=False)
    for k, p in [(0, first), (len(planes) - 1, last)]:
        on = plane == p["index"]
        distance = points[faces[on]].reshape(-1, 3) @ np.array(p["normal"]) + p["offset"]
        assert np.abs(distance).max() < 1e-12
        assert mesh.area_faces[on].sum() == pytest.approx(sections.areas[k], rel=1e-9)


def test_vtu_has_the_legacy_tetrahedra_and_volume(outputs):
    xml = meshio.read(outputs / "e.vtu")
    legacy = meshio.read(outputs / "e.vtk")
    assert [c.type for c in xml.cells] == ["tetra"]
    np.testing.assert_array_equal(xml.points, legacy.points)
    np.testing.assert_array_equal(xml.cells[0].data, legacy.cells[0].data)
    labels = xml.cell_data["label"][0]
    assert len(labels) == len(xml.cells[0].data) and set(labels.tolist()) == {1}
    volumes = tet_volumes(xml.points, xml.cells[0].data)
    assert volumes.min() > 0
    surface = trimesh.load(outputs / "e.obj", process=False)
    assert volumes.sum() == pytest.approx(surface.volume, rel=1e-6)
    # VTK's own reader: the same cells, all tetrahedra (type 10)
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(outputs / "e.vtu"))
    r.Update()
    grid = r.GetOutput()
    assert grid.GetNumberOfCells() == len(xml.cells[0].data)
    assert {grid.GetCellType(i) for i in range(grid.GetNumberOfCells())} == {vtk.VTK_TETRA}


def test_python_writes_the_same_files(outputs, tmp_path, eight):
    _, solid = eight
    solid.write(tmp_path / "p.vtp")
    solid.write_tets(tmp_path / "p.vtu")
    assert (tmp_path / "p.vtp").read_bytes() == (outputs / "e.vtp").read_bytes()
    assert (tmp_path / "p.vtu").read_bytes() == (outputs / "e.vtu").read_bytes()
    poly = read_vtp(tmp_path / "p.vtp")
    np.testing.assert_array_equal(vtk_to_numpy(poly.GetCellData().GetArray("plane")), solid.face_planes)


def test_two_labels_give_each_plane_triangle_its_region_label(tmp_path):
    def square(z, x0):
        return np.array([[x0, 0, z], [x0 + 1, 0, z], [x0 + 1, 1, z], [x0, 1, z]], float)

    planes = [{"point": [0, 0, z], "normal": [0, 0, 1], "contours": [{"points": square(z, 0), "label": 1}, {"points": square(z, 3), "label": 2}]} for z in (0, 1)]
    solid = slice2solid.reconstruct(slice2solid.sections_from_arrays(planes))
    solid.write(tmp_path / "two.vtp")
    poly = read_vtp(tmp_path / "two.vtp")
    plane = vtk_to_numpy(poly.GetCellData().GetArray("plane"))
    label = vtk_to_numpy(poly.GetCellData().GetArray("label"))
    points = vtk_to_numpy(poly.GetPoints().GetData())
    faces = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    x = points[faces].mean(axis=1)[:, 0]
    on = plane >= 0
    assert on.sum() > 0
    # caps: label by region (x < 2 is label 1); walls touch no plane and belong to a union: -1
    assert (label[on] == np.where(x[on] < 2, 1, 2)).all()
    assert (label[~on] == -1).all()
    assert vtk_volume(poly) == pytest.approx(2.0, rel=1e-12)
