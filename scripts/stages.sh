# Sourced by the README's commands: `stage NAME` starts a timed stage (and ends
# the one before it), `stage_end` ends the last; each prints its wall time, and
# the summary lists them all.
_stage_name=""
_stage_start=0
_stage_summary=""
stage_end() {
  if [ -n "$_stage_name" ]; then
    local took=$((SECONDS - _stage_start))
    printf '== %s: %d min %02d s\n' "$_stage_name" $((took / 60)) $((took % 60))
    _stage_summary+=$(printf '   %-34s %4d s' "$_stage_name" "$took")$'\n'
  fi
  _stage_name=""
  if [ -n "$_stage_summary" ] && [ $# -eq 0 ]; then
    printf '== stage times (total %d s):\n%s' "$SECONDS" "$_stage_summary"
  fi
}
stage() {
  [ -n "$_stage_name" ] && stage_end --quiet
  _stage_name="$1"
  _stage_start=$SECONDS
  echo "== $1"
}
