#!/usr/bin/env bash
# tests/check_public_api_test.sh: scripts/check-public-api.sh on the fixture
# tests/data/public_api (its README): a parameter, a variable and a member
# call that bear a public function's name are no use of it, so the function
# that only those "use" is reported, and the four real uses (a call, an
# address, a qualified name passed as a value) are counted. The ctest test
# check_public_api_fixture (label unit).
set -u
here=$(cd "$(dirname "$0")" && pwd)
out=$("$here/../scripts/check-public-api.sh" "$here/data/public_api")
rc=$?
expected="include/ptnet/shop.hpp:11: shop_name: called only by stage shop and tests"
first=$(printf '%s\n' "$out" | head -n 1)
if [ "$rc" -ne 1 ] || [ "$first" != "$expected" ] || [ "$(printf '%s\n' "$out" | wc -l)" -ne 2 ]; then
  echo "check_public_api_test: expected exit 1 and"
  echo "  $expected"
  echo "found exit $rc and"
  printf '%s\n' "$out" | sed 's/^/  /'
  exit 1
fi
echo "check_public_api_test: the fixture's parameter, variable and member call are no uses; its four uses are"
