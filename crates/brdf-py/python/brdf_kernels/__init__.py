"""brdf_kernels: the brdf-kernels reflection models for Python and NumPy.

Exact microfacet geometric attenuation factors (the modified G of *Acta Physica Sinica* 64,
184213 (2015), Blinn's V-groove G, Smith's separable and height-correlated G), every model
of the Rust catalogue by name (evaluation, importance sampling, directional albedo) and BLUT
lookup tables (build from a spec, load, save, look up, and the split-sum texture of a game
engine in its own container: :func:`export_engine`). Every function broadcasts its array
arguments as NumPy does, accepts any shape and strides, and returns float32 when every
array argument is float32, float64 otherwise; the values equal the Rust kernels' bit for
bit. Bad arguments raise ``ValueError`` naming the argument and its range; an invalid table
raises :class:`LutError`.
"""

from ._native import (
    LutError,
    Table,
    __version__,
    albedo,
    build_table,
    eval,
    export_engine,
    g_blinn,
    g_blinn_dots,
    g_modified,
    g_modified_dots,
    g_modified_vectors,
    g_smith_correlated,
    g_smith_separable,
    models,
    sample,
)

__all__ = [
    "LutError",
    "Table",
    "__version__",
    "albedo",
    "build_table",
    "eval",
    "export_engine",
    "g_blinn",
    "g_blinn_dots",
    "g_modified",
    "g_modified_dots",
    "g_modified_vectors",
    "g_smith_correlated",
    "g_smith_separable",
    "models",
    "sample",
]
