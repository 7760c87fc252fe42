# Shared by tests/oracle/build.sh and benches/peers/build.sh (sourced, not run): the checks for
# Debian's CGAL/OpenMesh packages, a build lock, and one compile rule with the flags CGAL needs.
# Callers set `CXX` (default g++) and `FORCE=1` to rebuild regardless of timestamps.

CXX="${CXX:-g++}"
cxx_build_lib="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cxx-build.sh"

# require_cxx_deps WHAT [PATH DESCRIPTION]...: exits 1 naming what is missing and the apt-get
# line, for the common packages plus the extra files given as (path, description) pairs.
require_cxx_deps() {
  local what="$1"; shift
  local apt_line="apt-get install -y g++ libcgal-dev libgmp-dev libmpfr-dev libboost-dev libopenmesh-dev"
  local missing=()
  command -v "$CXX" >/dev/null 2>&1 || missing+=("compiler $CXX")
  [ -f /usr/include/CGAL/version.h ] || missing+=("CGAL headers (libcgal-dev)")
  [ -f /usr/include/gmp.h ] || [ -f /usr/include/x86_64-linux-gnu/gmp.h ] || missing+=("GMP (libgmp-dev)")
  [ -f /usr/include/mpfr.h ] || missing+=("MPFR (libmpfr-dev)")
  [ -d /usr/include/boost ] || missing+=("Boost headers (libboost-dev)")
  if ! compgen -G "/usr/lib/*/libOpenMeshCore.so" >/dev/null && [ ! -f /usr/lib/libOpenMeshCore.so ]; then
    missing+=("OpenMesh library (libopenmesh-dev)")
  fi
  while [ "$#" -ge 2 ]; do
    [ -e "$1" ] || missing+=("$2")
    shift 2
  done
  if [ "${#missing[@]}" -gt 0 ]; then
    echo "error: cannot build $what; missing:" >&2
    for m in "${missing[@]}"; do echo "  - $m" >&2; done
    echo "install them with (as root):" >&2
    echo "  apt-get update && $apt_line" >&2
    exit 1
  fi
}

# lock_build_dir DIR: creates DIR and serialises concurrent callers (parallel test binaries);
# the second caller then finds the binaries up to date.
lock_build_dir() {
  mkdir -p "$1"
  if command -v flock >/dev/null 2>&1; then
    exec 9>"$1/.build.lock"
    flock 9
  fi
}

# cxx_build SRC BIN CALLER [COMPILER ARGS...]: compiles SRC into BIN unless BIN is newer than
# SRC, the calling script CALLER and this file. Writes a temporary file and renames it.
cxx_build() {
  local src="$1" bin="$2" caller="$3"; shift 3
  if [ -z "${FORCE:-}" ] && [ -x "$bin" ] && [ "$bin" -nt "$src" ] && [ "$bin" -nt "$caller" ] \
    && [ "$bin" -nt "$cxx_build_lib" ]; then
    echo "$bin is up to date" >&2
    return 0
  fi
  local tmp="$bin.tmp.$$" start
  start=$(date +%s)
  echo "building $bin ..." >&2
  # -frounding-math: required by CGAL's interval arithmetic filters with GCC.
  if ! "$CXX" -O2 -std=c++17 -frounding-math -DCGAL_DISABLE_GMPXX=1 -o "$tmp" "$src" "$@"; then
    rm -f "$tmp"
    return 1
  fi
  mv -f "$tmp" "$bin"
  echo "built $(basename "$bin") in $(( $(date +%s) - start )) s" >&2
}
