#!/usr/bin/env bash
# Speed and faces of `envelope simplify` against CGAL's envelope-filtered edge collapse, one
# mesh and epsilon at a time, without the oracle measurements of `peers` (minutes per row on
# large meshes): a quick table for an idle machine.
#
#   benches/ours_vs_cgal.sh MESH [EPS...]     e.g. benches/ours_vs_cgal.sh armadillo 1/64% 1%
#
# MESH is a name in .corpus/data/meshes (scripts/corpus.sh). EPS defaults to the seven
# epsilons of the issue. Ours: `seconds - verify.seconds` of the report (input check,
# envelopes and simplification; the built-in certificate runs and must hold, its time is
# shown apart). CGAL: the seconds `cgal_envelope_collapse` prints (its own timer, I/O
# excluded), at the same absolute epsilon (`epsilon_abs` of our report). Binaries:
# $ENVELOPE_BIN (else target/release/envelope) and benches/peers/build (benches/peers/build.sh).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mesh="${1:?usage: ours_vs_cgal.sh MESH [EPS...]}"
shift
epsilons=("$@")
[ ${#epsilons[@]} -gt 0 ] || epsilons=(1/64% 1/32% 1/16% 1/8% 1/4% 1/2% 1%)
input="$root/.corpus/data/meshes/$mesh.off"
ours="${ENVELOPE_BIN:-$root/target/release/envelope}"
cgal="$root/benches/peers/build/cgal_envelope_collapse"
for f in "$input" "$ours" "$cgal"; do
  [ -e "$f" ] || { echo "missing $f" >&2; exit 2; }
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

echo "| mesh | eps | ours faces | CGAL faces | faces ratio | ours s | (certificate s) | CGAL s | CGAL/ours time | envelopes |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for eps in "${epsilons[@]}"; do
  "$ours" simplify "$input" "$tmp/ours.off" --epsilon "$eps" --quiet --report "$tmp/r.json"
  read -r faces secs cert abs verdict method < <(python3 - "$tmp/r.json" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
v = r["verify"]
print(r["output_faces"], r["seconds"] - v["seconds"], v["seconds"], repr(r["epsilon_abs"]),
      v["verdict"], r["envelope"]["method"].replace(" ", ""))
EOF
)
  [ "$verdict" = holds ] || { echo "our certificate: $verdict" >&2; exit 1; }
  line="$("$cgal" "$input" "$tmp/cgal.off" "$abs" | tail -1)"
  cfaces="$(sed -n 's/.*faces=\([0-9]*\).*/\1/p' <<<"$line")"
  csecs="$(sed -n 's/.*seconds=\([0-9.e+-]*\).*/\1/p' <<<"$line")"
  python3 - "$mesh" "$eps" "$faces" "$cfaces" "$secs" "$cert" "$csecs" "$method" <<'EOF'
import sys
m, e, f, cf, s, c, cs, meth = sys.argv[1:]
f, cf, s, c, cs = int(f), int(cf), float(s), float(c), float(cs)
print(f"| {m} | {e} | {f:,} | {cf:,} | {f / cf:.2f} | {s:.2f} | ({c:.2f}) | {cs:.2f} | {cs / s:.1f} | {meth} |")
EOF
done
