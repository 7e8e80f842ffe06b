# Shared by the bench scripts (sourced after `HERE`, the bench folder, is set): the scenes folder,
# a scratch folder removed on exit, and the median of numbers on stdin, one per line.
SCENES=$(cd "$HERE/../scenes" && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%.3f", m }'; }
