#!/usr/bin/env bash
# Builds the CGAL/OpenMesh cross-check oracle into tests/oracle/build/envelope-oracle and prints
# its path. Idempotent: does nothing when the binary is newer than its sources and build scripts.
# Works from any cwd. Set FORCE=1 to rebuild anyway, CXX to choose the compiler.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../../scripts/cxx-build.sh"

require_cxx_deps "the envelope oracle" \
  /usr/include/OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh "OpenMesh headers (libopenmesh-dev)"
lock_build_dir "$here/build"
cxx_build "$here/envelope_oracle.cpp" "$here/build/envelope-oracle" "${BASH_SOURCE[0]}" \
  -lOpenMeshCore -lmpfr -lgmp
echo "$here/build/envelope-oracle"
