#!/usr/bin/env bash
# Rebuilds the small seed tables in fuzz/corpus/parse/seed_*.blut with the project's own
# generator (`cargo xtask lut generate`): one file per table kind and per lookup path the
# fuzz target checks (2-D and 3-D G with Catmull–Rom and linear u16 interpolation, the 3-D
# one with a log-warped σ axis: the documented exception of `LutView::sample`; E; split sum
# on √ axes, linear u16, the two-lane path; a 3 × 3 f32 split sum; an f16 E_avg). The other
# seeds (dfg_ts_smith.blut, kc_eavg_ggx.blut) are copies of the committed assets of those names
# (`cp assets/{dfg_ts_smith,kc_eavg_ggx}.blut fuzz/corpus/parse/`).
# Run from anywhere; only needed when the format changes (docs/fuzzing.md).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$root/fuzz/corpus/parse"
gen() { local name="$1"; shift; (cd "$root" && cargo xtask lut generate "$@" --samples 20 --force --out "$out/seed_$name.blut"); }
gen g2_cr --kind g-per-sigma --sigma 0.3 --res 9x9
gen g2_lin --kind g-per-sigma --sigma 0.3 --res 8x8 --interpolation linear
gen g3_cr --kind g-over-sigma --res 6x6x5
gen g3_lin_log --kind g-over-sigma --res 6x6x5 --interpolation linear --warp sigma=log
gen e_cr --kind e --model ggx --res 8x8
gen dfg_lin_sqrt --kind split-sum --model ggx --res 8x8 --interpolation linear --warp sqrt
gen dfg_f32_3 --kind split-sum --model ggx --res 3x3 --encoding f32
gen eavg_f16 --kind e-avg --model beckmann --res 5 --encoding f16 --interpolation linear
