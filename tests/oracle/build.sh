#!/usr/bin/env bash
# Builds the CGAL/OpenMesh cross-check oracle into tests/oracle/build/envelope-oracle.
# Idempotent: does nothing when the binary is newer than the source and this script.
# Works from any cwd. Set FORCE=1 to rebuild anyway, CXX to choose the compiler.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
src="$here/envelope_oracle.cpp"
out_dir="$here/build"
bin="$out_dir/envelope-oracle"
CXX="${CXX:-g++}"

apt_line="apt-get install -y g++ libcgal-dev libgmp-dev libmpfr-dev libboost-dev libopenmesh-dev"
missing=()
command -v "$CXX" >/dev/null 2>&1 || missing+=("compiler $CXX")
[ -f /usr/include/CGAL/version.h ] || missing+=("CGAL headers (libcgal-dev)")
[ -f /usr/include/gmp.h ] || [ -f /usr/include/x86_64-linux-gnu/gmp.h ] || missing+=("GMP (libgmp-dev)")
[ -f /usr/include/mpfr.h ] || missing+=("MPFR (libmpfr-dev)")
[ -d /usr/include/boost ] || missing+=("Boost headers (libboost-dev)")
[ -f /usr/include/OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh ] || missing+=("OpenMesh headers (libopenmesh-dev)")
if ! compgen -G "/usr/lib/*/libOpenMeshCore.so" >/dev/null && [ ! -f /usr/lib/libOpenMeshCore.so ]; then
  missing+=("OpenMesh library (libopenmesh-dev)")
fi
if [ "${#missing[@]}" -gt 0 ]; then
  echo "error: cannot build the envelope oracle; missing:" >&2
  for m in "${missing[@]}"; do echo "  - $m" >&2; done
  echo "install them with (as root):" >&2
  echo "  apt-get update && $apt_line" >&2
  exit 1
fi

mkdir -p "$out_dir"
# Serialise concurrent callers (parallel test binaries); the second one then sees "up to date".
if command -v flock >/dev/null 2>&1; then
  exec 9>"$out_dir/.build.lock"
  flock 9
fi

if [ -z "${FORCE:-}" ] && [ -x "$bin" ] && [ "$bin" -nt "$src" ] && [ "$bin" -nt "${BASH_SOURCE[0]}" ]; then
  echo "$bin is up to date" >&2
  echo "$bin"
  exit 0
fi

tmp="$bin.tmp.$$"
trap 'rm -f "$tmp"' EXIT
echo "building $bin (takes about a minute) ..." >&2
start=$(date +%s)
# -frounding-math: required by CGAL's interval arithmetic filters with GCC.
"$CXX" -O2 -std=c++17 -frounding-math -DCGAL_DISABLE_GMPXX=1 \
  -o "$tmp" "$src" -lOpenMeshCore -lmpfr -lgmp
mv -f "$tmp" "$bin"
echo "built in $(( $(date +%s) - start )) s" >&2
echo "$bin"
