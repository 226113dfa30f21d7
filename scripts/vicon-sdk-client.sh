#!/usr/bin/env bash
# Builds Vicon's own DataStream SDK client (C++, MIT, version 1.11) and the small program the Vicon tests run
# with it (scripts/vicon-sdk/vicon_sdk_client.cpp), and prints the program's path.
#
# The SDK's source comes from PyPI's pyvicon-datastream sdist (lib_src/), checked against its SHA-256. Its own
# CMake file downloads boost from the internet; scripts/vicon-sdk/CMakeLists.txt builds the same sources against
# Debian's boost (libboost-system-dev, libboost-thread-dev, libboost-filesystem-dev) and cmake, installed with apt
# when missing. A few minutes on 2 cores, once (scripts/test.sh builds it while cargo builds the tests): the result is cached under target/vicon-sdk/, keyed by a hash
# of the sdist and of this script, the CMake file and the program, so a change to any of them rebuilds.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

sdist_version="0.2.4"
sdist_sha256="ee65a26b53f96f65b65f795c9843116c49347e81c80f88fca14cfe3d3a2622ed"
sdist="pyvicon_datastream-$sdist_version.tar.gz"
packages=(cmake g++ libboost-system-dev libboost-thread-dev libboost-filesystem-dev)

key=$(cat scripts/vicon-sdk-client.sh scripts/vicon-sdk/CMakeLists.txt scripts/vicon-sdk/vicon_sdk_client.cpp <(echo "$sdist_sha256") |
  sha256sum | cut -c1-16)
cache="$root/target/vicon-sdk/$key"
exe="$cache/vicon-sdk-client"
if [ -x "$exe" ]; then
  echo "$exe"
  exit 0
fi

missing=()
for pkg in "${packages[@]}"; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "vicon-sdk-client.sh: installing ${missing[*]} with apt" >&2
  sudo_=""
  if [ "$(id -u)" -ne 0 ]; then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "vicon-sdk-client.sh: ${missing[*]} missing and no sudo to install them: as root, run" >&2
      echo "  apt-get install --no-install-recommends ${missing[*]}" >&2
      exit 1
    fi
    sudo_="sudo"
  fi
  $sudo_ apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

downloads="$root/target/vicon-sdk/downloads"
mkdir -p "$downloads"
if [ ! -f "$downloads/$sdist" ] || ! echo "$sdist_sha256  $downloads/$sdist" | sha256sum -c --quiet - 2>/dev/null; then
  echo "vicon-sdk-client.sh: downloading the DataStream SDK source (pyvicon-datastream $sdist_version sdist)" >&2
  rm -f "$downloads/$sdist"
  # Only this package is built from source; its build requirements (needed to read its metadata) come as wheels.
  python3 -m pip download --quiet --disable-pip-version-check --no-deps \
    --no-binary pyvicon-datastream "pyvicon-datastream==$sdist_version" -d "$downloads" >&2
fi
echo "$sdist_sha256  $downloads/$sdist" | sha256sum -c --quiet -

work="$root/target/vicon-sdk/build-$key"
rm -rf "$work"
mkdir -p "$work"
tar -xzf "$downloads/$sdist" -C "$work"
sdk="$work/pyvicon_datastream-$sdist_version/lib_src/vicondatastream-1.11.0"
echo "vicon-sdk-client.sh: building Vicon's DataStream SDK client (a few minutes, once)" >&2
# Unoptimised: the tests read a few thousand small frames with it, and -O0 compiles boost's templates in about
# half the time -O2 takes.
cmake -S scripts/vicon-sdk -B "$work/build" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O0 -DVICON_SDK_DIR="$sdk" >&2
cmake --build "$work/build" -j "$(nproc)" >&2
mkdir -p "$cache"
cp "$work/build/vicon-sdk-client" "$exe.tmp"
mv "$exe.tmp" "$exe"
rm -rf "$work"
echo "$exe"
