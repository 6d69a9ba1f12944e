# The project's hal test programs against the real drivers: the device tests that
# skip on a host without devices run for real here (a skip is a failure).
for t in /hil/bin/hal_tests /hil/bin/hal_*_tests; do
  [ -x "$t" ] && hil_gtest "$t"
done
