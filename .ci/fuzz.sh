#!/usr/bin/env bash
# The BLUT parser's fuzz target (fuzz/fuzz_targets/parse.rs; what it asserts: docs/fuzzing.md)
# for FUZZ_SECONDS seconds (default 60: the CI smoke run; the documented long run is 600).
# Installs what it needs: the nightly toolchain (minimal profile) and cargo-fuzz 0.13.2
# (skipped when that version is installed). Fails on any crash, panic, failed assertion,
# leak or timeout (libFuzzer's exit status; the input is kept in fuzz/artifacts/parse/).
#
# Regenerates nothing: fuzz/ builds against its own Cargo.lock (checked unchanged at the
# end), the checked-in seeds (fuzz/corpus/parse) are only read, and the inputs the run
# finds go to a temporary corpus (FUZZ_CORPUS to keep them elsewhere).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds="${FUZZ_SECONDS:-60}"
case "$seconds" in
    '' | *[!0-9]*) echo "FUZZ_SECONDS must be a whole number of seconds, got '$seconds'" >&2; exit 2 ;;
esac

echo "== nightly toolchain and cargo-fuzz 0.13.2"
rustup toolchain install nightly --profile minimal
if ! cargo fuzz --version 2>/dev/null | grep -q '0\.13\.2'; then
    cargo install cargo-fuzz --version 0.13.2 --locked
fi

corpus="${FUZZ_CORPUS:-$(mktemp -d)}"
mkdir -p "$corpus"
lock_before="$(sha256sum fuzz/Cargo.lock)"

echo "== fuzz target parse for ${seconds} s (new inputs in $corpus)"
cd fuzz
# The first corpus folder receives what the run finds; the seeds are read only.
cargo +nightly fuzz run parse "$corpus" corpus/parse -- \
    -max_total_time="$seconds" -print_final_stats=1
cd ..

if [ "$(sha256sum fuzz/Cargo.lock)" != "$lock_before" ]; then
    echo "fuzz/Cargo.lock changed during the build: commit the lock file that fuzz/ needs" >&2
    exit 1
fi
echo "== fuzz: no crash in ${seconds} s"
