#!/usr/bin/env bash
# The main demo, run by `make demo`: the simulated vehicle in front of the narrow gap of seed 000,
# inclined by 30 degrees, seen by its onboard 180-degree fisheye camera. Until the gap mission
# lands the vehicle holds its hover with the ground-truth autopilot; the run writes summary.json,
# CSVs, the onboard/third-person video and report.html into the output folder.
set -euo pipefail
aperture=${1:?usage: demo.sh APERTURE_BINARY OUT_DIR}
out=${2:?usage: demo.sh APERTURE_BINARY OUT_DIR}

"$aperture" sim gap --duration 3 --set gap.roll_deg=30 --out "$out"
echo "demo: open $out/report.html (video: $out/sim.mp4)"
