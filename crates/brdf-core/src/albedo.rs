//! Directional albedo by fixed-size quadrature (owned by the models issue).
