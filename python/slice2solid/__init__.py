"""slice2solid: reconstruct a solid from planar cross-sections of arbitrary orientation.

    import slice2solid
    solid = slice2solid.reconstruct(slice2solid.read("data/eight_15.csl"))
    print(solid.vertices.shape, solid.faces.shape, solid.report["surface"])

Sections come from `.csl`/`.json` files (`read`) or numpy arrays (`sections_from_arrays`); both
are validated and repaired by the Rust library as the command line does. `reconstruct` takes the
options of `slice2solid reconstruct`; `reconstruct_all_labels` every label at once as a partition
of space (implicit method, `--all-labels`); `check` and `compare` are the library's measuring
instruments on numpy meshes. Errors are `slice2solid.Error` subclasses (`InputError` keeps the
library's location text, also as `.location` and `.reason`).
"""

from ._slice2solid import (
    Error,
    GeometryError,
    InputError,
    Sections,
    Solid,
    UnavailableError,
    check,
    compare,
    read,
    reconstruct,
    reconstruct_all_labels,
    sections_from_arrays,
)

__all__ = [
    "Error",
    "GeometryError",
    "InputError",
    "Sections",
    "Solid",
    "UnavailableError",
    "check",
    "compare",
    "read",
    "reconstruct",
    "reconstruct_all_labels",
    "sections_from_arrays",
]
