#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Rewrites the name list of docs/object-map.md (between <!-- names:begin --> and
# <!-- names:end -->) from the object map's tables, objif/map/objects.h. The test
# ObjectNames.TheDocumentedNameListIsTheTables fails until the page matches the tables.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
cmake --build "$build" --target objif_tests >/dev/null
APCI_UPDATE_DOCS=1 "$build/bin/objif_tests" --gtest_filter='ObjectNames.TheDocumentedNameListIsTheTables' >/dev/null
echo "docs/object-map.md: name list updated"
