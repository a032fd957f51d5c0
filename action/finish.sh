#!/usr/bin/env bash
# action.yml "Gate", the last step: fails when hqview could not run
# (gate-status error) and, when fail-on-gate is true, when a gate failed.
# Environment: HQVIEW_GATE_STATUS, HQVIEW_EXIT_CODE, HQVIEW_FAIL_ON_GATE.
set -uo pipefail
status="${HQVIEW_GATE_STATUS:-error}"
code="${HQVIEW_EXIT_CODE:-}"
case "$status" in
  passed) echo "hqview: every gate passed"; exit 0 ;;
  failed)
    if [ "${HQVIEW_FAIL_ON_GATE:-true}" = true ]; then
      echo "::error::hqview: a gate failed (exit code $code; the job summary lists them)"
      exit 1
    fi
    echo "::warning::hqview: a gate failed (exit code $code); fail-on-gate is ${HQVIEW_FAIL_ON_GATE}"
    exit 0 ;;
  *)
    echo "::error::hqview could not run (exit code ${code:-none}; see the Analyse step's log)"
    exit 1 ;;
esac
