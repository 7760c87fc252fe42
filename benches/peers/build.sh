#!/usr/bin/env bash
# Builds the C++ peers of benches/src/bin/peers.rs into benches/peers/build/:
#   cgal_envelope_collapse  (CGAL 5.5 edge_collapse + Polyhedral_envelope_filter)
#   openmesh_decimate       (OpenMesh 9 DecimaterT + ModQuadricT + ModHausdorffT)
# Idempotent: a program is rebuilt only when its source or this script is newer. Works from any
# cwd. FORCE=1 rebuilds anyway, CXX chooses the compiler. Prints the build directory on stdout.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out_dir="$here/build"
CXX="${CXX:-g++}"

apt_line="apt-get install -y g++ libcgal-dev libgmp-dev libmpfr-dev libboost-dev libopenmesh-dev"
missing=()
command -v "$CXX" >/dev/null 2>&1 || missing+=("compiler $CXX")
[ -f /usr/include/CGAL/version.h ] || missing+=("CGAL headers (libcgal-dev)")
[ -f /usr/include/CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Polyhedral_envelope_filter.h ] \
  || missing+=("CGAL >= 5.5 Polyhedral_envelope_filter (libcgal-dev)")
[ -f /usr/include/gmp.h ] || [ -f /usr/include/x86_64-linux-gnu/gmp.h ] || missing+=("GMP (libgmp-dev)")
[ -f /usr/include/mpfr.h ] || missing+=("MPFR (libmpfr-dev)")
[ -d /usr/include/boost ] || missing+=("Boost headers (libboost-dev)")
[ -f /usr/include/OpenMesh/Tools/Decimater/ModHausdorffT.hh ] || missing+=("OpenMesh headers (libopenmesh-dev)")
if ! compgen -G "/usr/lib/*/libOpenMeshCore.so" >/dev/null && [ ! -f /usr/lib/libOpenMeshCore.so ]; then
  missing+=("OpenMesh library (libopenmesh-dev)")
fi
if [ "${#missing[@]}" -gt 0 ]; then
  echo "error: cannot build the benchmark peers; missing:" >&2
  for m in "${missing[@]}"; do echo "  - $m" >&2; done
  echo "install them with (as root):" >&2
  echo "  apt-get update && $apt_line" >&2
  exit 1
fi

mkdir -p "$out_dir"
if command -v flock >/dev/null 2>&1; then
  exec 9>"$out_dir/.build.lock"
  flock 9
fi

# build NAME LIBS...
build() {
  local name="$1"; shift
  local src="$here/$name.cpp" bin="$out_dir/$name"
  if [ -z "${FORCE:-}" ] && [ -x "$bin" ] && [ "$bin" -nt "$src" ] && [ "$bin" -nt "${BASH_SOURCE[0]}" ]; then
    echo "$bin is up to date" >&2
    return
  fi
  local tmp="$bin.tmp.$$" start
  start=$(date +%s)
  echo "building $bin ..." >&2
  # -frounding-math: required by CGAL's interval arithmetic filters with GCC.
  "$CXX" -O2 -std=c++17 -frounding-math -DCGAL_DISABLE_GMPXX=1 -DNDEBUG -o "$tmp" "$src" "$@"
  mv -f "$tmp" "$bin"
  echo "built $name in $(( $(date +%s) - start )) s" >&2
}

build cgal_envelope_collapse -lmpfr -lgmp
build openmesh_decimate -lOpenMeshTools -lOpenMeshCore
echo "$out_dir"
