// TetGen oracle shim: Delaunay tetrahedralization of a point set through a C ABI.
// Built by build.rs only with the cargo feature `tetgen`; linked against Debian's libtet (TetGen 1.5).
#define TETLIBRARY
#include <tetgen.h>

#include <cstdlib>
#include <cstring>

extern "C" {

// Tetrahedralizes `n` points (xyz interleaved). On success returns 0 and sets `*tets` to a malloc'ed
// array of 4 * `*ntets` indices into TetGen's output points, and `*opts` to a malloc'ed array of the
// `*nout` output points (xyz), both released with `s2s_tetgen_free`. TetGen may drop duplicated points
// and renumber the rest, so the caller maps output points back to input points by coordinates.
// Returns TetGen's error code (> 0) or -1 on an unexpected exception.
int s2s_tetgen_delaunay(const double *xyz, int n, int **tets, int *ntets, double **opts, int *nout,
                        int quiet) {
  *tets = nullptr;
  *ntets = 0;
  *opts = nullptr;
  *nout = 0;
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
    int m = out.numberoftetrahedra;
    int np = out.numberofpoints;
    double *q = (double *)std::malloc(sizeof(double) * 3 * (size_t)(np > 0 ? np : 1));
    if (!q) return 1;
    if (np > 0) std::memcpy(q, out.pointlist, sizeof(double) * 3 * (size_t)np);
    int *r = (int *)std::malloc(sizeof(int) * 4 * (size_t)(m > 0 ? m : 1));
    if (!r) {
      std::free(q);
      return 1;
    }
    for (int i = 0; i < m; i++)
      for (int k = 0; k < 4; k++) r[4 * i + k] = out.tetrahedronlist[out.numberofcorners * i + k] - out.firstnumber;
    *tets = r;
    *ntets = m;
    *opts = q;
    *nout = np;
    return 0;
  } catch (int code) {
    return code > 0 ? code : -1;
  } catch (...) {
    return -1;
  }
}

void s2s_tetgen_free(void *p) { std::free(p); }
}
