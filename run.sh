#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job on the embedded emulator.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/deps.sh
apci_install_deps
apci_build build >/dev/null
./build/bin/pcap_tc_init
./build/bin/apcictl status
