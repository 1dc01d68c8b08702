// TetGen oracle shim (to be written): exposes Delaunay tetrahedralization of a point set with a C ABI.
