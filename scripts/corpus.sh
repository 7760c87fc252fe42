#!/usr/bin/env bash
# Makes the libcgal-demo mesh corpus available at <repo>/.corpus/data/meshes (gitignored)
# and prints that directory on stdout. Idempotent: does nothing when it is already unpacked.
# Source: /usr/share/doc/libcgal-dev/data.tar.gz, shipped by Debian's libcgal-demo package.
# The whole data/meshes/ folder is unpacked (138 .off, plus a few .ply/.stl);
# the Rust client (envelope_tests::oracle::corpus_meshes) lists the .off files.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="$repo/.corpus"
meshes="$dest/data/meshes"
archive=/usr/share/doc/libcgal-dev/data.tar.gz

if compgen -G "$meshes/*.off" >/dev/null; then
  echo "$meshes"
  exit 0
fi

if [ ! -f "$archive" ]; then
  # Only the data archive is needed: fetch the package file and take it out, rather than
  # installing libcgal-demo with its Qt dependencies.
  deb_dir="$(mktemp -d)"
  trap 'rm -rf "$deb_dir"' EXIT
  echo "corpus: $archive missing; fetching libcgal-demo ..." >&2
  ( cd "$deb_dir" && { apt-get download libcgal-demo >&2 2>&1 \
      || { [ "$(id -u)" = 0 ] && apt-get update -qq >&2 && apt-get download libcgal-demo >&2; }; } ) \
    || { echo "error: cannot fetch libcgal-demo; as root run: apt-get update && apt-get install -y libcgal-demo" >&2; exit 1; }
  dpkg-deb --fsys-tarfile "$deb_dir"/libcgal-demo_*.deb \
    | tar -x -C "$deb_dir" ./usr/share/doc/libcgal-dev/data.tar.gz
  archive="$deb_dir/usr/share/doc/libcgal-dev/data.tar.gz"
fi
[ -f "$archive" ] || { echo "error: no libcgal-demo data archive" >&2; exit 1; }

mkdir -p "$dest"
tmp="$(mktemp -d "$dest/.unpack.XXXXXX")"
trap 'rm -rf "$tmp" "${deb_dir:-}"' EXIT
tar -xzf "$archive" -C "$tmp" data/meshes
mkdir -p "$dest/data"
rm -rf "$meshes"
mv "$tmp/data/meshes" "$meshes"
count=$(find "$meshes" -maxdepth 1 -name '*.off' | wc -l)
echo "corpus: unpacked $count .off meshes" >&2
echo "$meshes"
