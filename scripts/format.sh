#!/usr/bin/env bash
# The C sources in the style of .clang-format (clang-format, Debian package
# clang-format; scripts/install-deps.sh installs it).
#   scripts/format.sh           reformat every file in place
#   scripts/format.sh --check   change nothing; list the files that differ from
#                               the style and exit 1 if there is any
# The files: every *.c and *.h under src/ include/ tests/ bench/ python/.
set -euo pipefail
cd "$(dirname "$0")/.."

check=0
case "${1:-}" in
  "") ;;
  --check) check=1 ;;
  *)
    echo "usage: scripts/format.sh [--check]" >&2
    exit 2
    ;;
esac
command -v clang-format >/dev/null || {
  echo "format.sh: clang-format not found (scripts/install-deps.sh installs it)" >&2
  exit 2
}

mapfile -d '' files < <(find src include tests bench python -type f \( -name '*.c' -o -name '*.h' \) \
  -print0 | sort -z)

if [ $check -eq 0 ]; then
  clang-format -i --style=file "${files[@]}"
  exit 0
fi

# One run over all files; --ferror-limit=1 gives one message per file that
# differs ("FILE:LINE:COL: error: code should be clang-formatted [...]").
status=0
out=$(clang-format --dry-run --Werror --ferror-limit=1 --style=file "${files[@]}" 2>&1) || status=$?
[ $status -eq 0 ] && exit 0
differ=$(printf '%s\n' "$out" | sed -nE 's/^(.*):[0-9]+:[0-9]+: error: code should be clang-formatted.*/\1/p' |
  sort -u)
if [ -z "$differ" ]; then # failed for another reason (a bad .clang-format, ...)
  printf '%s\n' "$out" >&2
  exit 2
fi
printf '%s\n' "$differ"
echo "format.sh: $(printf '%s\n' "$differ" | wc -l) of ${#files[@]} files differ from" \
  ".clang-format (scripts/format.sh reformats them)" >&2
exit 1
