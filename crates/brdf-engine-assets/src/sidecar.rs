//! The JSON sidecars: their bytes as every layout writes them (`sidecar_bytes`) and their
//! `inverse_mapping`: one axis's physical value ↔ texture coordinate, read from the fields a
//! sidecar states (warp, lo, hi, count, placement) and evaluated in f64.

/// A sidecar's bytes: pretty-printed JSON and a final newline.
pub(crate) fn sidecar_bytes(side: &serde_json::Value) -> crate::Result<Vec<u8>> {
    let mut b =
        serde_json::to_vec_pretty(side).map_err(|e| crate::Error::Encode(format!("json: {e}")))?;
    b.push(b'\n');
    Ok(b)
}

/// One axis of the sidecar's `inverse_mapping`, read from its stated fields (warp, lo, hi,
/// count, placement) and evaluated in f64 — not from the exporter's f32 constants.
pub struct Mapping {
    /// Smallest physical value.
    pub lo: f64,
    /// Largest physical value.
    pub hi: f64,
    /// Nodes on the axis.
    pub count: usize,
    /// The warp's name (`linear`, `log`, `sqrt`, `cos`, `sqrt-cos`).
    pub warp: String,
    /// Endpoint placement (else texel centres).
    pub endpoint: bool,
}

impl Mapping {
    /// The axis from its JSON object; an unknown warp or placement, a missing field or a
    /// count outside 2..=4096 is an error naming it.
    pub fn from_json(m: &serde_json::Value) -> Result<Self, String> {
        let f = |k: &str| m[k].as_f64().ok_or_else(|| format!("sidecar: {k}"));
        let count = m["count"].as_u64().ok_or("sidecar: count")? as usize;
        if !(2..=4096).contains(&count) {
            return Err(format!("sidecar: axis count {count} outside 2..=4096"));
        }
        let endpoint = match m["placement"].as_str() {
            Some("endpoint") => true,
            Some("texel-centre") => false,
            p => return Err(format!("sidecar: unknown placement {p:?}")),
        };
        Ok(Self {
            lo: f("lo")?,
            hi: f("hi")?,
            count,
            warp: match m["warp"].as_str() {
                Some(w @ ("linear" | "log" | "sqrt" | "cos" | "sqrt-cos")) => w.to_string(),
                w => return Err(format!("sidecar: unknown warp {w:?}")),
            },
            endpoint,
        })
    }
    /// Step 1: x clamped to [lo, hi].
    pub fn clamp(&self, x: f64) -> f64 {
        x.clamp(self.lo, self.hi)
    }
    /// Steps 2–3: the warped unit coordinate t of x.
    pub fn t(&self, x: f64) -> f64 {
        let (lo, hi) = (self.lo, self.hi);
        let x = self.clamp(x);
        let sc = |c: f64| c.max(0.0).sqrt();
        match self.warp.as_str() {
            "log" => (x / lo).ln() / (hi / lo).ln(),
            "sqrt" => ((x - lo) / (hi - lo)).sqrt(),
            "cos" => (lo.cos() - x.cos()) / (lo.cos() - hi.cos()),
            "sqrt-cos" => (sc(lo.cos()) - sc(x.cos())) / (sc(lo.cos()) - sc(hi.cos())),
            _ => (x - lo) / (hi - lo), // linear
        }
        .clamp(0.0, 1.0)
    }
    /// Step 4: the texture coordinate of x.
    pub fn coord(&self, x: f64) -> f64 {
        let (t, n) = (self.t(x), self.count as f64);
        if self.endpoint {
            (t * (n - 1.0) + 0.5) / n
        } else {
            t
        }
    }
    /// The physical value at warped coordinate t (inverse of [`Mapping::t`]).
    pub fn node_at(&self, t: f64) -> f64 {
        let (lo, hi) = (self.lo, self.hi);
        let sc = |c: f64| c.max(0.0).sqrt();
        match self.warp.as_str() {
            "log" => lo * (hi / lo).powf(t),
            "sqrt" => lo + t * t * (hi - lo),
            "cos" => (lo.cos() - t * (lo.cos() - hi.cos())).acos(),
            "sqrt-cos" => {
                let s = sc(lo.cos()) - t * (sc(lo.cos()) - sc(hi.cos()));
                (s * s).acos()
            }
            _ => lo + t * (hi - lo), // linear
        }
    }
    /// Node i: t = i/(N − 1) (endpoint) or (i + ½)/N (texel centre).
    pub fn node(&self, i: usize) -> f64 {
        let n = self.count as f64;
        let t = if self.endpoint {
            i as f64 / (n - 1.0)
        } else {
            (i as f64 + 0.5) / n
        };
        self.node_at(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sidecar mapping of a log-warped endpoint axis (as in dfg_ggx.blut): node i lands on
    /// texel centre (i + ½)/N, the ends clamp, and t is ln(x/lo)/ln(hi/lo) by the closed form.
    #[test]
    fn mapping_puts_nodes_on_texel_centres() {
        let m = Mapping::from_json(&serde_json::json!({
            "lo": 0.0174524064372835, "hi": 1.0, "count": 64,
            "warp": "log", "placement": "endpoint"
        }))
        .unwrap();
        for i in 0..64 {
            let u = m.coord(m.node(i));
            assert!((u - (i as f64 + 0.5) / 64.0).abs() < 1e-12, "{i}: {u}");
        }
        assert_eq!(m.coord(0.0), 0.5 / 64.0);
        assert_eq!(m.coord(1.5), 63.5 / 64.0);
        let x = 0.1;
        let t = (x / 0.0174524064372835f64).ln() / (1.0 / 0.0174524064372835f64).ln();
        assert!((m.t(x) - t).abs() < 1e-15);
        let c = Mapping::from_json(&serde_json::json!({
            "lo": 0.0, "hi": 2.0, "count": 8, "warp": "linear", "placement": "texel-centre"
        }))
        .unwrap();
        assert!((c.node(3) - 2.0 * 3.5 / 8.0).abs() < 1e-15);
        assert!((c.coord(c.node(3)) - 3.5 / 8.0).abs() < 1e-15);
        assert!(Mapping::from_json(&serde_json::json!({
            "lo": 0.0, "hi": 1.0, "count": 8, "warp": "cubic", "placement": "endpoint"
        }))
        .is_err());
    }
}
