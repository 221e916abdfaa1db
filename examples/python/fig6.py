"""The paper's Fig. 6: G against θr at θi = 30°, σ = 0.3 (modified vs Blinn vs Smith), with
the ray-traced truth of the validation crate: its in-plane cells of docs/validation-2d.json
(a 2-D Gaussian surface; φ = 180° is the forward side θr > 0) with ±2 SE bars, and the two
1-D-profile values docs/validation.md prints (conditioned estimator, ±1 SE).
Run from the repository root: python examples/python/fig6.py [out.png]
"""
import json, sys
import matplotlib.pyplot as plt
import numpy as np
import brdf_kernels as bk

sigma, ti = 0.3, np.radians(30.0)
tr = np.radians(np.linspace(-89, 89, 357))
plt.plot(np.degrees(tr), bk.g_modified(ti, tr, sigma), label="modified G (paper)")
plt.plot(np.degrees(tr), bk.g_blinn(ti, tr), label="Blinn V-groove")
plt.plot(np.degrees(tr), bk.g_smith_correlated(np.cos(ti), np.cos(tr), np.sqrt(2) * sigma), label="Smith (height-correlated, m = √2σ)")
sweep = next(s for s in json.load(open("docs/validation-2d.json"))["sweeps"] if s["sigma"] == sigma)
cells = [c for c in sweep["cells"] if c["theta_i"] == 30.0 and c["phi"] in (0.0, 180.0)]
x = [c["theta_o"] * (1 if c["phi"] == 180.0 else -1) for c in cells]
plt.errorbar(x, [c["g"] for c in cells], yerr=[2 * c["g_se"] for c in cells], fmt="ks", ms=3, label="ray-traced, 2-D surface (docs/validation-2d.json)")
plt.errorbar([60, 80], [0.9986, 0.8130], yerr=[0.0002, 0.0019], fmt="ro", label="ray-traced, 1-D profile (docs/validation.md)")
plt.xlabel("θr (degrees)"), plt.ylabel("G"), plt.title("θi = 30°, σ = 0.3"), plt.legend(fontsize=8)
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "fig6.png", dpi=120)
