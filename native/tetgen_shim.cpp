// TetGen oracle shim: Delaunay tetrahedralization of a point set through a C ABI.
// Built by build.rs only with the cargo feature `tetgen`; linked against Debian's libtet (TetGen 1.5).
#define TETLIBRARY
#include <tetgen.h>

#include <cstdlib>
#include <cstring>

extern "C" {

// Tetrahedralizes `n` points (xyz interleaved). On success returns 0 and sets `*tets` to a malloc'ed
// array of 4 * `*ntets` point indices (0-based, into the input), to be released with
// `s2s_tetgen_free`. Points TetGen finds duplicated are simply not used by any tetrahedron.
// Returns TetGen's error code (> 0) or -1 on an unexpected exception.
int s2s_tetgen_delaunay(const double *xyz, int n, int **tets, int *ntets, int quiet) {
  *tets = nullptr;
  *ntets = 0;
  try {
    tetgenio in, out;
    in.firstnumber = 0;
    in.numberofpoints = n;
    in.pointlist = new REAL[3 * (size_t)n];
    std::memcpy(in.pointlist, xyz, sizeof(double) * 3 * (size_t)n);
    tetgenbehavior b;
    // Q: quiet; no 'p', 'q' or 'Y' switch: plain Delaunay of the points, no Steiner points.
    char sw[8];
    std::strcpy(sw, quiet ? "Q" : "V");
    if (!b.parse_commandline(sw)) return 10;
    tetrahedralize(&b, &in, &out);
    if (out.numberofpoints != n) return 11;  // TetGen renumbered points: our mapping would be wrong
    int m = out.numberoftetrahedra;
    int *r = (int *)std::malloc(sizeof(int) * 4 * (size_t)(m > 0 ? m : 1));
    if (!r) return 1;
    for (int i = 0; i < m; i++)
      for (int k = 0; k < 4; k++) r[4 * i + k] = out.tetrahedronlist[out.numberofcorners * i + k] - out.firstnumber;
    *tets = r;
    *ntets = m;
    return 0;
  } catch (int code) {
    return code > 0 ? code : -1;
  } catch (...) {
    return -1;
  }
}

void s2s_tetgen_free(int *p) { std::free(p); }
}
