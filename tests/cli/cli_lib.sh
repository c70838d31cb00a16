# Shared by the CLI test scripts (source it after setting `kasumi` and `src`): a scratch
# directory `work` removed on exit, a failure counter, and the exit-code check.

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_exit CODE PATTERN -- ARGS...: runs kasumi, checks the exit code and that stderr
# matches PATTERN (grep -E; empty pattern skips the check).
expect_exit() {
  local code="$1" pattern="$2"
  shift 3
  "$kasumi" "$@" >"$work/stdout" 2>"$work/stderr"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    fail "kasumi $* exited $got, expected $code; stderr: $(head -c 600 "$work/stderr")"
  elif [ -n "$pattern" ] && ! grep -qE -- "$pattern" "$work/stderr"; then
    fail "kasumi $* stderr lacks /$pattern/: $(head -c 600 "$work/stderr")"
  fi
}

# finish WHAT: the last line of a script: the count of failed checks and exit 1, or "WHAT: all
# checks passed" and exit 0.
finish() {
  if [ "$failures" -gt 0 ]; then
    echo "$1: $failures check(s) failed"
    exit 1
  fi
  echo "$1: all checks passed"
  exit 0
}
