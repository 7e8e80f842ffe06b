# Shared by the bench scripts (sourced after `HERE`, the bench folder, is set): the scenes folder,
# a scratch folder removed on exit, the median of numbers on stdin (one per line), and the checks of
# their arguments: a benchmark that cannot run says why and exits 2 (or 1 when a run fails), never
# prints a table of zeros (the bench audit of 2026-11-28: a missing build, RUNS=0 or an unknown
# scene gave exit 127 or 0 with "-nan" and no message).
SCENES=$(cd "$HERE/../scenes" && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.3f", m }'; }
# The script's "# Usage:" line and a reason on stderr, exit 2.
usage() { sed -n 's/^# Usage: /usage: /p' "$0" >&2; echo "$*" >&2; exit 2; }
# The dicsynth binary of build folder $1 (absolute), or the usage.
binary_of() {
  [ -n "${1:-}" ] || usage "missing: a build folder"
  [ -x "$1/dicsynth" ] || usage "$1: no dicsynth binary in this build folder"
  echo "$(cd "$1" && pwd)/dicsynth"
}
# $2 when it is a whole number >= ${3:-1} (RUNS, POINTS, SPP), else the usage naming $1.
count() {
  case "$2" in '' | *[!0-9]*) usage "$1 '$2': expected a whole number >= ${3:-1}" ;; esac
  [ "$2" -ge "${3:-1}" ] || usage "$1 $2: expected a whole number >= ${3:-1}"
  echo "$2"
}
# Runs a command once, untimed (a warm-up): when it fails, what it said and the command, exit 1.
check() { "$@" >"$OUT/check.log" 2>&1 || { cat "$OUT/check.log" >&2; echo "failed: $*" >&2; exit 1; }; }
