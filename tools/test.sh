#!/usr/bin/env bash
# Set up if needed (tools/setup.sh), then run the test suite: the GoogleTest unit tests of the
# LAMMPS-free core (through ctest) and the pytest suite that drives build/lmp, each on as many
# processes as the machine has cores (ctest -j, pytest-xdist's -n).
#
#   bash tools/test.sh          the default tier: every test but those marked "full"
#   bash tools/test.sh --full   every test: also the benchmark drivers' end-to-end runs, the
#                               core's stand-alone build and the Sphinx build of the manual
#
# Other arguments go to pytest, e.g. tools/test.sh -k harness  or  tools/test.sh -m "not slow"
# (a -m of your own replaces the tier's selection). The last lines give the counts of both.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tier=(-m "not full")
tier_name="default tier"
args=()
for arg in "$@"; do
  if [ "$arg" = --full ]; then tier=(); tier_name="full tier"; else args+=("$arg"); fi
done
bash "$here/tools/setup.sh" || { echo "[test] set-up failed" >&2; exit 1; }
jobs=$(nproc)

echo "[test] GoogleTest (ctest -j $jobs) ..."
ctest_log="$here/build/ctest.log"
(cd "$here/build" && ctest --output-on-failure -j "$jobs") >"$ctest_log" 2>&1
ctest_rc=$?
grep -E "tests passed|tests failed|\*\*\*Failed|Exception|Not Run" "$ctest_log" || true
[ $ctest_rc = 0 ] || tail -n 60 "$ctest_log"
summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$ctest_log" | tail -n 1)
g_total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$summary")
g_failed=$(sed -E 's/.*passed, ([0-9]+) tests failed.*/\1/' <<<"$summary")
[ -n "$g_total" ] || { g_total=0; g_failed=1; }

echo "[test] pytest ($tier_name, $jobs processes) ..."
cd "$here"
# --dist loadgroup: tests that share a module-scoped fixture run in one process (conftest.py
# groups them), the others go to whichever process is free
/usr/bin/python3 -m pytest -p no:cacheprovider -rfEs --durations=20 -n "$jobs" \
  --dist loadgroup "${tier[@]}" unittest/python "${args[@]}" | tee build/pytest.log
pytest_rc=${PIPESTATUS[0]}
p_line=$(grep -E "^=+ .*(passed|failed|error).* in [0-9.]+s" build/pytest.log | tail -n 1)
p_passed=$(grep -oE "[0-9]+ passed" <<<"$p_line" | grep -oE "[0-9]+" || echo 0)
p_failed=$(( $(grep -oE "[0-9]+ failed" <<<"$p_line" | grep -oE "[0-9]+" || echo 0) \
  + $(grep -oE "[0-9]+ error" <<<"$p_line" | grep -oE "[0-9]+" || echo 0) ))

echo
echo "[test] GoogleTest: $((g_total - g_failed)) passed, $g_failed failed (ctest rc $ctest_rc)"
echo "[test] pytest:     $p_passed passed, $p_failed failed (pytest rc $pytest_rc)"
echo "total: $((g_total - g_failed + p_passed)) passed, $((g_failed + p_failed)) failed"
[ $ctest_rc = 0 ] && [ $pytest_rc = 0 ] && [ "$g_total" -gt 0 ] && [ "$p_passed" -gt 0 ]
