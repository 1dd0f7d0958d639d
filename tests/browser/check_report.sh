#!/usr/bin/env bash
# Opens an aperture report.html in headless Chromium (Debian's `chromium`) the way a reader would
# and fails (exit 1, saying why) when the page logs anything to the console (script errors,
# resources it may not load) or shows a broken image; keeps a full-page screenshot.
#   check_report.sh REPORT_HTML SCREENSHOT_PNG [EXPECTED_TEXT...]
# Each EXPECTED_TEXT must appear in the page's text (e.g. the outcome line).
set -euo pipefail
report=$(realpath "${1:?usage: check_report.sh REPORT_HTML SCREENSHOT_PNG [EXPECTED_TEXT...]}")
screenshot=$(realpath -m "${2:?usage: check_report.sh REPORT_HTML SCREENSHOT_PNG [EXPECTED_TEXT...]}")
shift 2
chromium=$(command -v chromium || true)
[[ -n "$chromium" ]] || { echo "check_report: chromium is not installed (scripts/install-deps.sh installs it)" >&2; exit 1; }
[[ -f "$report" ]] || { echo "check_report: no report at $report" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
       --disable-background-networking --disable-component-update --disable-sync
       --user-data-dir="$work/profile" --enable-logging=stderr --v=0 --virtual-time-budget=10000)

# The report inside a probe page that reads it after it loaded: its images and its text.
cp "$report" "$work/report.html"
cat > "$work/probe.html" <<'HTML'
<!doctype html><html><body><pre id="probe">probe did not run</pre>
<iframe id="report" src="report.html" style="width:1280px;height:1000px"></iframe>
<script id="probe-script">
document.getElementById('report').addEventListener('load', function () {
  var doc = this.contentDocument, out = document.getElementById('probe');
  document.getElementById('probe-script').remove();  // the dumped DOM holds the results only
  if (!doc) { out.textContent = 'PROBE_NO_ACCESS'; return; }
  var broken = Array.from(doc.images).filter(function (i) { return !i.complete || i.naturalWidth === 0; })
                   .map(function (i) { return i.alt || i.src.slice(0, 48); });
  out.textContent = 'PROBE_IMAGES ' + doc.images.length + '\nPROBE_BROKEN ' + JSON.stringify(broken) +
                    '\nPROBE_TEXT ' + doc.body.innerText.replace(/\s+/g, ' ');
});
</script></body></html>
HTML
timeout 120 "$chromium" "${flags[@]}" --allow-file-access-from-files --dump-dom \
  "file://$work/probe.html" > "$work/dom.html" 2> "$work/console.txt" || true
failed=0
if grep -q "CONSOLE" "$work/console.txt"; then
  echo "check_report: $report logs to the browser console:" >&2
  grep "CONSOLE" "$work/console.txt" >&2
  failed=1
fi
if ! grep -q "PROBE_IMAGES" "$work/dom.html"; then
  echo "check_report: chromium did not load $report:" >&2
  tail -n 20 "$work/console.txt" >&2
  exit 1
fi
broken=$(sed -n 's/^.*PROBE_BROKEN //p' "$work/dom.html")
if [[ "$broken" != "[]" ]]; then
  echo "check_report: broken images in $report: $broken" >&2
  failed=1
fi
for expected in "$@"; do
  if ! grep "PROBE_TEXT " "$work/dom.html" | grep -qF -- "$expected"; then
    echo "check_report: $report does not show '$expected'" >&2
    failed=1
  fi
done

mkdir -p "$(dirname "$screenshot")"
timeout 120 "$chromium" "${flags[@]}" --hide-scrollbars --window-size=1280,2400 \
  --screenshot="$screenshot" "file://$report" > /dev/null 2>&1 || true
[[ -s "$screenshot" ]] || { echo "check_report: no screenshot written to $screenshot" >&2; failed=1; }
((failed == 0)) || exit 1
images=$(sed -n 's/^.*PROBE_IMAGES //p' "$work/dom.html")
echo "check_report: $report: $images images, none broken, no console output; screenshot $screenshot"
