/*
 * The brdf-kernels C example: evaluates the kernels and the embedded tables through the C
 * ABI (include/brdf.h, libbrdf_ffi.a) at fixed inputs, prints every input and result as
 * IEEE-754 bit patterns, and checks from C what bad input gives (null pointers, wrong
 * lengths, corrupt tables, non-finite input, unknown enum values, uninitialised handles).
 *
 * The same source runs on a Cortex-M4F under QEMU (mps2-an386, semihosting; startup.c and
 * mps2-an386.ld; newlib-nano for memcpy and memset only) and on the host. `cargo xtask cffi` builds both, runs them and compares
 * every value bit for bit with the host's Rust f32/f64 results.
 *
 * Output, one record per line:
 *   BRDF-C <abi version> <platform>
 *   TABLE <role> <file> <bytes> <fnv1a-32 of the bytes>
 *   R <kernel> <arg> ... = <value> ...      (f32 as 8 hex digits, f64 as 16, enums as u:<n>)
 *   CHECK <name> ok|FAIL
 *   STACK <peak bytes>                       (device only)
 *   END <results> <failed checks>
 * Exit status 0 when every check passed.
 */
#include "brdf.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifdef BRDF_DEVICE
#define PLATFORM "cortex-m4f"
/* startup.c: semihosting console output of a NUL-terminated string, and the stack peak. */
void startup_write0(const char *s);
size_t startup_stack_peak(void);
#else
#include <unistd.h>
#define PLATFORM "host"
#endif

/* The tables, embedded by tables.S (.incbin of the files in assets/). */
extern const uint8_t table_g[], table_g_end[];
extern const uint8_t table_dfg[], table_dfg_end[];
extern const uint8_t table_e[], table_e_end[];
extern const uint8_t table_eavg[], table_eavg_end[];

/* ---- output (no stdio: write(2) on the host, semihosting on the device) ---- */

static char line[256];
static size_t line_len;
static unsigned results, failed;

static void put(const char *s) {
    while (*s && line_len < sizeof line - 2) line[line_len++] = *s++;
}
static void flush_line(void) {
    line[line_len++] = '\n';
    line[line_len] = 0;
#ifdef BRDF_DEVICE
    startup_write0(line);
#else
    (void)!write(1, line, line_len);
#endif
    line_len = 0;
}
static void put_hex(uint64_t v, int digits) {
    char b[17];
    for (int i = digits - 1; i >= 0; i--) {
        b[i] = "0123456789abcdef"[v & 15];
        v >>= 4;
    }
    b[digits] = 0;
    put(b);
}
static void put_dec(uint64_t v) {
    char b[21];
    int i = 20;
    b[i] = 0;
    do {
        b[--i] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    put(&b[i]);
}
static uint32_t bits_f(float x) {
    uint32_t u;
    memcpy(&u, &x, 4);
    return u;
}
static uint64_t bits_d(double x) {
    uint64_t u;
    memcpy(&u, &x, 8);
    return u;
}
static void rec(const char *kernel) {
    put("R ");
    put(kernel);
    results++;
}
static void af(float x) {
    put(" ");
    put_hex(bits_f(x), 8);
}
static void ad(double x) {
    put(" ");
    put_hex(bits_d(x), 16);
}
static void au(uint32_t x) {
    put(" u:");
    put_dec(x);
}
static void eq(void) { put(" ="); }

static void check(const char *name, int ok) {
    put("CHECK ");
    put(name);
    put(ok ? " ok" : " FAIL");
    flush_line();
    if (!ok) failed++;
}

static uint32_t fnv1a(const uint8_t *p, size_t n) {
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 16777619u;
    return h;
}
static void table_line(const char *role, const char *file, const uint8_t *p, size_t n) {
    put("TABLE ");
    put(role);
    put(" ");
    put(file);
    put(" ");
    put_dec(n);
    put(" ");
    put_hex(fnv1a(p, n), 8);
    flush_line();
}

static int is_nan_f(float x) { return x != x; }
static int is_nan_d(double x) { return x != x; }
static int same_f(float a, float b) { return bits_f(a) == bits_f(b); }

/* ---- inputs ---- */

#define DEG (3.14159265358979f / 180.0f)
static const float SIGMAS[] = {0.1f, 0.3f, 0.6f, 1.0f};
/* In-plane (theta_i, theta_r) in degrees, theta_r signed. */
static const float ANGLES[][2] = {{0, 0}, {30, 30}, {30, -60}, {60, 75}, {80, -80}, {45, 10}};
/* (n.wi, n.wo, wi.wo) of unit-vector pairs above the surface. */
static const float DOTS[][3] = {{0.9f, 0.7f, 0.5f}, {0.5f, 0.5f, 0.2f},  {0.3f, 0.95f, 0.1f},
                                {1.0f, 0.6f, 0.6f}, {0.2f, 0.2f, -0.9f}, {0.7f, 0.7f, 0.96f}};
/* n.h = (n.wi + n.wo)/sqrt(2 + 2 wi.wo) for each row of DOTS (rows as f32), as a shader
 * would pass it. */
static const double DOTS_NH[] = {0.9237604100557466, 0.645497223566348, 0.8427498275082367, 0.8944271976639177, 0.8944270977039072, 0.7071067730152197};
/* Local-frame unit (wi, wo) pairs. */
static const float DIRS[][2][3] = {
    {{0.5f, 0.0f, 0.8660254f}, {-0.5f, 0.0f, 0.8660254f}},
    {{0.66446304f, 0.24184476f, 0.70710677f}, {-0.6040228f, -0.21984631f, 0.76604444f}},
    {{0.0f, 0.8660254f, 0.5f}, {-0.11697778f, -0.32139382f, 0.9396926f}},
    {{0.6830127f, 0.6830127f, 0.25881904f}, {-0.6830127f, -0.6830127f, 0.25881904f}},
};
/* (mu, roughness) for the split-sum and albedo tables. */
static const float MU_R[][2] = {{0.05f, 0.1f}, {0.3f, 0.25f}, {0.5f, 0.5f},
                                {0.8f, 0.75f}, {1.0f, 1.0f},  {0.62f, 0.33f}};
#define N_OF(a) (sizeof(a) / sizeof((a)[0]))

/* ---- kernels ---- */

static void kernels(void) {
    int g_ok = 1, recip_ok = 1;
    for (size_t s = 0; s < N_OF(SIGMAS); s++) {
        for (uint32_t conv = 0; conv < 2; conv++) {
            BrdfModifiedGF32 g;
            if (brdf_modified_g_init_f32(&g, SIGMAS[s], conv) != BRDF_STATUS_OK) g_ok = 0;
            for (size_t k = 0; k < N_OF(ANGLES); k++) {
                float ti = ANGLES[k][0] * DEG, tr = ANGLES[k][1] * DEG;
                BrdfGTermsF32 t = brdf_modified_g_terms_f32(&g, ti, tr);
                rec("mg_terms_f32"), af(SIGMAS[s]), au(conv), af(ti), af(tr), eq();
                af(t.gm), af(t.gs), af(t.g), flush_line();
                g_ok &= t.g >= 0.0f && t.g <= 1.0f && (same_f(t.g, t.gm) || same_f(t.g, t.gs));
            }
            for (size_t k = 0; k < N_OF(DOTS); k++) {
                float a = DOTS[k][0], b = DOTS[k][1], c = DOTS[k][2];
                BrdfGTermsF32 t = brdf_modified_g_terms_dots_f32(&g, a, b, c);
                rec("mg_terms_dots_f32"), af(SIGMAS[s]), au(conv), af(a), af(b), af(c), eq();
                af(t.gm), af(t.gs), af(t.g), flush_line();
                if (conv == BRDF_CONVENTION_RECIPROCAL)
                    recip_ok &= same_f(t.g, brdf_modified_g_dots_f32(&g, b, a, c));
            }
            /* The paper's M is exactly 1 at normal incidence (eq 6 with theta = 0). */
            g_ok &= brdf_modified_g_f32(&g, 0.0f, 0.0f) == 1.0f;
        }
    }
    check("modified_g_range_and_normal_incidence", g_ok);
    check("modified_g_dots_reciprocal", recip_ok);

    for (size_t s = 1; s < 3; s++) {
        BrdfModifiedGF64 g;
        brdf_modified_g_init_f64(&g, (double)SIGMAS[s], BRDF_CONVENTION_RECIPROCAL);
        for (size_t k = 0; k < N_OF(ANGLES); k++) {
            double ti = (double)(ANGLES[k][0] * DEG), tr = (double)(ANGLES[k][1] * DEG);
            BrdfGTermsF64 t = brdf_modified_g_terms_f64(&g, ti, tr);
            rec("mg_terms_f64"), ad((double)SIGMAS[s]), au(0), ad(ti), ad(tr), eq();
            ad(t.gm), ad(t.gs), ad(t.g), flush_line();
        }
    }

    int blinn_ok = 1;
    for (size_t k = 0; k < N_OF(ANGLES); k++) {
        float ti = ANGLES[k][0] * DEG, tr = ANGLES[k][1] * DEG;
        float v = brdf_g_blinn_f32(ti, tr);
        rec("blinn_f32"), af(ti), af(tr), eq(), af(v), flush_line();
        blinn_ok &= v >= 0.0f && v <= 1.0f;
    }
    for (size_t k = 0; k < N_OF(DOTS); k++) {
        float v = brdf_g_blinn_dots_f32(DOTS[k][0], DOTS[k][1], DOTS[k][2]);
        rec("blinn_dots_f32"), af(DOTS[k][0]), af(DOTS[k][1]), af(DOTS[k][2]), eq(), af(v);
        flush_line();
    }
    /* Eq 4 at the mirror direction: n.h = 1, so G = min(1, 2 cos / cos) = 1. */
    blinn_ok &= brdf_g_blinn_f32(30 * DEG, 30 * DEG) == 1.0f;
    check("blinn_range_and_mirror", blinn_ok);

    for (uint32_t d = 0; d < 2; d++) {
        for (size_t k = 0; k < N_OF(DOTS); k++) {
            float r = 0.1f + 0.2f * (float)k;
            float g1 = brdf_g1_smith_f32(d, DOTS[k][0], r);
            rec("g1_smith_f32"), au(d), af(DOTS[k][0]), af(r), eq(), af(g1), flush_line();
            for (uint32_t f = 0; f < 2; f++) {
                float g = brdf_g_smith_f32(d, f, DOTS[k][0], DOTS[k][1], r);
                rec("g_smith_f32"), au(d), au(f), af(DOTS[k][0]), af(DOTS[k][1]), af(r), eq();
                af(g), flush_line();
            }
        }
    }

    /* Torrance-Sparrow with every G and every Fresnel choice. */
    static const struct {
        uint32_t g, f;
        float p;
    } TS[] = {{BRDF_GEOMETRIC_MODIFIED, BRDF_FRESNEL_SCHLICK, 0.04f},
              {BRDF_GEOMETRIC_MODIFIED_PRINTED, BRDF_FRESNEL_ONE, 0.0f},
              {BRDF_GEOMETRIC_BLINN, BRDF_FRESNEL_DIELECTRIC, 1.5f},
              {BRDF_GEOMETRIC_SMITH_SEPARABLE, BRDF_FRESNEL_SCHLICK_IOR, 1.33f},
              {BRDF_GEOMETRIC_SMITH_CORRELATED, BRDF_FRESNEL_SCHLICK, 0.9f},
              {BRDF_GEOMETRIC_NONE, BRDF_FRESNEL_DIELECTRIC, 0.7f}};
    int ts_ok = 1;
    for (size_t j = 0; j < N_OF(TS); j++) {
        float sigma = SIGMAS[j % 3], ks = 1.0f, albedo = 0.2f;
        BrdfTorranceSparrowF32 ts;
        ts_ok &= brdf_torrance_sparrow_init_f32(&ts, sigma, TS[j].g, TS[j].f, TS[j].p, ks,
                                                albedo) == BRDF_STATUS_OK;
        BrdfTorranceSparrowF64 ts64;
        ts_ok &= brdf_torrance_sparrow_init_f64(&ts64, (double)sigma, TS[j].g, TS[j].f,
                                                (double)TS[j].p, (double)ks,
                                                (double)albedo) == BRDF_STATUS_OK;
        for (size_t k = 0; k < N_OF(DOTS); k++) {
            float a = DOTS[k][0], b = DOTS[k][1], c = DOTS[k][2];
            /* With n.h as a shader has it as well: the same BRDF where the three dots are
             * well conditioned (f32 within 1e-4, f64 within 1e-9 relative). */
            float nh = (float)DOTS_NH[k];
            float f = brdf_torrance_sparrow_eval_f32(&ts, a, b, c);
            float sp = brdf_torrance_sparrow_specular_f32(&ts, a, b, c);
            float fh = brdf_torrance_sparrow_eval_nh_f32(&ts, a, b, c, nh);
            rec("ts_f32"), af(sigma), au(TS[j].g), au(TS[j].f), af(TS[j].p), af(ks), af(albedo);
            af(a), af(b), af(c), af(nh), eq(), af(f), af(sp), af(fh), flush_line();
            ts_ok &= f >= sp && sp >= 0.0f;
            float df = fh - f, af_ = f < 0.0f ? -f : f;
            ts_ok &= (df < 0.0f ? -df : df) <= 1e-4f * af_;
            double nh64 = DOTS_NH[k];
            double f64 = brdf_torrance_sparrow_eval_f64(&ts64, (double)a, (double)b, (double)c);
            double sp64 =
                brdf_torrance_sparrow_specular_f64(&ts64, (double)a, (double)b, (double)c);
            double fh64 =
                brdf_torrance_sparrow_eval_nh_f64(&ts64, (double)a, (double)b, (double)c, nh64);
            rec("ts_f64"), ad((double)sigma), au(TS[j].g), au(TS[j].f), ad((double)TS[j].p);
            ad((double)ks), ad((double)albedo), ad((double)a), ad((double)b), ad((double)c);
            ad(nh64), eq(), ad(f64), ad(sp64), ad(fh64), flush_line();
            double dd = fh64 - f64, ad_ = f64 < 0.0 ? -f64 : f64;
            ts_ok &= (dd < 0.0 ? -dd : dd) <= 1e-9 * ad_;
        }
    }
    check("torrance_sparrow_init_and_lobe", ts_ok);

    /* Directional albedo: one Smith-masked Torrance-Sparrow surface and one GGX surface (the
     * quadrature takes ~4e5 evaluations). Energy: R <= 1 for Smith G with F <= 1 and
     * k_s = 1 plus rho_d = 0. */
    {
        BrdfTorranceSparrowF32 ts;
        brdf_torrance_sparrow_init_f32(&ts, 0.3f, BRDF_GEOMETRIC_SMITH_CORRELATED,
                                       BRDF_FRESNEL_ONE, 0.0f, 1.0f, 0.0f);
        float r = brdf_torrance_sparrow_albedo_f32(&ts, 0.7f);
        rec("ts_albedo_f32"), af(0.3f), au(BRDF_GEOMETRIC_SMITH_CORRELATED);
        au(BRDF_FRESNEL_ONE), af(0.0f), af(1.0f), af(0.0f), af(0.7f), eq(), af(r);
        flush_line();
        check("ts_albedo_in_0_1", r > 0.5f && r <= 1.0f);
    }

    int ggx_ok = 1;
    BrdfRgbF32 f0 = {0.95f, 0.64f, 0.54f};
    for (uint32_t form = 0; form < 2; form++) {
        BrdfGgxF32 g;
        ggx_ok &= brdf_ggx_init_f32(&g, f0, 0.3f, form) == BRDF_STATUS_OK;
        for (size_t k = 0; k < N_OF(DIRS); k++) {
            BrdfVec3F32 wi = {DIRS[k][0][0], DIRS[k][0][1], DIRS[k][0][2]};
            BrdfVec3F32 wo = {DIRS[k][1][0], DIRS[k][1][1], DIRS[k][1][2]};
            BrdfRgbF32 c = brdf_ggx_eval_f32(&g, wi, wo);
            rec("ggx_f32"), af(f0.r), af(f0.g), af(f0.b), af(0.3f), au(form);
            af(wi.x), af(wi.y), af(wi.z), af(wo.x), af(wo.y), af(wo.z), eq();
            af(c.r), af(c.g), af(c.b), flush_line();
            ggx_ok &= c.r >= c.g && c.g >= c.b && c.b >= 0.0f;
        }
        if (form == BRDF_SMITH_FORM_CORRELATED) {
            BrdfRgbF32 e = brdf_ggx_albedo_f32(&g, 0.5f);
            rec("ggx_albedo_f32"), af(f0.r), af(f0.g), af(f0.b), af(0.3f), au(form), af(0.5f);
            eq(), af(e.r), af(e.g), af(e.b), flush_line();
            ggx_ok &= e.r <= 1.0f && e.b > 0.0f;
        }
    }
    check("ggx_channels_ordered_and_albedo", ggx_ok);
}

/* ---- rough dielectric BSDF ---- */

/* Unit (wi, wo) pairs over the whole sphere: a mirror reflection pair, wi inside (light
 * transmitted up to the viewer), wo inside (light transmitted down), an off-plane pair. */
static const float RD_DIRS[][2][3] = {
    {{0.5f, 0.0f, 0.8660254f}, {-0.5f, 0.0f, 0.8660254f}},
    {{0.3f, 0.1f, -0.9486833f}, {-0.5f, 0.0f, 0.8660254f}},
    {{-0.5f, 0.0f, 0.8660254f}, {0.2f, 0.0f, -0.9797959f}},
    {{0.6830127f, 0.6830127f, 0.25881904f}, {-0.6040228f, -0.21984631f, 0.76604444f}},
};
/* (alpha, eta): air over glass, and glass over air (eta = 1/1.5). */
static const float RD_PARAMS[][2] = {{0.3f, 1.5f}, {0.5f, 0.6666667f}};

static BrdfVec3F32 v3(const float *p) {
    BrdfVec3F32 v = {p[0], p[1], p[2]};
    return v;
}
static float rel_f(float a, float b) {
    float d = a - b, m = a > b ? a : b;
    return (d < 0 ? -d : d) / (m > 1e-30f ? m : 1e-30f);
}

/* Values for the bit-exact comparison, plus the generalised reciprocity f*(wi, wo) =
 * f(wo, wi) (Walter et al. 2007 sec. 5.2; both sides are separate f32 evaluations, so
 * 1e-5 relative allows a few roundings) and the sampler's pdf equal to the pdf export. */
static void rough_dielectric_values(void) {
    int ok = 1, recip = 1, pdf_ok = 1;
    for (uint32_t d = 0; d < 2; d++) {
        for (size_t q = 0; q < N_OF(RD_PARAMS); q++) {
            float a = RD_PARAMS[q][0], eta = RD_PARAMS[q][1];
            BrdfRoughDielectricF32 m;
            ok &= brdf_rough_dielectric_init_f32(&m, d, a, eta) == BRDF_STATUS_OK;
            for (size_t k = 0; k < N_OF(RD_DIRS); k++) {
                BrdfVec3F32 wi = v3(RD_DIRS[k][0]), wo = v3(RD_DIRS[k][1]);
                float f = brdf_rough_dielectric_eval_f32(&m, wi, wo);
                float fa = brdf_rough_dielectric_eval_adjoint_f32(&m, wi, wo);
                float p = brdf_rough_dielectric_pdf_f32(&m, wo, wi);
                rec("rd_f32"), au(d), af(a), af(eta);
                af(wi.x), af(wi.y), af(wi.z), af(wo.x), af(wo.y), af(wo.z), eq();
                af(f), af(fa), af(p), flush_line();
                ok &= f > 0.0f && p >= 0.0f;
                recip &= rel_f(fa, brdf_rough_dielectric_eval_f32(&m, wo, wi)) < 1e-5f;
            }
            BrdfVec3F32 wo = v3(RD_DIRS[3][1]);
            for (int k = 0; k < 4; k++) {
                float u0 = 0.15f + 0.23f * k, u1 = 0.8f - 0.19f * k, uc = 0.02f + 0.3f * k;
                BrdfBsdfSampleF32 s;
                int st = brdf_rough_dielectric_sample_f32(&m, wo, u0, u1, uc, &s);
                ok &= st == BRDF_STATUS_OK;
                if (st != BRDF_STATUS_OK) continue;
                rec("rd_sample_f32"), au(d), af(a), af(eta), af(wo.x), af(wo.y), af(wo.z);
                af(u0), af(u1), af(uc), eq(), af(s.wi.x), af(s.wi.y), af(s.wi.z), af(s.pdf);
                af(s.weight.r), af(s.weight.g), af(s.weight.b), flush_line();
                pdf_ok &= s.specular == 0 &&
                          same_f(s.pdf, brdf_rough_dielectric_pdf_f32(&m, wo, s.wi));
            }
        }
    }
    BrdfRoughDielectricF64 m64;
    BrdfVec3F64 wi = {0.3, 0.1, -0.9486832980505138}, wo = {-0.5, 0.0, 0.8660254037844386};
    ok &= brdf_rough_dielectric_init_f64(&m64, 1, 0.3, 1.5) == BRDF_STATUS_OK;
    double f = brdf_rough_dielectric_eval_f64(&m64, wi, wo);
    rec("rd_f64"), au(1), ad(0.3), ad(1.5), ad(wi.x), ad(wi.y), ad(wi.z), ad(wo.x), ad(wo.y);
    ad(wo.z), eq(), ad(f), flush_line();
    check("rough_dielectric_values", ok && f > 0.0);
    check("rough_dielectric_generalised_reciprocity", recip);
    check("rough_dielectric_sample_pdf", pdf_ok);
}

/* Closed form: at normal incidence on a smooth interface (alpha 0, raised to the 1e-4 floor)
 * the reflected fraction is the Fresnel reflectance R0 = ((eta - 1)/(eta + 1))^2 and, in
 * the radiance convention, eta^2 times the transmitted integral is 1 - R0. Estimated with
 * N samples whose choice numbers are stratified, uc = (k + 1/2)/N: each estimate is a count
 * over N (weights G1 = 1 to f32 at the floor), within 1/(2N) of the exact fraction, so
 * |E_r - R0| <= 1/N; the sum adds only f32 rounding (1e-4). */
static void rough_dielectric_energy(void) {
    const int n = 1024;
    const float eta = 1.5f, r0 = (eta - 1.0f) * (eta - 1.0f) / ((eta + 1.0f) * (eta + 1.0f));
    BrdfRoughDielectricF32 m;
    int ok = brdf_rough_dielectric_init_f32(&m, BRDF_DIELECTRIC_DISTRIBUTION_GGX, 0.0f, eta) ==
             BRDF_STATUS_OK;
    BrdfVec3F32 wo = {0.0f, 0.0f, 1.0f};
    float er = 0.0f, et = 0.0f;
    for (int k = 0; k < n; k++) {
        float g = 0.61803398875f * (float)k;
        float u0 = g - (float)(int)g, u1 = ((float)k + 0.25f) / (float)n;
        BrdfBsdfSampleF32 s;
        ok &= brdf_rough_dielectric_sample_f32(&m, wo, u0, u1, ((float)k + 0.5f) / (float)n,
                                               &s) == BRDF_STATUS_OK;
        if (s.wi.z > 0.0f) er += s.weight.r; else et += s.weight.r;
    }
    er /= (float)n, et /= (float)n;
    float de = er - r0, dt = er + eta * eta * et - 1.0f;
    check("rough_dielectric_normal_incidence_fresnel",
          ok && de < 1.0f / n && -de < 1.0f / n && dt < 1e-4f && -dt < 1e-4f);
}

/* ---- tables ---- */

static void tables(void) {
    size_t ng = (size_t)(table_g_end - table_g), nd = (size_t)(table_dfg_end - table_dfg);
    size_t ne = (size_t)(table_e_end - table_e), na = (size_t)(table_eavg_end - table_eavg);
    table_line("g", "g_modified_sigma0.3.blut", table_g, ng);
    table_line("dfg", "dfg_ggx.blut", table_dfg, nd);
    table_line("e", "kc_e_ggx.blut", table_e, ne);
    table_line("eavg", "kc_eavg_ggx.blut", table_eavg, na);

    BrdfGTable g;
    BrdfDfgTable d;
    BrdfAlbedoTable e;
    BrdfAverageAlbedoTable a;
    int ok = brdf_g_table_parse(&g, table_g, ng) == BRDF_STATUS_OK;
    ok &= brdf_dfg_table_parse(&d, table_dfg, nd) == BRDF_STATUS_OK;
    ok &= brdf_albedo_table_parse(&e, table_e, ne) == BRDF_STATUS_OK;
    ok &= brdf_average_albedo_table_parse(&a, table_eavg, na) == BRDF_STATUS_OK;
    ok &= brdf_g_table_sigma(&g) == 0.3f;
    check("tables_parse", ok);

    float ti[N_OF(ANGLES)], tr[N_OF(ANGLES)], gb[N_OF(ANGLES)];
    int batch_ok = 1;
    for (size_t k = 0; k < N_OF(ANGLES); k++) {
        ti[k] = ANGLES[k][0] * DEG;
        tr[k] = ANGLES[k][1] * DEG;
        BrdfGTermsF32 t = brdf_g_table_terms(&g, ti[k], tr[k]);
        rec("g_table"), af(ti[k]), af(tr[k]), eq(), af(t.gm), af(t.gs), af(t.g), flush_line();
    }
    for (size_t k = 0; k < N_OF(DOTS); k++) {
        float v = brdf_g_table_g_dots(&g, DOTS[k][0], DOTS[k][1], DOTS[k][2]);
        rec("g_table_dots"), af(DOTS[k][0]), af(DOTS[k][1]), af(DOTS[k][2]), eq(), af(v);
        flush_line();
        ok &= v >= 0.0f && v <= 1.0f;
    }
    batch_ok &= brdf_g_table_g_batch(&g, ti, tr, gb, N_OF(ANGLES)) == BRDF_STATUS_OK;
    for (size_t k = 0; k < N_OF(ANGLES); k++)
        batch_ok &= same_f(gb[k], brdf_g_table_g(&g, ti[k], tr[k]));
    /* In place: out aliases theta_i. */
    batch_ok &= brdf_g_table_g_batch(&g, ti, tr, ti, N_OF(ANGLES)) == BRDF_STATUS_OK;
    for (size_t k = 0; k < N_OF(ANGLES); k++) batch_ok &= same_f(gb[k], ti[k]);

    float mu[N_OF(MU_R)], r[N_OF(MU_R)], ab[2][N_OF(MU_R)], eb[N_OF(MU_R)], avb[N_OF(MU_R)];
    for (size_t k = 0; k < N_OF(MU_R); k++) {
        mu[k] = MU_R[k][0];
        r[k] = MU_R[k][1];
        BrdfDfgF32 v = brdf_dfg_table_ab(&d, mu[k], r[k]);
        rec("dfg"), af(mu[k]), af(r[k]), eq(), af(v.a), af(v.b), flush_line();
        float ev = brdf_albedo_table_e(&e, mu[k], r[k]);
        rec("e"), af(mu[k]), af(r[k]), eq(), af(ev), flush_line();
        float av = brdf_average_albedo_table_e_avg(&a, r[k]);
        rec("eavg"), af(r[k]), eq(), af(av), flush_line();
        /* Split sum with F0 = F90 = 1 is the albedo with F = 1; both within [0, 1]. */
        ok &= v.a >= 0.0f && v.b >= 0.0f && v.a + v.b <= 1.0f + 1e-3f;
        ok &= ev >= 0.0f && ev <= 1.0f + 1e-3f && av >= 0.0f && av <= 1.0f + 1e-3f;
    }
    batch_ok &= brdf_dfg_table_ab_batch(&d, mu, r, ab[0], ab[1], N_OF(MU_R)) == BRDF_STATUS_OK;
    batch_ok &= brdf_albedo_table_e_batch(&e, mu, r, eb, N_OF(MU_R)) == BRDF_STATUS_OK;
    batch_ok &= brdf_average_albedo_table_e_avg_batch(&a, r, avb, N_OF(MU_R)) == BRDF_STATUS_OK;
    for (size_t k = 0; k < N_OF(MU_R); k++) {
        BrdfDfgF32 v = brdf_dfg_table_ab(&d, mu[k], r[k]);
        batch_ok &= same_f(ab[0][k], v.a) && same_f(ab[1][k], v.b);
        batch_ok &= same_f(eb[k], brdf_albedo_table_e(&e, mu[k], r[k]));
        batch_ok &= same_f(avb[k], brdf_average_albedo_table_e_avg(&a, r[k]));
    }
    check("tables_values_in_range", ok);
    check("tables_batch_equals_single_and_in_place", batch_ok);
}

/* ---- bad input, from C ---- */

static void bad_input(void) {
    const float nan = __builtin_nanf(""), inf = __builtin_inff();
    BrdfModifiedGF32 g;
    BrdfModifiedGF32 zero_g;
    memset(&zero_g, 0, sizeof zero_g);

    check("init_null_out", brdf_modified_g_init_f32(NULL, 0.3f, 0) == BRDF_STATUS_NULL_POINTER);
    check("init_sigma_nan", brdf_modified_g_init_f32(&g, nan, 0) == BRDF_STATUS_INVALID_ARGUMENT);
    check("failed_init_leaves_handle_unusable", is_nan_f(brdf_modified_g_f32(&g, 0.1f, 0.2f)));
    check("init_sigma_inf", brdf_modified_g_init_f32(&g, inf, 0) == BRDF_STATUS_INVALID_ARGUMENT);
    check("init_sigma_zero", brdf_modified_g_init_f32(&g, 0.0f, 0) == BRDF_STATUS_INVALID_ARGUMENT);
    check("init_sigma_negative",
          brdf_modified_g_init_f32(&g, -0.3f, 0) == BRDF_STATUS_INVALID_ARGUMENT);
    check("init_unknown_convention",
          brdf_modified_g_init_f32(&g, 0.3f, 7) == BRDF_STATUS_INVALID_ARGUMENT);
    check("query_zeroed_handle", is_nan_f(brdf_modified_g_f32(&zero_g, 0.1f, 0.2f)));
    check("query_null_handle", is_nan_f(brdf_modified_g_terms_f32(NULL, 0.1f, 0.2f).gs));
    check("query_null_handle_f64", is_nan_d(brdf_modified_g_f64(NULL, 0.1, 0.2)));

    brdf_modified_g_init_f32(&g, 0.3f, BRDF_CONVENTION_RECIPROCAL);
    check("angle_nan", is_nan_f(brdf_modified_g_f32(&g, nan, 0.2f)) &&
                           is_nan_f(brdf_modified_g_f32(&g, 0.2f, nan)));
    /* Out-of-range and infinite angles are clamped to [0, pi/2] x [-pi/2, pi/2]. */
    check("angle_inf_clamped",
          same_f(brdf_modified_g_f32(&g, inf, -inf), brdf_modified_g_f32(&g, 2.0f, -2.0f)) &&
              same_f(brdf_modified_g_f32(&g, -inf, 0.5f), brdf_modified_g_f32(&g, 0.0f, 0.5f)));
    check("dots_nonfinite", is_nan_f(brdf_modified_g_dots_f32(&g, inf, 0.5f, 0.1f)) &&
                                is_nan_f(brdf_modified_g_dots_f32(&g, 0.5f, nan, 0.1f)));
    check("dots_below_horizon", brdf_modified_g_dots_f32(&g, -0.2f, 0.5f, 0.1f) == 0.0f);
    {
        float a[2] = {0.5f, 0.7f}, o[2];
        check("batch_uninitialised",
              brdf_modified_g_dots_batch_f32(&zero_g, a, a, a, o, 2) ==
                  BRDF_STATUS_NOT_INITIALISED);
        check("batch_null_array",
              brdf_modified_g_dots_batch_f32(&g, a, NULL, a, o, 2) == BRDF_STATUS_NULL_POINTER);
        check("batch_empty_null_ok",
              brdf_modified_g_dots_batch_f32(&g, NULL, NULL, NULL, NULL, 0) == BRDF_STATUS_OK);
        check("batch_huge_n", brdf_modified_g_dots_batch_f32(&g, a, a, a, o, SIZE_MAX) ==
                                  BRDF_STATUS_BAD_LENGTH);
    }
    /* A handle of another type is refused. */
    {
        BrdfGgxF32 gx;
        BrdfRgbF32 f0 = {0.04f, 0.04f, 0.04f};
        brdf_ggx_init_f32(&gx, f0, 0.3f, BRDF_SMITH_FORM_CORRELATED);
        check("handle_of_other_type",
              is_nan_f(brdf_modified_g_f32((const BrdfModifiedGF32 *)(const void *)&gx, 0.1f,
                                           0.1f)));
        BrdfRgbF32 bad = {0.04f, nan, 0.04f};
        check("ggx_f0_nan", brdf_ggx_init_f32(&gx, bad, 0.3f, 0) == BRDF_STATUS_INVALID_ARGUMENT);
        f0.g = 1.5f;
        check("ggx_f0_above_1",
              brdf_ggx_init_f32(&gx, f0, 0.3f, 0) == BRDF_STATUS_INVALID_ARGUMENT);
        f0.g = 0.04f;
        check("ggx_alpha_zero", brdf_ggx_init_f32(&gx, f0, 0.0f, 0) == BRDF_STATUS_INVALID_ARGUMENT);
        check("ggx_unknown_form", brdf_ggx_init_f32(&gx, f0, 0.3f, 2) == BRDF_STATUS_INVALID_ARGUMENT);
        brdf_ggx_init_f32(&gx, f0, 0.3f, 0);
        BrdfVec3F32 up = {0, 0, 1}, bad_v = {inf, 0, 1}, below = {0.6f, 0, -0.8f};
        check("ggx_eval_nonfinite", is_nan_f(brdf_ggx_eval_f32(&gx, bad_v, up).g));
        check("ggx_eval_below_horizon", brdf_ggx_eval_f32(&gx, below, up).r == 0.0f);
        check("ggx_albedo_mu_nan_and_below",
              is_nan_f(brdf_ggx_albedo_f32(&gx, nan).b) &&
                  brdf_ggx_albedo_f32(&gx, -0.5f).b == 0.0f);
    }
    {
        BrdfTorranceSparrowF32 ts;
        check("ts_unknown_fresnel", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, 9, 0.0f, 1.0f,
                                                                   0.0f) ==
                                        BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_unknown_g", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 6, 0, 0.0f, 1.0f, 0.0f) ==
                                  BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_r0_above_1", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, BRDF_FRESNEL_SCHLICK,
                                                              2.0f, 1.0f, 0.0f) ==
                                   BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_eta_zero", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, BRDF_FRESNEL_DIELECTRIC,
                                                            0.0f, 1.0f, 0.0f) ==
                                 BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_albedo_nan", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, 0, 0.0f, 1.0f, nan) ==
                                   BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_ks_inf", brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, 0, 0.0f, inf, 0.0f) ==
                               BRDF_STATUS_INVALID_ARGUMENT);
        check("ts_failed_init_unusable", is_nan_f(brdf_torrance_sparrow_eval_f32(&ts, 0.5f, 0.5f,
                                                                                 0.2f)));
        float a[1] = {0.5f}, o[1];
        check("ts_batch_uninitialised",
              brdf_torrance_sparrow_eval_batch_f32(&ts, a, a, a, o, 1) ==
                  BRDF_STATUS_NOT_INITIALISED);
        brdf_torrance_sparrow_init_f32(&ts, 0.3f, 4, 0, 0.0f, 1.0f, 0.0f);
        check("ts_eval_nonfinite",
              is_nan_f(brdf_torrance_sparrow_eval_f32(&ts, 0.5f, -inf, 0.2f)));
        check("ts_below_horizon", brdf_torrance_sparrow_eval_f32(&ts, 0.5f, -0.1f, 0.2f) == 0.0f);
    }
    {
        BrdfRoughDielectricF32 rd;
        BrdfBsdfSampleF32 s;
        BrdfDeltaLobeF32 dl;
        BrdfVec3F32 up = {0.0f, 0.0f, 1.0f}, down = {0.0f, 0.6f, -0.8f};
        BrdfVec3F32 grazing = {1.0f, 0.0f, 1e-30f}, bad_v = {nan, 0.0f, 1.0f};
        check("rd_unknown_distribution",
              brdf_rough_dielectric_init_f32(&rd, 2, 0.3f, 1.5f) == BRDF_STATUS_INVALID_ARGUMENT);
        check("rd_eta_out_of_range",
              brdf_rough_dielectric_init_f32(&rd, 0, 0.3f, 0.05f) ==
                      BRDF_STATUS_INVALID_ARGUMENT &&
                  brdf_rough_dielectric_init_f32(&rd, 0, 0.3f, nan) ==
                      BRDF_STATUS_INVALID_ARGUMENT);
        check("rd_alpha_bad",
              brdf_rough_dielectric_init_f32(&rd, 0, -0.1f, 1.5f) ==
                      BRDF_STATUS_INVALID_ARGUMENT &&
                  brdf_rough_dielectric_init_f32(&rd, 0, inf, 1.5f) ==
                      BRDF_STATUS_INVALID_ARGUMENT);
        check("rd_failed_init_unusable",
              is_nan_f(brdf_rough_dielectric_eval_f32(&rd, up, up)) &&
                  brdf_rough_dielectric_sample_f32(&rd, up, 0.5f, 0.5f, 0.5f, &s) ==
                      BRDF_STATUS_NOT_INITIALISED);
        check("rd_null_handle", is_nan_f(brdf_rough_dielectric_pdf_f32(NULL, up, up)) &&
                                    is_nan_d(brdf_rough_dielectric_eval_adjoint_f64(
                                        NULL, (BrdfVec3F64){0, 0, 1}, (BrdfVec3F64){0, 0, 1})));
        brdf_rough_dielectric_init_f32(&rd, 0, 0.3f, 1.5f);
        check("rd_eval_nonfinite", is_nan_f(brdf_rough_dielectric_eval_f32(&rd, bad_v, up)));
        check("rd_sample_null_out", brdf_rough_dielectric_sample_f32(&rd, up, 0.5f, 0.5f, 0.5f,
                                                                     NULL) ==
                                        BRDF_STATUS_NULL_POINTER);
        check("rd_sample_bad_input",
              brdf_rough_dielectric_sample_f32(&rd, down, 0.5f, 0.5f, 0.5f, &s) ==
                      BRDF_STATUS_INVALID_ARGUMENT &&
                  brdf_rough_dielectric_sample_f32(&rd, up, 0.5f, 0.5f, nan, &s) ==
                      BRDF_STATUS_INVALID_ARGUMENT);
        s.pdf = 7.0f;
        check("rd_sample_grazing_no_sample",
              brdf_rough_dielectric_sample_f32(&rd, grazing, 0.5f, 0.5f, 0.5f, &s) ==
                      BRDF_STATUS_NO_SAMPLE && s.pdf == 7.0f);
        check("rd_no_delta_for_eta_not_1",
              brdf_rough_dielectric_delta_f32(&rd, up, &dl) == BRDF_STATUS_OK && dl.prob == 0.0f);
        BrdfGgxF32 gx;
        brdf_ggx_init_f32(&gx, (BrdfRgbF32){0.5f, 0.5f, 0.5f}, 0.3f, 0);
        check("rd_handle_of_other_type",
              is_nan_f(brdf_rough_dielectric_eval_f32((const BrdfRoughDielectricF32 *)(void *)&gx,
                                                      up, up)));
        /* eta = 1: the interface is invisible; all light goes straight through. */
        brdf_rough_dielectric_init_f32(&rd, 1, 0.3f, 1.0f);
        BrdfVec3F32 wo = {0.6f, 0.0f, 0.8f};
        check("rd_eta_1_delta",
              brdf_rough_dielectric_delta_f32(&rd, wo, &dl) == BRDF_STATUS_OK &&
                  dl.prob == 1.0f && dl.reflectance.g == 1.0f && dl.wi.x == -0.6f &&
                  dl.wi.z == -0.8f && brdf_rough_dielectric_eval_f32(&rd, dl.wi, wo) == 0.0f &&
                  brdf_rough_dielectric_sample_f32(&rd, wo, 0.3f, 0.3f, 0.3f, &s) ==
                      BRDF_STATUS_OK &&
                  s.specular == 1 && s.wi.z == -0.8f && s.weight.r == 1.0f);
        check("rd_delta_null_out",
              brdf_rough_dielectric_delta_f32(&rd, wo, NULL) == BRDF_STATUS_NULL_POINTER);
    }
    check("smith_unknown_distribution", is_nan_f(brdf_g1_smith_f32(5, 0.5f, 0.3f)));
    check("smith_unknown_form", is_nan_f(brdf_g_smith_f32(0, 5, 0.5f, 0.5f, 0.3f)));
    check("smith_roughness_bad", is_nan_f(brdf_g1_smith_f32(1, 0.5f, 0.0f)) &&
                                     is_nan_f(brdf_g1_smith_f32(1, 0.5f, inf)) &&
                                     is_nan_f(brdf_g_smith_f64(0, 1, 0.5, 0.5, nan)));
    check("smith_below_horizon", brdf_g1_smith_f32(1, -0.5f, 0.3f) == 0.0f);
    check("blinn_nan", is_nan_f(brdf_g_blinn_f32(nan, 0.1f)) &&
                           is_nan_f(brdf_g_blinn_dots_f32(0.5f, inf, 0.1f)));

    /* Tables: a corrupt copy of the (small) average-albedo table in RAM. */
    size_t na = (size_t)(table_eavg_end - table_eavg);
    uint8_t buf[256];
    BrdfAverageAlbedoTable t;
    int fits = na <= sizeof buf;
    check("eavg_table_fits_scratch", fits);
    if (!fits) return;
    check("parse_null_bytes",
          brdf_average_albedo_table_parse(&t, NULL, na) == BRDF_STATUS_NULL_POINTER);
    check("parse_null_out",
          brdf_average_albedo_table_parse(NULL, table_eavg, na) == BRDF_STATUS_NULL_POINTER);
    check("parse_huge_len", brdf_average_albedo_table_parse(&t, table_eavg, SIZE_MAX) ==
                                BRDF_STATUS_BAD_LENGTH);
    check("parse_empty", brdf_average_albedo_table_parse(&t, table_eavg, 0) ==
                             BRDF_STATUS_TABLE_TRUNCATED);
    check("parse_truncated_header",
          brdf_average_albedo_table_parse(&t, table_eavg, 5) == BRDF_STATUS_TABLE_TRUNCATED);
    check("parse_truncated_payload", brdf_average_albedo_table_parse(&t, table_eavg, na - 1) ==
                                         BRDF_STATUS_TABLE_PAYLOAD_LENGTH);
    memcpy(buf, table_eavg, na);
    buf[na - 1] ^= 0x40; /* a payload bit */
    check("parse_corrupt_payload_checksum",
          brdf_average_albedo_table_parse(&t, buf, na) == BRDF_STATUS_TABLE_CHECKSUM);
    memcpy(buf, table_eavg, na);
    buf[0] ^= 0xff;
    check("parse_bad_magic", brdf_average_albedo_table_parse(&t, buf, na) ==
                                 BRDF_STATUS_TABLE_BAD_MAGIC);
    memcpy(buf, table_eavg, na);
    buf[4] = 0x7f; /* the version varint */
    check("parse_unsupported_version", brdf_average_albedo_table_parse(&t, buf, na) ==
                                           BRDF_STATUS_TABLE_UNSUPPORTED_VERSION);
    check("failed_parse_leaves_handle_unusable",
          is_nan_f(brdf_average_albedo_table_e_avg(&t, 0.5f)));
    memcpy(buf, table_eavg, na);
    check("parse_ok_from_ram", brdf_average_albedo_table_parse(&t, buf, na) == BRDF_STATUS_OK &&
                                   same_f(brdf_average_albedo_table_e_avg(&t, 0.4f),
                                          brdf_average_albedo_table_e_avg(&t, 0.4f)));
    check("eavg_nan_and_inf", is_nan_f(brdf_average_albedo_table_e_avg(&t, nan)) &&
                                  same_f(brdf_average_albedo_table_e_avg(&t, inf),
                                         brdf_average_albedo_table_e_avg(&t, 1e30f)));
    buf[na - 1] ^= 0x40;
    check("reparse_corrupt_invalidates",
          brdf_average_albedo_table_parse(&t, buf, na) == BRDF_STATUS_TABLE_CHECKSUM &&
              is_nan_f(brdf_average_albedo_table_e_avg(&t, 0.4f)));
    {
        BrdfGTable gt;
        size_t nd = (size_t)(table_dfg_end - table_dfg);
        check("parse_wrong_kind",
              brdf_g_table_parse(&gt, table_dfg, nd) == BRDF_STATUS_TABLE_WRONG_KIND);
        check("wrong_kind_unusable", is_nan_f(brdf_g_table_g(&gt, 0.1f, 0.1f)));
        float x[1] = {0.1f}, o[1];
        check("table_batch_uninitialised",
              brdf_g_table_g_batch(&gt, x, x, o, 1) == BRDF_STATUS_NOT_INITIALISED);
        BrdfGTable3 g3;
        size_t ng = (size_t)(table_g_end - table_g);
        check("parse_2d_as_3d_wrong_kind",
              brdf_g_table3_parse(&g3, table_g, ng) == BRDF_STATUS_TABLE_WRONG_KIND);
        float lo, hi;
        check("sigma_range_uninitialised",
              brdf_g_table3_sigma_range(&g3, &lo, &hi) == BRDF_STATUS_NOT_INITIALISED);
        BrdfDfgTable dt;
        brdf_dfg_table_parse(&dt, table_dfg, nd);
        check("dfg_batch_null", brdf_dfg_table_ab_batch(&dt, x, x, o, NULL, 1) ==
                                    BRDF_STATUS_NULL_POINTER);
        check("dfg_nan", is_nan_f(brdf_dfg_table_ab(&dt, nan, 0.5f).b));
    }
    int names_ok = 1;
    for (int s = -1; s < 20; s++) names_ok &= brdf_status_str(s) != NULL;
    check("status_names", names_ok);
    check("abi_version", brdf_abi_version() == BRDF_ABI_VERSION);
}

int main(void) {
    put("BRDF-C ");
    put_dec(brdf_abi_version());
    put(" " PLATFORM);
    flush_line();
    kernels();
    rough_dielectric_values();
    rough_dielectric_energy();
    tables();
    bad_input();
#ifdef BRDF_DEVICE
    put("STACK ");
    put_dec(startup_stack_peak());
    flush_line();
#endif
    put("END ");
    put_dec(results);
    put(" ");
    put_dec(failed);
    flush_line();
    return failed == 0 ? 0 : 1;
}
