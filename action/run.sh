#!/usr/bin/env bash
# action.yml "Analyse": `hqview analyze` (a mesh) or `hqview batch` (a
# directory or manifest) with the action's inputs, then `hqview diff` against
# the baseline when there is one. hqview's exit code is captured, never
# fatal: this step always writes its outputs (exit-code, gate-status, bundle,
# worst-mesh, report-html, comment-body) and succeeds; action/finish.sh fails
# the job when fail-on-gate says so.
#
# Environment: HQVIEW_INPUTS, HQVIEW_MODE (auto|analyze|batch),
# HQVIEW_OUTPUT, HQVIEW_OPTIONS (shell words, not expanded), HQVIEW_GATES and
# HQVIEW_DIFF_GATES (one rule per line), HQVIEW_BASELINE, HQVIEW_LINK_BASE,
# HQVIEW_SINGLE_FILE (true|viewer|false); RUNNER_TEMP, GITHUB_OUTPUT.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source=SCRIPTDIR/lib.sh
source "$here/lib.sh"

inputs="${HQVIEW_INPUTS:-}"
out="${HQVIEW_OUTPUT:-hqview-report}"
mode="${HQVIEW_MODE:-auto}"
work="${RUNNER_TEMP:-/tmp}/hqview-action"
mkdir -p "$work"
rm -f "$work/diff.md" "$work/comment-draft.md"

fail_early() {  # an input the action cannot use: outputs as for an hqview usage error
  echo "::error::$(command_text "$1")"
  output exit-code 2
  output gate-status error
  output bundle ""
  output worst-mesh ""
  output report-html ""
  output comment-body ""
  exit 0
}

[ -n "$inputs" ] || fail_early "inputs: empty (a mesh, a directory or a manifest)"
if [ "$mode" = auto ]; then
  if [ -d "$inputs" ]; then mode="batch"
  else
    case "${inputs,,}" in *.csv | *.json) mode="batch" ;; *) mode="analyze" ;; esac
  fi
fi
case "$mode" in analyze | batch) ;; *) fail_early "mode: '$mode' (auto, analyze or batch)" ;; esac

args=()
if ! words "${HQVIEW_OPTIONS:-}" > "$work/options" 2> "$work/options.err"; then
  fail_early "options: $(cat "$work/options.err")"
fi
mapfile -d '' -t options < "$work/options"
mapfile -d '' -t gates < <(lines "${HQVIEW_GATES:-}")
for g in "${gates[@]}"; do args+=(--gate "$g"); done
if [ -n "${HQVIEW_LINK_BASE:-}" ]; then args+=(--link-base "$HQVIEW_LINK_BASE"); fi
case "${HQVIEW_SINGLE_FILE:-true}" in
  true) args+=(--single-file) ;;
  viewer) args+=(--single-file=viewer) ;;
  false | "") ;;
  *) fail_early "single-file: '${HQVIEW_SINGLE_FILE}' (true, viewer or false)" ;;
esac

# --force: a runner's workspace may hold the output of an earlier step.
echo "hqview $mode $inputs -o $out ${options[*]} ${args[*]}"
hqview "$mode" "$inputs" -o "$out" --force "${options[@]}" "${args[@]}"
code=$?

case "$code" in
  0) status=passed ;;
  1) status=failed ;;
  3) if [ "$mode" = batch ]; then status=failed; else status=error; fi ;;  # batch: a mesh failed, the others are there
  *) status=error ;;
esac
bundle=""
if [ -f "$out/index.json" ] || [ -f "$out/report.json" ]; then bundle="$out"; fi

# The baseline: a bundle or batch folder (its index.json or report.json).
if [ -n "${HQVIEW_BASELINE:-}" ] && [ -n "$bundle" ]; then
  if [ -f "$HQVIEW_BASELINE/index.json" ] || [ -f "$HQVIEW_BASELINE/report.json" ] || [ -f "$HQVIEW_BASELINE" ]; then
    mapfile -d '' -t diff_gates < <(lines "${HQVIEW_DIFF_GATES:-}")
    dargs=()
    for g in "${diff_gates[@]}"; do dargs+=(--gate "$g"); done
    hqview diff "$HQVIEW_BASELINE" "$bundle" "${dargs[@]}" --markdown "$work/diff.md" --quiet
    dcode=$?
    case "$dcode" in
      0) ;;
      1) if [ "$status" = passed ]; then status=failed; code=1; fi ;;
      *) echo "::warning::hqview diff failed (exit $dcode): no comparison with the baseline"; rm -f "$work/diff.md" ;;
    esac
  else
    echo "::notice::baseline $(command_text "$HQVIEW_BASELINE"): no report.json or index.json there (a first run?): no comparison"
  fi
fi

# The worst mesh: a failed one first, else the lowest minimum scaled Jacobian.
worst=""
if [ "$mode" = analyze ]; then
  worst="$(basename -- "$inputs")"
elif [ -f "$out/index.json" ]; then
  worst="$(jq -r '[.meshes[] | select(.status != "skipped")] as $m
    | (([$m[] | select(.status == "failed")] | .[0].path)
       // ([$m[] | select(.headline["quality.scaled_jacobian.min"] != null)]
           | min_by(.headline["quality.scaled_jacobian.min"]) | .path)) // ""' "$out/index.json")"
fi

# The comment's draft: the diff, then the summary (links rewritten and the
# size capped by action/comment.sh, which knows the artifacts' URLs).
draft="$work/comment-draft.md"
: > "$draft"
if [ -f "$work/diff.md" ]; then cat "$work/diff.md" >> "$draft"; printf '\n' >> "$draft"; fi
if [ -n "$bundle" ] && [ -f "$bundle/summary.md" ]; then
  cat "$bundle/summary.md" >> "$draft"
else
  # shellcheck disable=SC2016  # the backticks are Markdown
  printf '## HQView: no report\n\n`hqview %s` stopped with exit code %s; the log of this step says why.\n' "$mode" "$code" >> "$draft"
fi

report=""
if [ -n "$bundle" ] && [ -f "$bundle/report.html" ]; then report="$bundle/report.html"; fi
output exit-code "$code"
output gate-status "$status"
output bundle "$bundle"
output worst-mesh "$worst"
output report-html "$report"
output comment-body "$draft"
echo "hqview: exit code $code, gates $status${worst:+, worst mesh $worst}"
exit 0
