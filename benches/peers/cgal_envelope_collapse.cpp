// CGAL peer for benches/src/bin/peers.rs: edge collapse restricted to a polyhedral envelope.
//
//   cgal_envelope_collapse IN.off OUT.off EPSILON [--plain]
//
// Follows CGAL 5.5's example `Surface_mesh_simplification/edge_collapse_envelope.cpp`:
// Lindstrom-Turk cost and placement, `Polyhedral_envelope_filter` (absolute EPSILON) wrapped
// around `Bounded_normal_change_filter`, stop predicate "count 0" (collapse as long as the filter
// allows). `--plain` drops the normal-change filter (the envelope filter alone). Prints `faces=N seconds=S` on stdout; S covers the collapse only (no I/O).
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Polyhedral_envelope_filter.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace SMS = CGAL::Surface_mesh_simplification;
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Filter = SMS::Polyhedral_envelope_filter<Kernel, SMS::Bounded_normal_change_filter<>>;
using PlainFilter = SMS::Polyhedral_envelope_filter<Kernel>;

template <class F>
void collapse(Mesh& mesh, const F& filter) {
  SMS::Count_stop_predicate<Mesh> stop(0);
  SMS::edge_collapse(mesh, stop,
                     CGAL::parameters::get_cost(SMS::LindstromTurk_cost<Mesh>())
                         .get_placement(SMS::LindstromTurk_placement<Mesh>())
                         .filter(filter));
}

int main(int argc, char** argv) {
  const bool plain = argc == 5 && std::string(argv[4]) == "--plain";
  if (argc != 4 && !plain) {
    std::cerr << "usage: cgal_envelope_collapse IN.off OUT.off EPSILON [--plain]\n";
    return 2;
  }
  const double eps = std::strtod(argv[3], nullptr);
  Mesh mesh;
  std::ifstream in(argv[1]);
  if (!in || !(in >> mesh) || mesh.is_empty() || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "error: cannot read " << argv[1] << " as a triangle Surface_mesh\n";
    return 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (plain) {
    collapse(mesh, PlainFilter(eps));
  } else {
    collapse(mesh, Filter(eps));
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  mesh.collect_garbage();
  std::ofstream out(argv[2]);
  out.precision(17);
  if (!(out << mesh)) {
    std::cerr << "error: cannot write " << argv[2] << "\n";
    return 1;
  }
  std::cout << "faces=" << mesh.number_of_faces() << " seconds=" << secs << "\n";
  return 0;
}
