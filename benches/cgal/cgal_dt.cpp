// Times CGAL's Delaunay_triangulation_3 (Epick, range insertion) on an `x y z` point file, the
// comparison program of benches/kernel_vs_cgal.sh (not built by cargo).
// Build: g++ -O3 -DNDEBUG -o /tmp/cgal_dt cgal_dt.cpp -lgmp   (Debian: apt-get install libcgal-dev)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Delaunay_triangulation_3<K> DT;

int main(int argc, char** argv) {
  if (argc < 2) { std::cerr << "usage: cgal_dt POINTS.xyz\n"; return 2; }
  std::vector<K::Point_3> pts;
  FILE* f = std::fopen(argv[1], "r");
  if (!f) { std::cerr << "cannot read " << argv[1] << "\n"; return 1; }
  double x, y, z;
  while (std::fscanf(f, "%lf %lf %lf", &x, &y, &z) == 3) pts.emplace_back(x, y, z);
  std::fclose(f);
  auto t0 = std::chrono::steady_clock::now();
  DT dt(pts.begin(), pts.end());
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"points\":%zu,\"tets\":%zu,\"seconds\":%.6f,\"valid\":%s}\n", pts.size(),
              (size_t)dt.number_of_finite_cells(), s, argc > 2 && !dt.is_valid() ? "false" : "true");
  return 0;
}
