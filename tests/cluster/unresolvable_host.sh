#!/usr/bin/env bash
# The test cluster needs no host-name resolution (issue 19): runs a Slurm test
# (tests/cluster/slurm_*.sh) in a UTS namespace of its own whose host name resolves nowhere, as
# on a fresh chroot or container whose /etc/hosts does not name the machine. The test must pass;
# a skip whose reason is an unresolvable name fails here.
#
#   bash tests/cluster/unresolvable_host.sh TEST.sh /path/to/simbob /path/to/repo [BUILD]
#
# Exit 77 (skip) when this machine cannot make a UTS namespace (not root, or a container that
# forbids it), or when the made-up name resolves after all (a wildcard DNS), or when the test
# itself skips for another reason (no Slurm here).
set -uo pipefail
TEST=${1:?usage: unresolvable_host.sh TEST.sh SIMBOB REPO [BUILD]}
shift
NAME="simbob-unresolvable-$$"
if ! unshare --uts true 2>/dev/null; then
  printf 'SKIP: cannot make a UTS namespace here (unshare --uts needs root and CAP_SYS_ADMIN)\n'
  exit 77
fi
out=$(mktemp)
trap 'rm -f "$out"' EXIT
# Inside the namespace: the new name, a check that it does not resolve, then the test.
unshare --uts bash -c '
  hostname "$1" || exit 2
  if getent ahosts "$1" >/dev/null; then echo "RESOLVES: $(getent ahosts "$1" | head -n 1)"; exit 3; fi
  shift
  exec bash "$@"' unresolvable "$NAME" "$TEST" "$@" 2>&1 | tee "$out"
status=${PIPESTATUS[0]}
case $status in
  0) printf 'ok: %s ran with the host name %s, which does not resolve\n' "$(basename "$TEST")" "$NAME" ;;
  2) printf 'SKIP: cannot set the host name in a UTS namespace\n'; exit 77 ;;
  3) printf 'SKIP: the made-up host name %s resolves here\n' "$NAME"; exit 77 ;;
  77)
    if grep -qi 'resolve' "$out"; then
      printf 'FAIL: %s skipped because the host name %s does not resolve: the test cluster must not need it\n' \
        "$(basename "$TEST")" "$NAME"
      exit 1
    fi
    exit 77 ;;
esac
exit "$status"
