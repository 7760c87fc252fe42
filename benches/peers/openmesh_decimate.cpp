// OpenMesh peer for benches/src/bin/peers.rs: quadric-priority decimation under a Hausdorff
// tolerance.
//
//   openmesh_decimate IN.off OUT.off EPSILON
//
// `Decimater::DecimaterT` on a double-precision triangle mesh with `ModQuadricT` (priority
// only: no quadric error limit) and `ModHausdorffT` (binary, tolerance EPSILON), decimated as
// far as the modules allow, garbage collected, written with 17 digits. Prints
// `faces=N seconds=S` on stdout; S covers the decimation only (no I/O).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <chrono>
#include <cstdlib>
#include <iostream>

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
using ModQuadric = OpenMesh::Decimater::ModQuadricT<Mesh>::Handle;
using ModHausdorff = OpenMesh::Decimater::ModHausdorffT<Mesh>::Handle;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: openmesh_decimate IN.off OUT.off EPSILON\n";
    return 2;
  }
  const double eps = std::strtod(argv[3], nullptr);
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, argv[1]) || mesh.n_faces() == 0) {
    std::cerr << "error: cannot read " << argv[1] << "\n";
    return 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  Decimater dec(mesh);
  ModQuadric quadric;
  ModHausdorff hausdorff;
  dec.add(quadric);
  dec.add(hausdorff);
  dec.module(quadric).unset_max_err();  // priority only
  dec.module(hausdorff).set_tolerance(eps);
  dec.module(hausdorff).set_binary(true);
  if (!dec.initialize()) {
    std::cerr << "error: decimater initialisation failed\n";
    return 1;
  }
  dec.decimate();  // 0 = as many collapses as the modules allow
  mesh.garbage_collection();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!OpenMesh::IO::write_mesh(mesh, argv[2], OpenMesh::IO::Options::Default, 17)) {
    std::cerr << "error: cannot write " << argv[2] << "\n";
    return 1;
  }
  std::cout << "faces=" << mesh.n_faces() << " seconds=" << secs << "\n";
  return 0;
}
