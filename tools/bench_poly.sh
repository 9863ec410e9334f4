#!/usr/bin/env bash
# Runs trajkit's polynomial-evaluation benchmark and the NumPy peer back to back, in one run.
# Usage: tools/bench_poly.sh
set -euo pipefail
cd "$(dirname "$0")/.."
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
date -u
cargo bench -p trajkit --bench poly_eval -- --noplot 2>&1 | grep -E "^poly_eval|time:|thrpt:"
python3 tools/bench_poly_peer.py
