#!/usr/bin/env bash
# Installs the Debian 12 packages curvestep needs, and only the missing ones.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  catch2
  gcc-arm-none-eabi libstdc++-arm-none-eabi-newlib libnewlib-arm-none-eabi binutils-arm-none-eabi
  libserialport-dev libgpiod-dev
  libcli11-dev nlohmann-json3-dev
  libtinyxml2-dev
  hershey-fonts-data  # the source of the SVG text font (scripts/generate_hershey_font.py) and its glyph test
  qemu-system-arm socat valgrind python3 python3-scipy
  clang libclang-rt-14-dev
  chromium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "curvestep: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
