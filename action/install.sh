#!/usr/bin/env bash
# action.yml "Install HQView": a released .deb ($HQVIEW_DEB: a path or an
# https URL), or a build from the action's own checkout ($GITHUB_ACTION_PATH,
# into $HQVIEW_BUILD_DIR; ccache's directory is restored by actions/cache).
# Also jq and gh, which the other steps use (GitHub's Ubuntu runners have
# them; a debian:12 container has not). hqview goes on $GITHUB_PATH.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

apt_install() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    $sudo apt-get update -q
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

tools=()
command -v jq >/dev/null 2>&1 || tools+=(jq)
command -v gh >/dev/null 2>&1 || tools+=(gh)
deb="${HQVIEW_DEB:-}"
if [[ "$deb" == https://* ]]; then command -v curl >/dev/null 2>&1 || tools+=(curl ca-certificates); fi
if [ ${#tools[@]} -gt 0 ]; then apt_install "${tools[@]}"; fi

if [ -n "$deb" ]; then
  if [[ "$deb" == https://* ]]; then
    file="${RUNNER_TEMP:-/tmp}/hqview.deb"
    curl --fail --location --silent --show-error --output "$file" -- "$deb"
    deb="$file"
  elif [[ "$deb" == *://* ]]; then
    echo "::error::deb: only a path or an https:// URL ($deb)" >&2
    exit 2
  fi
  if [ ! -f "$deb" ]; then
    echo "::error::deb: no such file: $deb" >&2
    exit 2
  fi
  case "$deb" in /*) ;; *) deb="./$deb" ;; esac
  $sudo apt-get update -q
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "$deb"
  bin="$(dirname "$(command -v hqview)")"
else
  build="${HQVIEW_BUILD_DIR:-$root/build}"
  "$root/scripts/setup" --build
  export CCACHE_BASEDIR="$root"
  HQVIEW_BUILD_DIR="$build" "$root/scripts/build" -DHQVIEW_BUILD_TESTS=OFF -DHQVIEW_BUILD_BENCH=OFF
  bin="$build/apps/hqview"
fi
"$bin/hqview" --version
if [ -n "${GITHUB_PATH:-}" ]; then echo "$bin" >> "$GITHUB_PATH"; fi
