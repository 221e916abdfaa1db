//! Validation of the masking–shadowing terms against physics.
//!
//! * [`profile`]: long periodic 1-D random profiles with Gaussian heights and a Gaussian
//!   autocorrelation, and the exact conditioning of such a profile on one facet's slope.
//! * [`surface`]: ray-traced ground truth on those profiles: the bistatic G(θi, θr), the
//!   one-sided G1(θ | α), the projected-area identity and a slope-bin estimator.
//! * [`facet`]: the paper's own single-neighbour facet model simulated geometrically.
//! * [`smith1d`]: an independent 1-D Smith Λ (Gaussian slopes), for the known-answer checks.
//! * [`surface2d`], [`study2d`], [`report2d`]: the same measurement in three dimensions, on
//!   2-D Gaussian random height fields (triangle pairs, exact conditioning and tracing).
//! * [`stats`]: estimates with batch-means and binomial standard errors.
//! * [`study`]: the grids, error tables and figure data; [`figures`] and [`report`] write
//!   the SVG/PNG figures and `docs/validation.md` (`cargo xtask plot`).
//!
//! Geometry follows docs/conventions.md §1: the light comes from the −x side at θi ≥ 0, θr is
//! signed (θr > 0 forward), the facet tilt is α = (θr − θi)/2, so a facet that mirrors the
//! light into the viewer has slope dz/dx = −tan α.

pub mod albedo_fig;
pub mod dfg_fig;
pub mod document;
pub mod facet;
pub mod figures;
pub mod profile;
pub mod progress;
pub mod report;
pub mod report2d;
pub mod smith1d;
pub mod stats;
pub mod study;
pub mod study2d;
pub mod surface;
pub mod surface2d;
pub mod textbook;
