#!/usr/bin/env bash
# Fails on a Markdown file that the code, docs, scenarios or configuration cite but that the
# repository does not hold. A reference resolves when a tracked .md file's path ends with it
# (leading ./ and ../ dropped), so docs/design.md, design.md (from docs/) and ../docs/design.md
# all name the same file. Lines that cite another project's documentation name that project
# (socketcand's protocol description) and are not checked.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mapfile -t tracked < <(git ls-files '*.md')
resolves() {
  local ref=$1 path
  while [[ $ref == ./* || $ref == ../* ]]; do ref=${ref#./}; ref=${ref#../}; done
  for path in "${tracked[@]}"; do
    [[ $path == "$ref" || $path == */"$ref" ]] && return 0
  done
  return 1
}
status=0
while IFS= read -r hit; do
  file=${hit%%:*}
  rest=${hit#*:}
  line=${rest#*:}
  [[ $line == *socketcand* ]] && continue
  for ref in $(grep -oE '[A-Za-z0-9_./-]*[A-Za-z0-9_-]\.md\b' <<<"$line"); do
    if ! resolves "$ref"; then
      echo "$file: cites $ref, which the repository does not have"
      status=1
    fi
  done
done < <(grep -rInE --exclude-dir=node_modules --exclude-dir=dist --exclude=check-doc-refs.sh \
           '[A-Za-z0-9_-]\.md\b' src tests web/src docs scenarios config scripts ./*.md)
[ "$status" -eq 0 ] && echo "check-doc-refs: every cited Markdown file is in the repository"
exit "$status"
