#!/usr/bin/env bash
# action.yml "Summary and pull-request comment": the report as the job summary
# ($GITHUB_STEP_SUMMARY) and, on a pull request, as one comment posted or
# updated with gh (found by its hidden marker line). Relative links of
# summary.md point at the one-file report's artifact (else the bundle's)
# unless the bundle was published with --link-base; images that cannot be
# shown from an artifact become links. The body stays under GitHub's 65,536
# characters (the summary's tail is cut at a line, with a note). A comment
# that cannot be posted (a read-only token: a fork's pull request) is a
# notice in the summary, never a failure: this step always succeeds.
#
# Environment: HQVIEW_COMMENT (update|new|off), HQVIEW_COMMENT_KEY,
# HQVIEW_COMMENT_BODY (run.sh's draft), HQVIEW_LINK_BASE, HQVIEW_ARTIFACT_URL,
# HQVIEW_REPORT_URL, GH_TOKEN; GITHUB_EVENT_PATH, GITHUB_REPOSITORY,
# GITHUB_STEP_SUMMARY, RUNNER_TEMP.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source=SCRIPTDIR/lib.sh
source "$here/lib.sh"

max_bytes=65000  # GitHub: 65,536 characters; bytes >= characters
mode="${HQVIEW_COMMENT:-update}"
key="$(printf '%s' "${HQVIEW_COMMENT_KEY:-hqview}" | tr -c 'A-Za-z0-9._-' '-')"
marker="<!-- hqview-action:$key -->"
draft="${HQVIEW_COMMENT_BODY:-}"
work="${RUNNER_TEMP:-/tmp}/hqview-action"
mkdir -p "$work"
body="$work/comment.md"
summary="${GITHUB_STEP_SUMMARY:-/dev/null}"

case "$mode" in update | new | off) ;; *)
  echo "::warning::comment: '$(command_text "$mode")' is not update, new or off: no comment"
  mode=off ;;
esac

target="${HQVIEW_REPORT_URL:-${HQVIEW_ARTIFACT_URL:-}}"
{
  printf '%s\n' "$marker"
  if [ -n "$draft" ] && [ -f "$draft" ]; then
    if [ -z "${HQVIEW_LINK_BASE:-}" ] && [ -n "$target" ]; then
      # Markdown links and images whose destination is relative (no scheme,
      # not an anchor): to the artifact.
      # (perl-base is part of every Debian and Ubuntu system.)
      HQVIEW_TARGET="$target" perl -pe \
        's{!?\[([^\]]*)\]\((?![A-Za-z][A-Za-z0-9+.-]*:|#)[^)\s]*\)}{[$1](<$ENV{HQVIEW_TARGET}>)}g' "$draft"
    else
      cat "$draft"
    fi
  fi
} > "$work/comment-full.md"
footer=""
if [ -n "${HQVIEW_REPORT_URL:-}" ]; then footer+="[the one-file report](<$HQVIEW_REPORT_URL>)"; fi
if [ -n "${HQVIEW_ARTIFACT_URL:-}" ]; then footer+="${footer:+ · }[the bundle (zip)](<$HQVIEW_ARTIFACT_URL>)"; fi
if [ -n "$footer" ]; then footer=$'\n---\n'"Full report: $footer"$'\n'; fi

# The cap: whole lines of the draft while they fit, then a note.
size=$(wc -c < "$work/comment-full.md")
if [ $((size + ${#footer})) -le $max_bytes ]; then
  cp "$work/comment-full.md" "$body"
else
  note=$'\n'"_The report is longer than a comment allows: its last NNNNNNNN lines are left out here; they are in the full report._"$'\n'
  budget=$((max_bytes - ${#footer} - ${#note}))
  head -c "$budget" "$work/comment-full.md" | sed '$d' > "$body"  # the last, maybe cut, line goes
  left=$(( $(wc -l < "$work/comment-full.md") - $(wc -l < "$body") ))
  printf '%s' "${note/NNNNNNNN/$left}" >> "$body"
fi
printf '%s' "$footer" >> "$body"
cat "$body" >> "$summary"

note_summary() {  # a line in the job summary and the log
  echo "$1"
  printf '\n> %s\n' "$1" >> "$summary"
}

if [ "$mode" = off ]; then exit 0; fi
pr=""
if [ -n "${GITHUB_EVENT_PATH:-}" ] && [ -f "$GITHUB_EVENT_PATH" ]; then
  pr="$(jq -r '.pull_request.number // empty' "$GITHUB_EVENT_PATH")"
fi
if [ -z "$pr" ]; then
  echo "not a pull request: the report is in the job summary only"
  exit 0
fi
repo="${GITHUB_REPOSITORY:?}"
json="$work/comment.json"
jq -n --rawfile body "$body" '{body: $body}' > "$json"

gh_failed() {  # what gh said, as a notice (a fork's read-only token) or a warning
  local err="$1"
  if grep -q -e 'HTTP 403' -e 'Resource not accessible by integration' "$err"; then
    note_summary "HQView could not post the pull-request comment (the token is read-only, as on a pull request from a fork): the report is in this job summary."
  else
    echo "::warning::gh: $(command_text "$(tail -c 500 "$err")")"
    note_summary "HQView could not post the pull-request comment (gh failed): the report is in this job summary."
  fi
  exit 0
}

id=""
if [ "$mode" = update ]; then
  if ! gh api --paginate "repos/$repo/issues/$pr/comments" > "$work/comments.json" 2> "$work/gh.err"; then
    gh_failed "$work/gh.err"
  fi
  id="$(jq -r --arg m "$marker" '.[] | select((.body // "") | contains($m)) | .id' "$work/comments.json" | head -n 1)"
fi
if [ -n "$id" ]; then
  gh api -X PATCH "repos/$repo/issues/comments/$id" --input "$json" > /dev/null 2> "$work/gh.err" || gh_failed "$work/gh.err"
  echo "updated comment $id of pull request #$pr"
else
  gh api -X POST "repos/$repo/issues/$pr/comments" --input "$json" > /dev/null 2> "$work/gh.err" || gh_failed "$work/gh.err"
  echo "commented on pull request #$pr"
fi
exit 0
