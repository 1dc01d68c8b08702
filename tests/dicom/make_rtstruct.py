#!/usr/bin/env python3
"""Write the DICOM RT Structure Set test files of tests/io_rtstruct.rs, and beside each the same
sections as slice2solid JSON (explicit planes, holes given with hole_of), so the tests can check that
reading the .dcm (planes fitted, holes found by nesting, keyholes repaired) gives what the JSON says.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pydicom
    /tmp/venv/bin/python tests/dicom/make_rtstruct.py      # writes tests/dicom/*.dcm and *.json

The output is deterministic (fixed UIDs and dates), so rerunning it changes no committed file.
Coordinates are rounded to 6 decimals because DICOM stores them as decimal strings of at most 16
characters (DS); the JSON carries the very same decimals.
"""
import json
import math
import os

from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.sequence import Sequence
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

HERE = os.path.dirname(os.path.abspath(__file__))
RT_STRUCTURE_SET_STORAGE = "1.2.840.10008.5.1.4.1.1.481.3"


def uid(name):
    return generate_uid(entropy_srcs=["slice2solid-tests", name])


def r6(x):
    return round(x, 6) + 0.0  # + 0.0 turns -0.0 into 0.0


def polygon(center, u, v, radius, n, start=0.0, clockwise=False):
    """n points of a regular polygon in the plane spanned by unit vectors u, v around center."""
    pts = []
    for k in range(n):
        a = start + 2 * math.pi * k / n
        if clockwise:
            a = -a
        pts.append([r6(center[i] + radius * (math.cos(a) * u[i] + math.sin(a) * v[i])) for i in range(3)])
    return pts


def on_z(points2, z):
    return [[r6(x), r6(y), r6(z)] for x, y in points2]


class Rtstruct:
    """An RT Structure Set being built: ROIs with their closed planar contours."""

    def __init__(self, name):
        self.name = name
        self.rois = []  # (number, name, contour geometric type, [contour points])

    def roi(self, number, name, geometric_type="CLOSED_PLANAR"):
        self.rois.append((number, name, geometric_type, []))
        return self.rois[-1][3]

    def dataset(self, with_contours=True):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = RT_STRUCTURE_SET_STORAGE
        meta.MediaStorageSOPInstanceUID = uid(self.name + "/instance")
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds = Dataset()
        ds.file_meta = meta
        ds.SOPClassUID = RT_STRUCTURE_SET_STORAGE
        ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
        ds.StudyInstanceUID = uid(self.name + "/study")
        ds.SeriesInstanceUID = uid(self.name + "/series")
        ds.FrameOfReferenceUID = uid("frame")
        ds.Modality = "RTSTRUCT"
        ds.PatientName = "Phantom^Test"
        ds.PatientID = "S2S-TEST"
        ds.StudyDate = ds.StructureSetDate = "20240101"
        ds.StructureSetLabel = self.name
        rois = Sequence()
        for number, name, _, _ in self.rois:
            item = Dataset()
            item.ROINumber = number
            item.ReferencedFrameOfReferenceUID = ds.FrameOfReferenceUID
            item.ROIName = name
            item.ROIGenerationAlgorithm = "MANUAL"
            rois.append(item)
        ds.StructureSetROISequence = rois
        if with_contours:
            roi_contours = Sequence()
            for number, _, geometric_type, contours in self.rois:
                item = Dataset()
                item.ReferencedROINumber = number
                item.ROIDisplayColor = [255, 0, 0]
                seq = Sequence()
                for points in contours:
                    c = Dataset()
                    c.ContourGeometricType = geometric_type
                    c.NumberOfContourPoints = len(points)
                    c.ContourData = [x for p in points for x in p]
                    seq.append(c)
                item.ContourSequence = seq
                roi_contours.append(item)
            ds.ROIContourSequence = roi_contours
        return ds

    def save(self, **kw):
        path = os.path.join(HERE, self.name + ".dcm")
        self.dataset(**kw).save_as(path, enforce_file_format=True)
        return path


class Sections:
    """The same contours as slice2solid JSON: planes with explicit equations and holes."""

    def __init__(self):
        self.planes = []

    def plane(self, point, normal):
        self.planes.append({"point": point, "normal": normal, "contours": []})
        return self.planes[-1]["contours"]

    def save(self, name):
        with open(os.path.join(HERE, name + ".json"), "w") as f:
            json.dump({"planes": self.planes}, f, indent=1)
            f.write("\n")


def axial_two_rois():
    """Two ROIs on axial planes. "Body": disks on z = 0 and 16, rings (a contour inside a contour
    becomes a hole) on z = 4, 8, 12, and on z = 8 an island inside the ring's hole (a third level of
    nesting: material again). "Lesion": a small polygon beside it, on two of Body's planes and one
    of its own. Some contours are clockwise (RTSTRUCT does not fix the orientation). "Marker": one
    POINT contour (a fiducial), which bounds nothing and is skipped."""
    rt, js = Rtstruct("axial_two_rois"), Sections()
    body = rt.roi(1, "Body")
    lesion = rt.roi(2, "Lesion")
    rt.roi(3, "Marker", "POINT").append([[0.0, 0.0, 8.0]])
    ex, ey = [1, 0, 0], [0, 1, 0]
    per_plane = {}

    def plane_z(z):
        if z not in per_plane:
            per_plane[z] = js.plane([0, 0, z], [0, 0, 1])
        return per_plane[z]

    for z in [0, 4, 8, 12, 16]:
        contours = plane_z(z)
        if z in (0, 16):
            body.append(polygon([0, 0, z], ex, ey, 10, 20, clockwise=(z == 16)))
            contours.append({"points": body[-1], "label": 1})
            continue
        outer = polygon([0, 0, z], ex, ey, 12, 24)
        hole = polygon([0.5, 0, z], ex, ey, 5, 16, clockwise=(z == 4))
        body += [hole, outer]  # the hole first: nesting does not depend on the order
        contours.append({"points": outer, "label": 1})
        contours.append({"points": hole, "hole_of": len(contours) - 1})
        if z == 8:
            body.append(polygon([0.5, 0, z], ex, ey, 2, 8))
            contours.append({"points": body[-1], "label": 1})
    for z in [4, 6, 8]:
        contours = plane_z(z)
        lesion.append(polygon([30, 0, z], ex, ey, 4, 12, start=0.1))
        contours.append({"points": lesion[-1], "label": 2})
    rt.save()
    js.save(rt.name)


def oblique():
    """One ROI, "Prostate", on four oblique planes of a freehand sweep: a sphere cut at offsets -9,
    -3, 3, 9 along the direction (1, 2, 2)/3, each plane tilted a few degrees its own way (so no two
    are parallel, and no two cross inside the sphere); each contour is the cross-section circle as a
    32-gon."""
    rt, js = Rtstruct("oblique"), Sections()
    roi = rt.roi(7, "Prostate")
    c, radius = [5.0, -3.0, 40.0], 15.0
    tilts = [(0.05, -0.03), (-0.04, 0.02), (0.0, 0.06), (0.03, 0.04)]
    for k, offset in enumerate([-9.0, -3.0, 3.0, 9.0]):
        normal = unit([1 + tilts[k][0] * 3, 2 + tilts[k][1] * 3, 2 - tilts[k][0] * 3])
        center = [c[i] + offset * normal[i] for i in range(3)]
        u = unit(cross(normal, [1.0, 0.0, 0.0]))
        v = cross(normal, u)
        r = math.sqrt(radius**2 - offset**2)
        roi.append(polygon(center, u, v, r, 32, clockwise=(k % 2 == 1)))
        js.plane(center, normal).append({"points": roi[-1], "label": 7})
    rt.save()
    js.save(rt.name)


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def keyhole():
    """One ROI, "Ring", on three axial planes: squares on z = 0 and 10 and, on z = 5, a keyhole
    contour (the outline runs in along a zero-width channel, round a square hole clockwise, and back
    out), which is how contouring tools write a hole as one contour. The JSON gives the outer square
    and the hole as two contours."""
    rt, js = Rtstruct("keyhole"), Sections()
    roi = rt.roi(1, "Ring")
    outer = [[10, 0], [10, 10], [-10, 10], [-10, -10], [10, -10]]
    hole_cw = [[4, 0], [4, -4], [-4, -4], [-4, 4], [4, 4]]
    for z in [0, 10]:
        roi.append(on_z(outer, z))
        js.plane([0, 0, z], [0, 0, 1]).append({"points": roi[-1], "label": 1})
    roi.append(on_z(outer + [[10, 0]] + hole_cw + [[4, 0]], 5))
    contours = js.plane([0, 0, 5], [0, 0, 1])
    contours.append({"points": on_z(outer, 5), "label": 1})
    contours.append({"points": on_z(hole_cw, 5), "hole_of": 0})
    rt.save()
    js.save(rt.name)


def error_files():
    """Files the reader must refuse with a located error."""
    rt = Rtstruct("no_roi_contours")
    rt.roi(1, "Body").append(on_z([[0, 0], [1, 0], [1, 1]], 0))
    rt.save(with_contours=False)

    rt = Rtstruct("nonplanar")
    bent = rt.roi(3, "Bent")
    bent.append(on_z([[0, 0], [20, 0], [20, 20], [0, 20]], 0))
    bent.append([[0, 0, 5], [20, 0, 5], [20, 20, 8], [0, 20, 5]])  # one corner 3 off the plane
    rt.save()


if __name__ == "__main__":
    axial_two_rois()
    oblique()
    keyhole()
    error_files()
