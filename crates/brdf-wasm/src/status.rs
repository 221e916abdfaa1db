//! Status codes returned by the array and loading exports (`i32`): 0 or a positive count on
//! success, a negative code on failure.

/// Success.
pub const OK: i32 = 0;
/// A model parameter is NaN, infinite or outside its documented range, or the model id or G
/// kind is unknown.
pub const BAD_PARAM: i32 = -1;
/// A null pointer, or an array length/size beyond the documented maximum.
pub const BAD_BUFFER: i32 = -2;
/// The LUT bytes were rejected by the validating view (truncated, corrupt, wrong kind, …).
pub const BAD_LUT: i32 = -3;
/// A LUT query before a LUT was loaded successfully.
pub const NO_LUT: i32 = -4;
