# Shared by the guest's /init and checks: result lines and small helpers.
# Every check prints exactly one line "HIL <name> PASS|FAIL [(reason)]"; the host
# counts them (sim/hil/run.sh).

hil_result() {  # hil_result NAME PASS|FAIL [reason]
  echo "HIL $1 $2${3:+ ($3)}"
  echo "$2" >> /tmp/hil.results
}
hil_pass() { hil_result "$1" PASS "${2:-}"; }
hil_fail() { hil_result "$1" FAIL "${2:-}"; }
hil_check() {  # hil_check NAME COMMAND...: PASS when the command succeeds
  local name=$1
  shift
  local log
  log=/tmp/check-$(echo "$name" | tr / _).log
  if "$@" > "$log" 2>&1; then
    hil_pass "$name"
  else
    hil_fail "$name" "exit $?"
    sed 's/^/  | /' "$log" | tail -20
  fi
}
# Run a gtest program; one HIL line per test case ("<program>/<Suite.Test>").
# Skips count as failures here: inside the guest every device is present.
hil_gtest() {  # hil_gtest PROGRAM [gtest args...]
  local prog=$1 name
  shift
  name=$(basename "$prog")
  local log=/tmp/gtest-$name.log
  "$prog" --gtest_color=no "$@" > "$log" 2>&1
  local rc=$?
  # gtest's per-case result lines end in "(N ms)"; the summary repeats them without.
  awk '/^\[ +(OK|FAILED|SKIPPED) +\] [^ ]+ \([0-9]+ ms\)$/ {
         line = $0; sub(/^\[ +/, "", line); split(line, part, / +\] /)
         split(part[2], rest, " "); print part[1], rest[1] }' "$log" > "/tmp/gtest-$name.cases"
  local cases
  cases=$(wc -l < "/tmp/gtest-$name.cases")
  # Measured figures the tests print ("figure: ...") are kept in the console log.
  grep '^figure: ' "$log" | sed 's/^/  | /'

  while read -r tag test; do
    case $tag in
      OK) hil_pass "$name/$test" ;;
      FAILED) hil_fail "$name/$test" ;;
      SKIPPED) hil_fail "$name/$test" "skipped in the guest: $(grep -B3 -F "] $test (" "$log" | grep -m1 'skipped:' | cut -c1-100)" ;;
    esac
  done < "/tmp/gtest-$name.cases"
  if [ "$rc" -ne 0 ] || [ "$cases" -eq 0 ]; then
    # Failures: show the log; a crash (no FAILED line) still fails the program.
    grep -q '^\[  FAILED  \]' "$log" || hil_fail "$name" "exit $rc after $cases test cases"
    sed 's/^/  | /' "$log" | grep -v '^  | \[ \(RUN\|       OK\) ' | tail -60
  fi
}
