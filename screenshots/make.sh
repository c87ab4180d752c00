#!/usr/bin/env bash
# Takes the README's screenshots of the real app under Xvfb (Debian; installs what it
# needs). Usage: bash screenshots/make.sh   (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
need="libgl1 libglx-mesa0 libgl1-mesa-dri libegl1 libegl-mesa0 libxkbcommon-x11-0 libx11-xcb1 libxcursor1 libxi6 xvfb xdotool imagemagick xauth"
if ! command -v xvfb-run >/dev/null || ! command -v xdotool >/dev/null || ! command -v import >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $need
fi
cargo build --release
out=screenshots
# Fresh settings for each script: the shots show the defaults, and one script's
# choices do not carry into the next.
for script in session workbench; do
  home=$(mktemp -d)
  HOME="$home" XDG_DATA_HOME="$home/data" XDG_CONFIG_HOME="$home/config" \
    xvfb-run -a -s "-screen 0 1280x820x24" bash "screenshots/$script.sh" "$out"
  rm -rf "$home"
done
