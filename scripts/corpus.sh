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
  if [ "$(id -u)" = 0 ]; then
    echo "corpus: $archive missing; installing libcgal-demo ..." >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y libcgal-demo >&2 || { apt-get update >&2 && apt-get install -y libcgal-demo >&2; }
  else
    echo "error: $archive is missing; install it with (as root):" >&2
    echo "  apt-get update && apt-get install -y libcgal-demo" >&2
    exit 1
  fi
fi
[ -f "$archive" ] || { echo "error: $archive still missing after installing libcgal-demo" >&2; exit 1; }

mkdir -p "$dest"
tmp="$(mktemp -d "$dest/.unpack.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$archive" -C "$tmp" data/meshes
mkdir -p "$dest/data"
rm -rf "$meshes"
mv "$tmp/data/meshes" "$meshes"
count=$(find "$meshes" -maxdepth 1 -name '*.off' | wc -l)
echo "corpus: unpacked $count .off meshes" >&2
echo "$meshes"
