#!/usr/bin/env bash
# Checks that the core's docs, as docs.rs builds them (tests/check.sh's docs step), show the
# items of its optional features and mark each with the feature it needs: the module `saved`
# (feature serde) and `build_parallel` of the AABB tree and of Bvh4 (feature parallel).
# Usage: tests/docs_features.sh target/doc/bvhlab
set -euo pipefail
docs=${1:?the core docs folder, e.g. target/doc/bvhlab}
failed=0

# The part of an HTML page from the element with id $2 to the next method's (all of it
# without $2).
section() {
    if [ -z "$2" ]; then
        cat "$1"
    else
        perl -0777 -ne 'print $1 if /id="\Q$ENV{ANCHOR}\E"(.*?)(id="method\.|\z)/s' "$1"
    fi
}

# A page, a feature, what the page shows, and for a method its anchor: the feature's badge
# must be on the page (for a method, in its own section).
expect() {
    local file=$docs/$1 badge="Available on <strong>crate feature <code>$2</code>"
    if [ ! -f "$file" ]; then
        echo "docs: $3 is missing ($file does not exist)"
        failed=1
    elif ! ANCHOR="${4:-}" section "$file" "${4:-}" | grep -q "$badge"; then
        echo "docs: $3 is not marked as needing the feature $2 ($file)"
        failed=1
    fi
}

expect saved/index.html serde "the module saved"
expect saved/fn.save.html serde "saved::save"
expect structure/bvh/struct.Bvh4.html parallel "Bvh4::build_parallel" method.build_parallel
expect structure/bvh/layout/struct.Bvh.html parallel "Bvh::build_parallel" method.build_parallel
if [ "$failed" = 0 ]; then
    echo "docs: every feature's items are there and marked"
fi
exit "$failed"
