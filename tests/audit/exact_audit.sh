#!/bin/sh
# The independent audit of the geometry (tests/audit/exact_audit.py: Python 3, standard library
# only). Usage: exact_audit.sh RG2 SRC_DIR. Skipped (exit 0, a SKIP line) only when there is no
# python3 on the path.
if ! command -v python3 >/dev/null 2>&1; then
    echo "SKIP: exact_audit: no python3 on the path"
    exit 0
fi
exec python3 "$(dirname "$0")/exact_audit.py" "$1" "$2"
