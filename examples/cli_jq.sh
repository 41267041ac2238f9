#!/usr/bin/env bash
# The command line piped to jq: simulate the Fig. 4 case, keep the JSON, and pull out the
# fields one needs (jq: https://jqlang.org; the same pipeline works with any JSON tool).
#
#   bash examples/cli_jq.sh                  # writes examples/out/cli_jq/
#   bash examples/cli_jq.sh --out /tmp/cli
#
# PYTHON selects the interpreter (default: python3); run from the repository root or with
# phasekit installed.
set -euo pipefail
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    *) echo "cli_jq.sh: error: unknown argument $1 (usage: cli_jq.sh --out DIR)" >&2; exit 2 ;;
  esac
done
# without --out: examples/out/cli_jq beside this script (git-ignored)
[ -n "$out" ] || out="$(cd "$(dirname "$0")" && pwd)/out/cli_jq"
command -v jq >/dev/null || { echo "cli_jq.sh: error: jq is not installed (apt-get install jq)" >&2; exit 2; }
mkdir -p "$out"
py="${PYTHON:-python3}"

# one run, the whole JSON kept (it carries the model, the start and the options: pk.rerun reads it)
"$py" -m phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 10.5 --json > "$out/run.json"
# the summary fields
jq '{status, t_jump, R_min, theta_end, n_events, backend}' "$out/run.json" | tee "$out/summary.json"
# the events as a table: name and time
jq -r '.events[] | [.kind, .t] | @tsv' "$out/run.json" > "$out/events.tsv"
# a small sweep: t_jump for three Omega0, one JSON object per line
for w in 10.5 12 15; do
  "$py" -m phasekit simulate --a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 "$w" --json \
    | jq -c --arg w "$w" '{omega0: ($w | tonumber), status, t_jump}'
done | tee "$out/sweep.jsonl"
