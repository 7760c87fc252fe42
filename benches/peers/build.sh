#!/usr/bin/env bash
# Builds the C++ peers of benches/src/bin/peers.rs into benches/peers/build/:
#   cgal_envelope_collapse  (CGAL 5.5 edge_collapse + Polyhedral_envelope_filter)
#   openmesh_decimate       (OpenMesh 9 DecimaterT + ModQuadricT + ModHausdorffT)
# Idempotent: a program is rebuilt only when its source or a build script is newer. Works from
# any cwd. FORCE=1 rebuilds anyway, CXX chooses the compiler. Prints the build directory.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../../scripts/cxx-build.sh"

require_cxx_deps "the benchmark peers" \
  /usr/include/CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Polyhedral_envelope_filter.h \
  "CGAL >= 5.5 Polyhedral_envelope_filter (libcgal-dev)" \
  /usr/include/OpenMesh/Tools/Decimater/ModHausdorffT.hh "OpenMesh headers (libopenmesh-dev)"
lock_build_dir "$here/build"
for peer in "cgal_envelope_collapse -lmpfr -lgmp" "openmesh_decimate -lOpenMeshTools -lOpenMeshCore"; do
  set -- $peer
  name="$1"; shift
  cxx_build "$here/$name.cpp" "$here/build/$name" "${BASH_SOURCE[0]}" -DNDEBUG "$@"
done
echo "$here/build"
