#!/bin/sh
# CTest Web.HtmlViewer: the page `luxel bake ... --html` writes, opened from disk in headless
# Chromium with no network, shows the bake as `luxel render` does and logs no error
# (tools/three-check/html_check.mjs).
# Usage: html_viewer.sh LUXEL THREE_CHECK_DIR OUT_DIR
# Exit status 77 (CTest's SKIP_RETURN_CODE) when Node.js, Chromium or the npm packages are missing.
luxel=$1 check=$2 out=$3
if ! command -v node >/dev/null 2>&1; then
  echo "html-check: SKIP: node not found (scripts/install-deps.sh installs it)"
  exit 77
fi
exec node "$check/html_check.mjs" --luxel "$luxel" --out "$out"
