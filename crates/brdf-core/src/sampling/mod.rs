//! Importance sampling (owned by the models issue).
