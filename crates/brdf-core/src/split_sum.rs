//! Split-sum (DFG) and energy-compensation integrals (owned by the LUT issue).
