#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages the project needs, only those missing.
# Idempotent and quiet; sourced by test.sh, run.sh and the CI stages.
APCI_DEB_PACKAGES=(
  cmake g++ make pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  libeigen3-dev libcli11-dev libfmt-dev nlohmann-json3-dev zlib1g-dev
  libusb-1.0-0-dev umockdev libumockdev-dev
  ccache
)
# Only the CI stages after ./test.sh need these (scripts/ci/): clang and its
# libFuzzer/sanitizer runtimes for the fuzzers, clang-tidy and cppcheck for
# static analysis, dpkg-dev (dpkg-shlibdeps) and file for the Debian package.
APCI_CI_DEB_PACKAGES=(
  clang-14 libclang-rt-14-dev clang-tidy-14 cppcheck
  dpkg-dev file
)

apci_install_packages() {
  local missing=()
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "installing missing Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
      echo "error: need root (or sudo) to install: ${missing[*]}" >&2; return 1
    fi
  fi
  $sudo apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

apci_install_deps() { apci_install_packages "${APCI_DEB_PACKAGES[@]}"; }
apci_install_ci_deps() { apci_install_packages "${APCI_DEB_PACKAGES[@]}" "${APCI_CI_DEB_PACKAGES[@]}"; }

# ccache (installed with the rest) makes a rebuild of an unchanged tree cheap,
# also across build directories of one checkout: the package stage's build-pkg
# compiles the same sources with the same flags as ./test.sh's build, so in CI
# it costs links, not a second full build.
# Sourced from the checkout's top directory.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
apci_launcher_args() {
  if command -v ccache >/dev/null 2>&1; then
    echo "-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
  fi
}

apci_build() {
  local build_dir="${1:-build}"
  # shellcheck disable=SC2046
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo $(apci_launcher_args) >/dev/null
  cmake --build "$build_dir" -j"$(nproc)"
}
