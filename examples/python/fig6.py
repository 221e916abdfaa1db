"""The paper's Fig. 6: G against θr at θi = 30°, σ = 0.3 (modified vs Blinn vs Smith).

The full ray-traced curve exists only as a drawing (docs/figures/fig6_*.svg); the two
ray-traced values at θi = 30°, σ = 0.3 that docs/validation.md prints as numbers (the
"Effect of a slope bin" table, conditioned estimator, ±1 SE) are plotted as points.
Run: python examples/python/fig6.py [out.png]
"""
import sys

import matplotlib.pyplot as plt
import numpy as np

import brdf_kernels as bk

sigma, ti = 0.3, np.radians(30.0)
tr = np.radians(np.linspace(-89, 89, 357))
plt.plot(np.degrees(tr), bk.g_modified(ti, tr, sigma), label="modified G (paper)")
plt.plot(np.degrees(tr), bk.g_blinn(ti, tr), label="Blinn V-groove")
m = np.sqrt(2) * sigma  # Beckmann width of Gaussian slopes
plt.plot(np.degrees(tr), bk.g_smith_correlated(np.cos(ti), np.cos(tr), m), label="Smith (height-correlated)")
plt.errorbar([60, 80], [0.9986, 0.8130], yerr=[0.0002, 0.0019], fmt="ko", label="ray-traced (docs/validation.md)")
plt.xlabel("θr (degrees)"), plt.ylabel("G"), plt.title("θi = 30°, σ = 0.3"), plt.legend()
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "fig6.png", dpi=120)
