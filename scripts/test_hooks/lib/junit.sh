# Sourced by the test hooks: write_junit XML SUITE CASE SECONDS [FAILURE_MESSAGE LOG] writes a JUnit
# file of one test case, which scripts/summarize_test_results.py and catkin_test_results count; a
# failure carries the message and the last 80 lines of LOG.
write_junit() {
  local xml=$1 suite=$2 case=$3 seconds=$4 message=${5:-} log=${6:-}
  local failures=0 body=""
  if [ -n "$message" ]; then
    failures=1
    # The report inside CDATA; a literal "]]>" in it would end the section early.
    local report=""
    [ -n "$log" ] && report=$(tail -n 80 "$log" | sed 's/]]>/]] >/g' | tr -d '\000-\010\013\014\016-\037')
    body="<failure message=\"$(printf '%s' "$message" | sed 's/&/\&amp;/g; s/"/\&quot;/g; s/</\&lt;/g')\"><![CDATA[$report]]></failure>"
  fi
  cat > "$xml" <<XML
<?xml version="1.0" encoding="utf-8"?>
<testsuite name="$suite" tests="1" failures="$failures" errors="0">
  <testcase classname="$suite" name="$case" time="$seconds">$body</testcase>
</testsuite>
XML
}
