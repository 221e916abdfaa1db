//! Batch (structure-of-arrays) entry points (owned by the benchmarks issue).
