#!/usr/bin/env bash
# ctest `browser.<kind>`: writes the report.html of one short `aperture` run and opens it in
# headless Chromium (check_report.sh): no console output, no broken image, the outcome and the
# run's description on the page. The screenshot stays in SCREENSHOT_DIR/<kind>.png.
#   report_test.sh run|sim|bench APERTURE WORK_DIR SCREENSHOT_DIR
set -euo pipefail
kind=${1:?usage: report_test.sh run|sim|bench APERTURE WORK_DIR SCREENSHOT_DIR}
aperture=${2:?}
work=${3:?}/$kind
screens=${4:?}
check="$(dirname "$0")/check_report.sh"
rm -rf "$work"
mkdir -p "$work"
case "$kind" in
  run)
    "$aperture" render gap --frames 3 --out "$work/dataset" > /dev/null
    "$aperture" run --source "$work/dataset" --calib "$work/dataset/calib.yaml" \
      --frontends gap,image_quality --out "$work/out" > /dev/null
    expected=("Outcome: done" "aperture run" "gap poses" "Configuration" "wall time")
    ;;
  sim)
    # A second of hovering on ground truth among the robot and the tagged obstacles of `tags`
    # (drawn in the views); its own mission `deliver` flies for minutes.
    "$aperture" sim tags --set mission=hover --duration 1 --out "$work/out" > /dev/null
    expected=("Outcome: " "aperture sim" "Path seen from above" "Path seen from the side"
              "Configuration" "wall time")
    ;;
  bench)
    "$aperture" bench gap --trials 2 --seed 4 --autopilot ground_truth --duration 6 \
      --out "$work/out" > /dev/null
    expected=("Outcome: passed" "aperture bench gap" "success rate" "Configuration" "wall time")
    ;;
  *)
    echo "report_test: unknown kind '$kind' (run, sim or bench)" >&2
    exit 2
    ;;
esac
"$check" "$work/out/report.html" "$screens/$kind.png" "${expected[@]}"
