#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages the project needs, only those missing.
# Idempotent and quiet; sourced by test.sh, run.sh and the CI stages.
# What building the libraries and tools needs (./run.sh installs only these).
APCI_RUN_DEB_PACKAGES=(
  cmake g++ make pkg-config
  libeigen3-dev libcli11-dev libfmt-dev nlohmann-json3-dev zlib1g-dev
  libusb-1.0-0-dev libedit-dev
  ccache
)
# Everything ./test.sh needs: the above, the test and benchmark frameworks,
# Boost (Boost.Geometry, headers only, for the gouge tests' stock-removal oracle),
# umockdev for the USB tests, pybind11, NumPy, pytest and matplotlib for the
# Python package `apci` and its tests, zsh and bash-completion for the tests
# of the shell completion, and pandoc, which writes the man pages from docs/.
APCI_DEB_PACKAGES=(
  "${APCI_RUN_DEB_PACKAGES[@]}"
  libgtest-dev libgmock-dev libbenchmark-dev libboost-dev
  umockdev libumockdev-dev
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib
  zsh bash-completion pandoc
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

apci_install_run_deps() { apci_install_packages "${APCI_RUN_DEB_PACKAGES[@]}"; }
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

# Warnings are errors only where we choose (docs/hardening.md, "Warnings and
# the Release build"): APCI_WERROR=ON in the environment (.ci/run sets it)
# makes ./test.sh's and ./run.sh's build fail on any compiler warning (it is
# also the option's default for any other configure); the release, fuzz and
# sanitizer stages always build with -DAPCI_WERROR=ON.
apci_werror() {
  case "${APCI_WERROR:-OFF}" in
    ON|on|1|yes|true) echo ON ;;
    OFF|off|0|no|false|"") echo OFF ;;
    *) echo "APCI_WERROR: ON or OFF, not '$APCI_WERROR'" >&2; return 2 ;;
  esac
}

# apci_configure BUILD_DIR [cmake options]: configures BUILD_DIR as ./test.sh
# does (Release: -O3, what a user's Release build compiles, so that CI's
# warnings-as-errors and the suite cover the optimiser's view in one build;
# ccache), quietly.
apci_configure() {
  local build_dir="$1" werror
  shift
  werror=$(apci_werror) || return
  # shellcheck disable=SC2046
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release $(apci_launcher_args) \
    -DAPCI_WERROR="$werror" "$@" >/dev/null
}

# apci_build [BUILD_DIR]: configures with the tests and benchmarks and builds everything.
# The test programs' own sources at -O1 (APCI_TEST_COMPILE_OPTIONS, cmake/test_programs.cmake):
# what they test keeps -O3, and so do the sources named OPTIMIZED; -O1 compiles a test file
# in about three quarters of the time (docs/hardening.md, "Warnings and the Release build").
apci_build() {
  local build_dir="${1:-build}"
  apci_configure "$build_dir" -DAPCI_BUILD_TESTS=ON -DAPCI_BUILD_BENCH=ON \
    -DAPCI_TEST_COMPILE_OPTIONS=-O1
  cmake --build "$build_dir" -j"$(nproc)"
}
