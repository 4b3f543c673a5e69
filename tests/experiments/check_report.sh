#!/usr/bin/env bash
# Browser check of the experiment report (ctest, label render):
#   check_report.sh DELTAPATH EXPERIMENT.yaml WORKDIR
# Runs the experiment, then opens a copy of report.html with an injected checker script
# in headless Chromium (no network, fresh profile) and requires every <img> to have
# loaded (naturalWidth > 0) and no error event / console message. Two negative controls
# must FAIL with the same checker: the report with one image deleted, and the report
# with a console.error. Exit 77 (ctest skip) when chromium is not installed.
set -euo pipefail
deltapath=$1 experiment=$2 work=$3

chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "chromium not installed (Debian package chromium); skipping the browser check"
  exit 77
fi

rm -rf "$work"
mkdir -p "$work"
"$deltapath" experiment "$experiment" --out "$work/out" --quiet

checker='<script>
window.__dpErrors = [];
window.addEventListener("error", function (e) {
  var t = e.target, what = e.message || (t && (t.src || t.href)) || "unknown";
  window.__dpErrors.push("error event: " + what);
}, true);
(function () {
  var wrap = function (kind) {
    var orig = console[kind];
    console[kind] = function () {
      window.__dpErrors.push("console." + kind + ": " + Array.prototype.join.call(arguments, " "));
      orig.apply(console, arguments);
    };
  };
  wrap("error"); wrap("warn");
})();
window.addEventListener("load", function () {
  var imgs = document.images, bad = [];
  for (var i = 0; i < imgs.length; i++)
    if (!(imgs[i].complete && imgs[i].naturalWidth > 0)) bad.push(imgs[i].getAttribute("src"));
  var ok = imgs.length > 0 && bad.length === 0 && window.__dpErrors.length === 0;
  var d = document.createElement("pre");
  d.textContent = "DP" + "-CHECK " + (ok ? "OK" : "FAIL") + " images=" + imgs.length + " broken=[" + bad.join(" ") +
                  "] errors=[" + window.__dpErrors.join(" | ") + "]";
  document.body.appendChild(d);
});
</script>'

# check DIR -> prints the checker line; returns 0 only if the page passed.
check() {
  local dir=$1 name=$2
  local page="$dir/dp-check.html"
  # The checker goes first in <head> so it sees every later error.
  awk -v s="$checker" '{ print } /<head>/ && !done { print s; done = 1 }' "$dir/report.html" > "$page"
  local profile="$work/profile-$name"
  rm -rf "$profile"
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --user-data-dir="$profile" \
    --enable-logging=stderr --v=0 --virtual-time-budget=10000 --dump-dom "file://$(realpath "$page")" \
    > "$work/$name.dom" 2> "$work/$name.log" || true
  local line
  line=$(grep -o 'DP-CHECK [^<]*' "$work/$name.dom" || echo "DP-CHECK MISSING (page did not finish; see $work/$name.log)")
  echo "$name: $line"
  if grep -q ':CONSOLE(' "$work/$name.log"; then
    echo "$name: console messages in the browser log:"
    grep ':CONSOLE(' "$work/$name.log" | head -5
    return 1
  fi
  [[ $line == "DP-CHECK OK"* ]]
}

status=0
check "$work/out" report || { echo "FAIL: the report did not load cleanly"; status=1; }

# Negative control 1: one image missing must be detected.
cp -r "$work/out" "$work/missing"
victim=$(ls "$work/missing/report/"*.png | head -1)
rm "$victim"
if check "$work/missing" missing-image; then echo "FAIL: a report with $(basename "$victim") deleted passed"; status=1; fi

# Negative control 2: a console error must be detected.
cp -r "$work/out" "$work/console"
sed -i 's#</body>#<script>console.error("deliberate error");</script></body>#' "$work/console/report.html"
if check "$work/console" console-error; then echo "FAIL: a report with a console error passed"; status=1; fi

[ $status -eq 0 ] && echo "report check passed (and both negative controls failed as they should)"
exit $status
