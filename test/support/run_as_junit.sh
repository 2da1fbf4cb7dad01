#!/usr/bin/env bash
# Runs a shell test and records its outcome as a one-case JUnit file, which is what catkin's
# run_tests / catkin_test_results count. Usage: run_as_junit.sh RESULT.xml NAME COMMAND [ARGS...]
set -u
result="$1"
name="$2"
shift 2
mkdir -p "$(dirname "$result")"
log="$(mktemp)"
SECONDS=0
"$@" >"$log" 2>&1
status=$?
seconds=$SECONDS
cat "$log"
escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' "$1"; }
{
  echo '<?xml version="1.0" encoding="UTF-8"?>'
  if [ "$status" -eq 0 ]; then
    echo "<testsuite name=\"$name\" tests=\"1\" failures=\"0\" errors=\"0\" time=\"$seconds\">"
    echo "  <testcase classname=\"$name\" name=\"$name\" time=\"$seconds\"/>"
  else
    echo "<testsuite name=\"$name\" tests=\"1\" failures=\"1\" errors=\"0\" time=\"$seconds\">"
    echo "  <testcase classname=\"$name\" name=\"$name\" time=\"$seconds\"><failure message=\"exit $status\"><![CDATA["
    tail -n 40 "$log" | sed 's/]]>/]] >/g'
    echo "]]></failure></testcase>"
  fi
  echo "</testsuite>"
} >"$result"
rm -f "$log"
exit "$status"
