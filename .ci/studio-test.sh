#!/usr/bin/env bash
# HairSheet Studio in a real browser: Debian's Chromium driven by Playwright (tests/studio). Installs what a fresh
# machine lacks (Chromium from Debian's packages, playwright-core from npm); prints "studio browser tests: Passed: N,
# Failed: N", or one SKIPPED line saying why when this machine cannot run a browser.
set -uo pipefail
cd "$(dirname "$0")/.."

if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "studio browser tests: SKIPPED: Node.js/npm not installed"; exit 0
fi
if [ ! -x /usr/bin/chromium ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && sudo="sudo -n"
  echo "installing Debian's chromium for the studio's browser tests"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1 ||
    { $sudo apt-get update -q >/dev/null 2>&1 && $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1; }
fi
if [ ! -x /usr/bin/chromium ]; then
  echo "studio browser tests: SKIPPED: Chromium could not be installed (apt-get install chromium failed)"; exit 0
fi

dotnet build -c Release src/HairSim.Cli -nologo -v q >/dev/null || { echo "studio browser tests: Passed: 0, Failed: 1 (the CLI did not build)"; exit 1; }
(cd tests/studio && npm ci --no-audit --no-fund >/dev/null 2>&1) || { echo "studio browser tests: Passed: 0, Failed: 1 (npm ci in tests/studio failed)"; exit 1; }

tap=$(mktemp)
(cd tests/studio && STUDIO_ARTIFACTS="${STUDIO_ARTIFACTS:-$PWD/artifacts}" node --test --test-reporter=tap studio.test.mjs) >"$tap" 2>&1
status=$?
# Results, and each failure's error text: the lines of a YAML "error: |-" block are indented deeper than the key.
awk '/^ *(not )?ok /{print; depth=-1; next}
     /^ +(error|message):/{print; match($0, /^ +/); depth=RLENGTH; next}
     depth>=0 { match($0, /^ +/); if (RLENGTH>depth) {print; next} else depth=-1 }' "$tap" | sed 's/^/  /'
pass=$(grep -Eo '^# pass [0-9]+' "$tap" | awk '{print $3}')
fail=$(grep -Eo '^# fail [0-9]+' "$tap" | awk '{print $3}')
skipped=$(grep -Eo '^# skipped [0-9]+' "$tap" | awk '{print $3}')
if [ -n "$(grep 'studio browser tests: SKIPPED' "$tap")" ]; then grep 'studio browser tests: SKIPPED' "$tap"; exit 0; fi
if [ -z "$pass" ]; then cat "$tap"; echo "studio browser tests: Passed: 0, Failed: 1 (no test report)"; exit 1; fi
# node:test counts the suite itself; report the tests only.
echo "studio browser tests: Passed: $((pass > 0 ? pass : 0)), Failed: ${fail:-0}${skipped:+ (skipped ${skipped})}"
[ "$status" -eq 0 ] && [ "${fail:-0}" -eq 0 ]
