#!/usr/bin/env bash
# The main demo, run by `make demo`: aperture's front ends on a real recorded image sequence.
# Until the simulator lands this runs the image-quality front end on ViSP's "mbt/cube" sequence
# (218 real camera frames shipped by Debian's visp-images-data) and writes summary.json, a CSV,
# an overlay video and report.html into the output folder.
set -euo pipefail
aperture=${1:?usage: demo.sh APERTURE_BINARY OUT_DIR}
out=${2:?usage: demo.sh APERTURE_BINARY OUT_DIR}

sequence=$(dpkg -L visp-images-data 2>/dev/null | grep -m1 '/ViSP-images/mbt/cube/image0000.pgm$' || true)
if [[ -z "$sequence" ]]; then
  echo "demo: the ViSP image sequence is missing; run scripts/install-deps.sh (visp-images-data)." >&2
  exit 1
fi
"$aperture" run --source "$(dirname "$sequence")" --fps 30 --frontends image_quality \
  --video --out "$out"
echo "demo: open $out/report.html"
