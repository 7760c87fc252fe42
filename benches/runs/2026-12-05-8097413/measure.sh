#!/bin/bash
# usage: measure.sh BIN OUTFILE "methods" "placements" "meshes" "eps" [extra]
BIN=$1; OUT=$2; METHODS=$3; PLACEMENTS=$4; MESHES=$5; EPS=$6; EXTRA=$7
D=/work/main/.corpus/data/meshes
T=$(mktemp -d)
for m in $MESHES; do for e in $EPS; do for p in $PLACEMENTS; do for meth in $METHODS; do
  popt=""; [ "$p" != default ] && popt="--placement $p"
  $BIN simplify $D/$m.off $T/o.off --epsilon $e --method $meth $popt --report $T/r.json --quiet $EXTRA >/dev/null 2>$T/err
  rc=$?
  python3 - "$m" "$e" "$p" "$meth" "$rc" "$T/r.json" >> $OUT <<'PY'
import json,sys
m,e,p,meth,rc,path=sys.argv[1:]
try:
  r=json.load(open(path))
  v=r.get('verify') or {}
  print(m,e,p,meth,r['input_faces'],r['output_faces'],"%.2f"%r['simplify_seconds'],"viol=%s"%(len(v.get('violations',[])) if v else 'skip'),rc,sep='\t')
except Exception as ex:
  print(m,e,p,meth,'-','-','-','err',rc,sep='\t')
PY
  rm -f $T/r.json
done; done; done; done
