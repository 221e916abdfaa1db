//! Zero-copy, no_std LUT view (owned by the LUT issue).
