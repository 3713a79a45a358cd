#!/bin/sh
# Random pole designs through every STEP and IGES layout (tests/audit/pole_audit.py: Python 3,
# standard library only). Usage: pole_audit.sh RG2 [N [FIRST_SEED]]. Skipped (exit 0, a SKIP
# line) only when there is no python3 on the path.
if ! command -v python3 >/dev/null 2>&1; then
    echo "SKIP: pole_audit: no python3 on the path"
    exit 0
fi
exec python3 "$(dirname "$0")/pole_audit.py" "$@"
