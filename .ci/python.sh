#!/usr/bin/env bash
# The Python package's check: builds crates/brdf-py (PyO3 + maturin) into a virtual
# environment under .cache/, imports it, and runs its pytest suite. Needs python3 (≥ 3.9)
# with venv, cargo, and PyPI and crates.io. The bit-for-bit tests also run
# `cargo xtask eval …` / `cargo xtask lut generate` (release xtask, built on first use).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PY=${PYTHON:-python3}
VENV=.cache/python-venv
if [ ! -x "$VENV/bin/python" ]; then
    "$PY" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install --quiet --upgrade pip
"$VENV/bin/python" -m pip install --quiet pytest numpy hypothesis
echo "== pip install ./crates/brdf-py"
"$VENV/bin/python" -m pip install --quiet --force-reinstall --no-deps ./crates/brdf-py
"$VENV/bin/python" -c "import brdf_kernels; print('brdf_kernels', brdf_kernels.__version__)"

echo "== pytest crates/brdf-py/tests"
set +e
BRDF_PY_REQUIRE_RUST=1 "$VENV/bin/python" -m pytest -q crates/brdf-py/tests
rc=$?
set -e
if [ "$rc" -eq 5 ]; then
    echo "python.sh: pytest collected no tests (exit 5): the suite is missing" >&2
    exit 1
fi
exit "$rc"
