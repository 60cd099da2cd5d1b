#!/usr/bin/env bash
# Writes a SCORM package of the lab for an LMS (Moodle, Canvas, Blackboard, Brightspace):
#
#   bash web/package.sh scorm12            # SCORM 1.2, every lesson, passing at 80
#   bash web/package.sh scorm2004 --lessons slab-test,bvh-intersect --mastery 70
#   bash web/package.sh scorm12 --lesson-file my-exam.toml --title "Week 3: BVHs"
#
# Options: --lessons NAMES (comma-separated, the lab's lesson names), --lesson-file FILE
# (a teacher's lesson; may be given more than once), --mastery N (the score that passes,
# 0-100), --title TEXT (what the LMS shows), --sandbox (the lab in a sandboxed frame),
# --out DIR (target/packages/ by default). README, "For teachers", says what the package
# does and how its score is counted.
#
# Builds the page first when dist/ lacks it (web/build.sh); needs Node.js and zip.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v zip >/dev/null; then
  echo "web/package.sh: needs zip (Debian: apt-get install zip)" >&2
  exit 1
fi
if [ ! -f dist/bvh-lab-offline.html ]; then
  bash web/build.sh
fi
node web/package.mjs "$@"
