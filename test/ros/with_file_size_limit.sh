#!/usr/bin/env bash
# Test helper (launch-prefix): runs a command with its files limited to KB kilobytes, as on a disk
# that fills. SIGXFSZ is ignored (the disposition survives exec), so a write past the limit
# fails with EFBIG like ENOSPC instead of killing the process.
# Usage: with_file_size_limit.sh KB COMMAND [ARGS...]
set -euo pipefail
limit_kb="$1"; shift
trap '' XFSZ
ulimit -f "$limit_kb"
exec "$@"
