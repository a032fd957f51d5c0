# shellcheck shell=bash
# Helpers of the action's scripts (sourced): outputs, words, messages.

# output NAME VALUE: a step output, in GITHUB_OUTPUT's multi-line form with a
# random delimiter, so no value (a mesh path) can add or end an output.
output() {
  local delimiter
  delimiter="hqview_$(od -An -N12 -tx1 /dev/urandom | tr -d ' \n')"
  if [ -n "${GITHUB_OUTPUT:-}" ]; then
    printf '%s<<%s\n%s\n%s\n' "$1" "$delimiter" "$2" "$delimiter" >> "$GITHUB_OUTPUT"
  fi
}

# words TEXT: the words of TEXT, NUL-terminated, split as a shell splits them
# (quotes and backslashes) but without any expansion ($, `, globs stay text).
words() {
  printf '%s' "$1" | xargs -r printf '%s\0'
}

# lines TEXT: the non-blank lines of TEXT, trimmed, NUL-terminated.
lines() {
  printf '%s\n' "$1" | sed -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' -e '/^$/d' | tr '\n' '\0'
}

# A workflow command's text: % and line breaks escaped (GitHub's rule).
command_text() {
  local s="$1"
  s="${s//'%'/%25}"
  s="${s//$'\r'/%0D}"
  s="${s//$'\n'/%0A}"
  printf '%s' "$s"
}
