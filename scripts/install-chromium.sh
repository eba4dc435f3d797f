#!/usr/bin/env bash
# Installs Debian's headless Chromium for tests/report.rs (the report is
# opened in it, checked for console errors and screenshotted). Needs root and
# Debian's package archive; where either is missing it says so and exits 1,
# and the browser test skips with a message.
set -euo pipefail
if command -v chromium >/dev/null 2>&1; then
  exit 0
fi
if [ "$(id -u)" != 0 ]; then
  echo "install-chromium: not root; install Debian's 'chromium' package by hand" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq >/dev/null
apt-get install -y -qq chromium >/dev/null
command -v chromium >/dev/null
