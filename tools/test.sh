#!/usr/bin/env bash
# Set up if needed (tools/setup.sh), then run the whole test suite: the GoogleTest unit tests
# of the LAMMPS-free core (through ctest) and the pytest suite that drives build/lmp.
# Extra arguments go to pytest, e.g. tools/test.sh -k harness  or  tools/test.sh -m "not slow".
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/tools/setup.sh" || { echo "[test] set-up failed" >&2; exit 1; }

echo "[test] GoogleTest (ctest) ..."
ctest_log="$here/build/ctest.log"
(cd "$here/build" && ctest --output-on-failure -j "$(nproc)") >"$ctest_log" 2>&1
ctest_rc=$?
grep -E "tests passed|tests failed|\*\*\*Failed|Exception|Not Run" "$ctest_log" || true
[ $ctest_rc = 0 ] || tail -n 60 "$ctest_log"
summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$ctest_log" | tail -n 1)
g_total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$summary")
g_failed=$(sed -E 's/.*passed, ([0-9]+) tests failed.*/\1/' <<<"$summary")
[ -n "$g_total" ] || { g_total=0; g_failed=1; }

echo "[test] pytest ..."
cd "$here"
/usr/bin/python3 -m pytest -p no:cacheprovider -rfEs unittest/python "$@" | tee build/pytest.log
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
