"""Type stubs of the compiled module (python/src/*.rs)."""

import os
from typing import Any, Literal, Mapping, Optional, Protocol, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
_Points = npt.ArrayLike

class Error(Exception):
    """Any error of slice2solid; the text is the library's."""

class InputError(Error):
    """Malformed or invalid input, `location: reason`."""

    location: str
    reason: str

class GeometryError(Error): ...
class UnavailableError(Error): ...

class Sections:
    """Validated cross-sections."""

    def __len__(self) -> int: ...
    @property
    def n_labels(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def labels(self) -> dict[int, int]:
        """Number of regions per label."""
    @property
    def areas(self) -> list[float]:
        """Area of each section (holes subtracted)."""
    @property
    def planes(self) -> list[dict[str, Any]]:
        """Per section: normal, offset, index, regions ({label, outer, holes})."""
    def write(self, path: _Path) -> None:
        """Write as .csl or .json."""

class Solid:
    """A reconstructed solid."""

    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """(n, 3) surface vertices."""
    @property
    def faces(self) -> npt.NDArray[np.int64]:
        """(m, 3) surface triangles, counter-clockwise seen from outside."""
    @property
    def tet_vertices(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def tets(self) -> Optional[npt.NDArray[np.int64]]:
        """(k, 4) tetrahedra (None for the implicit method)."""
    @property
    def face_planes(self) -> npt.NDArray[np.int32]:
        """Per face: the input plane it lies on, or -1."""
    @property
    def face_labels(self) -> npt.NDArray[np.int32]:
        """Per face: its label, or -1."""
    @property
    def tet_labels(self) -> Optional[npt.NDArray[np.int32]]: ...
    @property
    def report(self) -> dict[str, Any]:
        """The `--report` JSON: method, phases, counts, values, warnings, total_seconds, surface."""
    def write(self, path: _Path) -> None:
        """Write the surface: .obj, .ply, .stl, .off or .vtp (with cell data)."""
    def write_tets(self, path: _Path) -> None:
        """Write the tetrahedra: .vtk, .mesh or .vtu (with labels)."""

class _Mesh(Protocol):
    @property
    def vertices(self) -> Any: ...
    @property
    def faces(self) -> Any: ...

_MeshArg = Union[Tuple[_Points, _Points], _Mesh]

def read(path: _Path, strict: bool = False) -> Sections: ...
def sections_from_arrays(
    planes: Sequence[Mapping[str, Any]],
    n_labels: int = 0,
    strict: bool = False,
    source: str = "arrays",
) -> Sections: ...
def reconstruct(
    sections: Sections,
    method: Literal["delaunay", "implicit"] = "delaunay",
    label: Optional[int] = None,
    depth: int = 9,
    no_branching: bool = False,
    no_cutting: bool = False,
    no_thicken: bool = False,
    no_shared_samples: bool = False,
    keep_topology: bool = False,
) -> Solid: ...
def reconstruct_all_labels(sections: Sections, depth: int = 9) -> dict[str, Any]: ...
def check(vertices: _Points, faces: _Points, sections: Optional[Sections] = None) -> dict[str, Any]: ...
def compare(a: _MeshArg, b: _MeshArg, samples: int = 25000, seed: int = 0) -> dict[str, Any]: ...
