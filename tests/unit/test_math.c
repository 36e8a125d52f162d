/* Unit tests for scenes/math/sm_vec.h, sm_mat.h, sm_view.h and sm_bounds.h.
 * Every function with a cglm twin is compared against cglm 0.8.8 (the oracle; never linked
 * into the program) on thousands of inputs from a fixed-seed splitmix64, and against
 * double-precision references where cglm is not exact enough or wrong.
 * Tolerances are in units of u = 2^-24 (float unit roundoff) times the size of what is
 * summed: the a-priori rounding bounds of Higham ("Accuracy and Stability of Numerical
 * Algorithms", ch. 3), a sum of n products within n u sum|a_i b_i|, so two implementations
 * within it differ by at most twice it. Each bound says where it comes from; all leave 2x
 * headroom. Boolean tests (culling, intersection) may disagree with a reference only where
 * the deciding quantity is within rounding of the boundary: such cases are counted, any
 * other disagreement fails. cglm's SSE code needs 16-byte alignment, so every array handed
 * to both libraries is declared with cglm's type. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include <cglm/cglm.h>

#include "scenes/math/sm_bounds.h"

#define U 0x1p-24                  /* float unit roundoff */
#define PI_D 3.14159265358979323846
#define N_DRAWS 4000               /* random draws per comparison */

/* >>rng: splitmix64 (Steele, Lea, Flood 2014), fixed seed per test ---------------------- */

typedef struct splitmix { uint64_t s; } splitmix;

static uint64_t splitmix_next(splitmix *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* uniform in [lo, hi) */
static float rnd(splitmix *r, float lo, float hi)
{
    double x = (double)(splitmix_next(r) >> 11) * 0x1p-53;
    return (float)(lo + (hi - lo) * x);
}

static void rnd_vec(splitmix *r, float *v, int n, float lo, float hi)
{
    for (int i = 0; i < n; i++)
        v[i] = rnd(r, lo, hi);
}

/* uniform direction */
static void rnd_unit3(splitmix *r, float v[3])
{
    double n2;
    do {
        rnd_vec(r, v, 3, -1.0f, 1.0f);
        n2 = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
    } while (n2 < 0.01 || n2 > 1.0);
    for (int i = 0; i < 3; i++)
        v[i] = (float)(v[i] / sqrt(n2));
}

/* >>checks ------------------------------------------------------------------------------ */

static void near_(double got, double want, double tol, const char *what, int line, int i)
{
    if (!(fabs(got - want) <= tol))
        fail_msg("line %d, draw %d, %s: got %.9g, want %.9g, |diff| %.3g > tol %.3g",
                 line, i, what, got, want, fabs(got - want), tol);
}
#define NEAR(got, want, tol, what, i) near_((got), (want), (tol), (what), __LINE__, (i))

static void expect_finite(const float *p, int n, const char *what)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(p[i]))
            fail_msg("%s: entry %d is %g", what, i, (double)p[i]);
}

/* equal as numbers (-0 == +0) */
static void expect_equal_(const float *got, const float *want, int n, const char *what, int line)
{
    for (int i = 0; i < n; i++)
        if (!(got[i] == want[i]))
            fail_msg("line %d, %s: entry %d is %.9g, want %.9g", line, what, i, (double)got[i],
                     (double)want[i]);
}
#define EXPECT_EQUAL(got, want, n, what) expect_equal_((got), (want), (n), (what), __LINE__)

/* Two evaluations of the same formula (e.g. into a separate and an aliased output): equal
 * unless the compiler contracts one call site into FMAs and not the other (GCC does that
 * only with -ffp-contract=fast, not in ISO C mode), hence 1e-5 of the largest entry. */
static void expect_close_(const float *got, const float *want, int n, const char *what, int line)
{
    double mx = 1.0;
    for (int i = 0; i < n; i++)
        mx = fmax(mx, fabs(want[i]));
    for (int i = 0; i < n; i++)
        if (!(fabs(got[i] - want[i]) <= 1e-5 * mx))
            fail_msg("line %d, %s: entry %d is %.9g, want %.9g", line, what, i, (double)got[i],
                     (double)want[i]);
}
#define EXPECT_CLOSE(got, want, n, what) expect_close_((got), (want), (n), (what), __LINE__)

static bool all_zero(const float *p, int n)
{
    for (int i = 0; i < n; i++)
        if (p[i] != 0.0f)
            return false;
    return true;
}

static bool all_nan(const float *p, int n)
{
    for (int i = 0; i < n; i++)
        if (!isnan(p[i]))
            return false;
    return true;
}

/* A boolean disagreeing with its reference is allowed only at the boundary: |margin| is
 * within `slack` (rounding of the deciding quantity). */
static void bool_agree_(bool got, bool want, double margin, double slack, int *near_boundary,
                        const char *what, int line, int i)
{
    if (got == want)
        return;
    if (fabs(margin) <= slack) {
        (*near_boundary)++;
        return;
    }
    fail_msg("line %d, draw %d, %s: got %d, want %d, margin %.6g (slack %.3g)",
             line, i, what, got, want, margin, slack);
}
#define BOOL_AGREE(got, want, margin, slack, nb, what, i) \
    bool_agree_((got), (want), (margin), (slack), (nb), (what), __LINE__, (i))

/* >>double references ------------------------------------------------------------------- */

/* Gauss-Jordan with partial pivoting in double on column-major n x n (n <= 4) floats.
 * Returns false for an exactly singular pivot. */
static bool ref_inverse(const float *m, int n, double *inv)
{
    double a[4][8];
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++) {
            a[r][c] = m[c * n + r];
            a[r][n + c] = r == c ? 1.0 : 0.0;
        }
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int r = k + 1; r < n; r++)
            if (fabs(a[r][k]) > fabs(a[p][k]))
                p = r;
        if (a[p][k] == 0.0)
            return false;
        for (int c = 0; c < 2 * n; c++) {
            double t = a[k][c];
            a[k][c] = a[p][c];
            a[p][c] = t;
        }
        double d = a[k][k];
        for (int c = 0; c < 2 * n; c++)
            a[k][c] /= d;
        for (int r = 0; r < n; r++) {
            if (r == k)
                continue;
            double f = a[r][k];
            for (int c = 0; c < 2 * n; c++)
                a[r][c] -= f * a[k][c];
        }
    }
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++)
            inv[c * n + r] = a[r][n + c];
    return true;
}

/* infinity norm (largest row sum) of a column-major n x n matrix */
static double norm_inf_f(const float *m, int n)
{
    double best = 0.0;
    for (int r = 0; r < n; r++) {
        double s = 0.0;
        for (int c = 0; c < n; c++)
            s += fabs(m[c * n + r]);
        best = fmax(best, s);
    }
    return best;
}

static double norm_inf_d(const double *m, int n)
{
    double best = 0.0;
    for (int r = 0; r < n; r++) {
        double s = 0.0;
        for (int c = 0; c < n; c++)
            s += fabs(m[c * n + r]);
        best = fmax(best, s);
    }
    return best;
}

static double max_abs_d(const double *m, int n)
{
    double best = 0.0;
    for (int i = 0; i < n; i++)
        best = fmax(best, fabs(m[i]));
    return best;
}

/* determinant (sign = true) or permanent of |m| (sign = false) by the Leibniz sum over
 * all permutations, in double; the permanent of |m| bounds every term of the determinant
 * formula, so it is the scale of the determinant's rounding error. */
static double leibniz(const float *m, int n, bool sign)
{
    static const int p3[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    double sum = 0.0;
    if (n == 3) {
        for (int k = 0; k < 6; k++) {
            double t = 1.0;
            for (int c = 0; c < 3; c++)
                t *= m[c * 3 + p3[k][c]];
            sum += sign ? (k < 3 ? t : -t) : fabs(t);
        }
        return sum;
    }
    /* n == 4: enumerate permutations by Heap's algorithm, tracking parity */
    int p[4] = {0, 1, 2, 3}, cnt[4] = {0, 0, 0, 0}, parity = 0, i = 0;
    for (;;) {
        double t = 1.0;
        for (int c = 0; c < 4; c++)
            t *= m[c * 4 + p[c]];
        sum += sign ? (parity ? -t : t) : fabs(t);
        while (i < 4 && cnt[i] >= i) {
            cnt[i] = 0;
            i++;
        }
        if (i >= 4)
            break;
        int j = (i % 2) ? cnt[i] : 0, tmp = p[j];
        p[j] = p[i];
        p[i] = tmp;
        parity ^= 1;
        cnt[i]++;
        i = 0;
    }
    return sum;
}

/* a random 4x4 with entries in [-1, 1] and condition number (inf norm) <= kmax */
static double rnd_mat4_cond(splitmix *r, mat4 m, double inv[16], double kmax)
{
    for (;;) {
        rnd_vec(r, &m[0][0], 16, -1.0f, 1.0f);
        if (!ref_inverse(&m[0][0], 4, inv))
            continue;
        double k = norm_inf_f(&m[0][0], 4) * norm_inf_d(inv, 4);
        if (k <= kmax)
            return k;
    }
}

/* a random affine T * R * S with scales in [0.1, 10] */
static void rnd_trs(splitmix *r, mat4 m)
{
    vec3 t, axis, s;
    mat4 tm, rm, sm;
    rnd_vec(r, t, 3, -50.0f, 50.0f);
    rnd_unit3(r, axis);
    for (int i = 0; i < 3; i++)
        s[i] = expf(rnd(r, logf(0.1f), logf(10.0f)));
    glm_translate_make(tm, t);
    glm_rotate_make(rm, rnd(r, -SM_PI, SM_PI), axis);
    glm_scale_make(sm, s);
    glm_mat4_mul(tm, rm, m);
    glm_mat4_mul(m, sm, m);
}

/* >>vec ------------------------------------------------------------------------------------ */

/* Componentwise ops do one rounding (lerp three) on operands of magnitude <= |a| + |b|,
 * like cglm: they must agree within 2 u (|a| + |b|) per component (lerp: 8 u). dot: a sum
 * of n products, n u sum|a_i b_i| per implementation, tolerance 2 * 4 u * sum. norm:
 * relative (n/2 + 1) u each, 8 u used. normalize: unit result, 8 u per component. */
static void test_vec_ops_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed0001u};
    for (int i = 0; i < N_DRAWS; i++) {
        vec4 a, b, got, want;
        float s = rnd(&r, -10.0f, 10.0f);
        float scale = (float)pow(10.0, rnd(&r, -3.0f, 3.0f));
        rnd_vec(&r, a, 4, -scale, scale);
        rnd_vec(&r, b, 4, -scale, scale);
        for (int n = 3; n <= 4; n++) {
            double tol[4], sab = 0.0;
            for (int k = 0; k < n; k++) {
                tol[k] = 2.0 * U * (fabs(a[k]) + fabs(b[k]));
                sab += fabs((double)a[k] * b[k]);
            }
#define CMP(what, fsm, fglm, tolk)                                                  \
    do {                                                                             \
        fsm;                                                                         \
        fglm;                                                                        \
        for (int k = 0; k < n; k++)                                                  \
            NEAR(got[k], want[k], (tolk), what, i);                                  \
    } while (0)
            if (n == 3) {
                CMP("vec3_add", sm_vec3_add(a, b, got), glm_vec3_add(a, b, want), tol[k]);
                CMP("vec3_sub", sm_vec3_sub(a, b, got), glm_vec3_sub(a, b, want), tol[k]);
                CMP("vec3_scale", sm_vec3_scale(a, s, got), glm_vec3_scale(a, s, want),
                    2.0 * U * fabs(a[k] * s));
                CMP("vec3_min", sm_vec3_min(a, b, got), glm_vec3_minv(a, b, want), 0.0);
                CMP("vec3_max", sm_vec3_max(a, b, got), glm_vec3_maxv(a, b, want), 0.0);
                CMP("vec3_negate", (sm_vec3_copy(a, got), sm_vec3_negate(got)),
                    glm_vec3_negate_to(a, want), 0.0);
                CMP("vec3_normalize_to", sm_vec3_normalize_to(a, got),
                    glm_vec3_normalize_to(a, want), 8.0 * U);
                CMP("vec3_copy", sm_vec3_copy(a, got), glm_vec3_copy(a, want), 0.0);
                /* cross: each component a difference of two products, 2 u (|a_i b_j| +
                 * |a_j b_i|) per implementation. */
                CMP("vec3_cross", sm_vec3_cross(a, b, got), glm_vec3_cross(a, b, want),
                    4.0 * U * (fabs(a[(k + 1) % 3] * b[(k + 2) % 3])
                               + fabs(a[(k + 2) % 3] * b[(k + 1) % 3])));
                NEAR(sm_vec3_dot(a, b), glm_vec3_dot(a, b), 8.0 * U * sab, "vec3_dot", i);
                NEAR(sm_vec3_norm(a), glm_vec3_norm(a), 8.0 * U * glm_vec3_norm(a), "vec3_norm", i);
                NEAR(sm_vec3_norm2(a), glm_vec3_norm2(a), 8.0 * U * glm_vec3_norm2(a), "vec3_norm2", i);
                /* distance: the difference rounds once (2 u (|a| + |b|)), then the norm */
                double dscale = 8.0 * U * (glm_vec3_norm(a) + glm_vec3_norm(b));
                NEAR(sm_vec3_distance(a, b), glm_vec3_distance(a, b), dscale, "vec3_distance", i);
                NEAR(sm_vec3_distance2(a, b), glm_vec3_distance2(a, b),
                     dscale * (glm_vec3_norm(a) + glm_vec3_norm(b)) * 2.0, "vec3_distance2", i);
            } else {
                CMP("vec4_add", sm_vec4_add(a, b, got), glm_vec4_add(a, b, want), tol[k]);
                CMP("vec4_sub", sm_vec4_sub(a, b, got), glm_vec4_sub(a, b, want), tol[k]);
                CMP("vec4_scale", sm_vec4_scale(a, s, got), glm_vec4_scale(a, s, want),
                    2.0 * U * fabs(a[k] * s));
                CMP("vec4_copy", sm_vec4_copy(a, got), glm_vec4_copy(a, want), 0.0);
            }
#undef CMP
        }
    }
}

/* In-place forms and aliasing of output with inputs give the same as separate outputs. */
static void test_vec_aliasing(void **state)
{
    (void)state;
    splitmix r = {0x5eed0002u};
    for (int i = 0; i < 500; i++) {
        vec4 a, b, sep, al;
        rnd_vec(&r, a, 4, -5.0f, 5.0f);
        rnd_vec(&r, b, 4, -5.0f, 5.0f);

        sm_vec3_cross(a, b, sep);
        glm_vec4_copy(a, al);
        sm_vec3_cross(al, b, al);
        EXPECT_CLOSE(al, sep, 3, "cross dest = a");
        glm_vec4_copy(b, al);
        sm_vec3_cross(a, al, al);
        EXPECT_CLOSE(al, sep, 3, "cross dest = b");

        sm_vec3_normalize_to(a, sep);
        glm_vec4_copy(a, al);
        sm_vec3_normalize(al);
        EXPECT_CLOSE(al, sep, 3, "normalize in place");

        glm_vec4_copy(a, al);
        sm_vec3_muladds(b, 2.0f, al);
        for (int k = 0; k < 3; k++)
            NEAR(al[k], a[k] + 2.0f * b[k], 2.0 * U * (fabs(a[k]) + fabs(2.0f * b[k])), "muladds", i);
    }
}

/* Degenerate vectors: defined results, and the rescaling path for tiny/huge vectors. */
static void test_vec_degenerate(void **state)
{
    (void)state;
    vec4 z = {0.0f, 0.0f, 0.0f, 0.0f}, out = {1.0f, 1.0f, 1.0f, 1.0f};

    sm_vec3_normalize_to(z, out);
    assert_true(all_zero(out, 3));
    assert_true(sm_vec3_norm(z) == 0.0f);

    /* Plain sqrt(sum of squares) underflows (1e-30^2 = 0 in float) or overflows
     * (1e30^2 = inf): rescaled, these normalize like (3, 4, 0) / 5 and (1, 0, 0). */
    const struct { float x, y; double nx, ny, norm, tol; } cases[] = {
        {3e-30f, 4e-30f, 0.6, 0.8, 5e-30, 4.0 * U},
        {3e-40f, 4e-40f, 0.6, 0.8, 5e-40, 1e-5},   /* subnormal: ~18 significant bits */
        {1e-44f, 0.0f, 1.0, 0.0, 1e-44, 0.2},      /* 7 * 2^-149: 3 bits */
        {3e30f, 4e30f, 0.6, 0.8, 5e30, 4.0 * U},
        {3e37f, 4e37f, 0.6, 0.8, 5e37, 4.0 * U},
    };
    for (int k = 0; k < (int)(sizeof cases / sizeof cases[0]); k++) {
        vec3 v = {cases[k].x, cases[k].y, 0.0f}, n;
        sm_vec3_normalize_to(v, n);
        expect_finite(n, 3, "normalize tiny/huge");
        NEAR(sqrt((double)n[0] * n[0] + (double)n[1] * n[1]), 1.0, 4.0 * U, "normalized length", k);
        NEAR(n[0], cases[k].nx, 4.0 * U + (k == 1 ? 1e-5 : 0.0), "normalize x", k);
        NEAR(n[1], cases[k].ny, 4.0 * U + (k == 1 ? 1e-5 : 0.0), "normalize y", k);
        NEAR(sm_vec3_norm(v), cases[k].norm, cases[k].tol * cases[k].norm, "norm tiny/huge", k);
        sm_vec3_normalize(v);
        EXPECT_CLOSE(v, n, 3, "normalize in place");
    }
    /* a norm beyond FLT_MAX is +inf (correct overflow), not NaN */
    vec3 big = {FLT_MAX, FLT_MAX, 0.0f};
    assert_true(isinf(sm_vec3_norm(big)));
    vec3 nb;
    sm_vec3_normalize_to(big, nb);
    NEAR(nb[0], sqrt(0.5), 4.0 * U, "normalize FLT_MAX", 0);

    vec3 bad = {1.0f, NAN, 0.0f}, nn;
    sm_vec3_normalize_to(bad, nn);
    assert_true(all_nan(nn, 3));
    vec3 inf = {INFINITY, 0.0f, 0.0f};
    sm_vec3_normalize_to(inf, nn);
    assert_true(all_nan(nn, 3));
    assert_true(isnan(sm_vec3_norm(bad)));
    assert_true(isinf(sm_vec3_norm(inf)));
}

/* >>mat4 ----------------------------------------------------------------------------------- */

/* mul / mulv: each entry a sum of 4 products: 4 u sum|a_ik b_kj| per implementation
 * (gamma_4 bound), so tolerance 8 u * that sum. transpose, pick3, translate/scale make:
 * exact. */
static void test_mat4_products_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed0003u};
    for (int i = 0; i < N_DRAWS; i++) {
        mat4 a, b, got, want;
        vec4 v, gv, wv;
        float sa = (float)pow(10.0, rnd(&r, -2.0f, 2.0f));
        rnd_vec(&r, &a[0][0], 16, -sa, sa);
        rnd_vec(&r, &b[0][0], 16, -1.0f, 1.0f);
        rnd_vec(&r, v, 4, -10.0f, 10.0f);

        sm_mat4_mul(a, b, got);
        glm_mat4_mul(a, b, want);
        for (int c = 0; c < 4; c++)
            for (int rr = 0; rr < 4; rr++) {
                double s = 0.0;
                for (int k = 0; k < 4; k++)
                    s += fabs(a[k][rr] * b[c][k]);
                NEAR(got[c][rr], want[c][rr], 8.0 * U * s, "mat4_mul", i);
            }

        sm_mat4_mulv(a, v, gv);
        glm_mat4_mulv(a, v, wv);
        for (int rr = 0; rr < 4; rr++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += fabs(a[k][rr] * v[k]);
            NEAR(gv[rr], wv[rr], 8.0 * U * s, "mat4_mulv", i);
        }

        vec3 v3 = {v[0], v[1], v[2]}, g3, w3;
        sm_mat4_mulv3(a, v3, v[3], g3);
        glm_mat4_mulv3(a, v3, v[3], w3);
        for (int rr = 0; rr < 3; rr++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += fabs(a[k][rr] * v[k]);
            NEAR(g3[rr], w3[rr], 8.0 * U * s, "mat4_mulv3", i);
        }

        sm_mat4_transpose_to(a, got);
        glm_mat4_transpose_to(a, want);
        assert_memory_equal(got, want, sizeof(mat4));

        mat3 g33, w33;
        sm_mat4_pick3(a, g33);
        glm_mat4_pick3(a, w33);
        assert_memory_equal(g33, w33, sizeof(mat3));

        sm_mat4_translate_make(v3, got);
        glm_translate_make(want, v3);
        assert_memory_equal(got, want, sizeof(mat4));
        sm_mat4_scale_make(v3, got);
        glm_scale_make(want, v3);
        assert_memory_equal(got, want, sizeof(mat4));

        sm_mat4_copy(a, got);
        assert_memory_equal(got, a, sizeof(mat4));
    }
    mat4 id, gid;
    glm_mat4_identity(id);
    sm_mat4_identity(gid);
    assert_memory_equal(id, gid, sizeof(mat4));
}

/* dest may alias a and/or b (and v for mulv). */
static void test_mat4_aliasing(void **state)
{
    (void)state;
    splitmix r = {0x5eed0004u};
    for (int i = 0; i < 200; i++) {
        mat4 a, b, sep, al;
        vec4 v, vs, va;
        double ref[16];
        rnd_mat4_cond(&r, a, ref, 100.0);
        rnd_vec(&r, &b[0][0], 16, -1.0f, 1.0f);
        rnd_vec(&r, v, 4, -1.0f, 1.0f);

        sm_mat4_mul(a, b, sep);
        glm_mat4_copy(a, al);
        sm_mat4_mul(al, b, al);
        EXPECT_CLOSE(&al[0][0], &sep[0][0], 16, "mul dest = a");
        glm_mat4_copy(b, al);
        sm_mat4_mul(a, al, al);
        EXPECT_CLOSE(&al[0][0], &sep[0][0], 16, "mul dest = b");
        sm_mat4_mul(a, a, sep);
        glm_mat4_copy(a, al);
        sm_mat4_mul(al, al, al);
        EXPECT_CLOSE(&al[0][0], &sep[0][0], 16, "mul dest = a = b");

        sm_mat4_mulv(a, v, vs);
        glm_vec4_copy(v, va);
        sm_mat4_mulv(a, va, va);
        EXPECT_CLOSE(va, vs, 4, "mulv dest = v");

        sm_mat4_inv(a, sep);
        glm_mat4_copy(a, al);
        sm_mat4_inv(al, al);
        EXPECT_CLOSE(&al[0][0], &sep[0][0], 16, "inv dest = m");
    }
}

/* Inverse of random matrices with condition number kappa (inf norm) <= 1e4 (worse draws
 * are rejected: float carries ~7 digits, so kappa u must stay well below 1). Perturbation
 * theory bounds the error of a computed inverse by c u kappa |inv| for a modest constant
 * c; for the cofactor formulas the largest c observed over these draws is ~1.1 (4x4) and
 * ~1.4 (3x3) against the exact inverse in double (printed when the test runs), so c = 8
 * is used (sm vs cglm: 16); the residual M inv(M) - I gets 8 u kappa. det: compared
 * with the double Leibniz sum, tolerance 16 u * permanent(|M|) (every term of the
 * expansion is bounded by the permanent; ~3 roundings per term and ~5 in the sums). */
static void test_mat4_inv_det_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed0005u};
    double worst = 0.0, worst_res = 0.0;
    for (int i = 0; i < N_DRAWS; i++) {
        mat4 m, got, want, prod;
        double ref[16];
        double kappa = rnd_mat4_cond(&r, m, ref, 1e4);
        double xmax = max_abs_d(ref, 16);

        sm_mat4_inv(m, got);
        glm_mat4_inv(m, want);
        for (int k = 0; k < 16; k++) {
            double e = fabs((&got[0][0])[k] - ref[k]);
            worst = fmax(worst, e / (U * kappa * xmax));
            NEAR((&got[0][0])[k], ref[k], 8.0 * U * kappa * xmax, "mat4_inv vs exact", i);
            NEAR((&got[0][0])[k], (&want[0][0])[k], 16.0 * U * kappa * xmax, "mat4_inv vs cglm", i);
        }
        sm_mat4_mul(m, got, prod);
        for (int c = 0; c < 4; c++)
            for (int rr = 0; rr < 4; rr++) {
                double e = fabs(prod[c][rr] - (c == rr ? 1.0 : 0.0));
                worst_res = fmax(worst_res, e / (U * kappa));
                NEAR(prod[c][rr], c == rr ? 1.0 : 0.0, 8.0 * U * kappa, "M inv(M) - I", i);
            }

        double det = leibniz(&m[0][0], 4, true), perm = leibniz(&m[0][0], 4, false);
        NEAR(sm_mat4_det(m), det, 16.0 * U * perm, "mat4_det vs exact", i);
        NEAR(sm_mat4_det(m), glm_mat4_det(m), 32.0 * U * perm, "mat4_det vs cglm", i);
    }
    print_message("mat4_inv: largest error / (u kappa |inv|) = %.2f, residual / (u kappa) = %.2f "
                  "(tolerance 8)\n", worst, worst_res);

    /* Affine transforms (what the renderer inverts): kappa is at most ~1e4 here too, but
     * check against cglm with the same scaled bound on many draws. */
    for (int i = 0; i < N_DRAWS; i++) {
        mat4 m, got, want;
        double ref[16];
        rnd_trs(&r, m);
        assert_true(ref_inverse(&m[0][0], 4, ref));
        double kappa = norm_inf_f(&m[0][0], 4) * norm_inf_d(ref, 4), xmax = max_abs_d(ref, 16);
        sm_mat4_inv(m, got);
        glm_mat4_inv(m, want);
        for (int k = 0; k < 16; k++) {
            NEAR((&got[0][0])[k], ref[k], 8.0 * U * kappa * xmax, "affine inv vs exact", i);
            NEAR((&got[0][0])[k], (&want[0][0])[k], 16.0 * U * kappa * xmax, "affine inv vs cglm", i);
        }
    }
}

static void test_mat4_inv_exact_and_degenerate(void **state)
{
    (void)state;
    /* T(1,2,3) S(2,4,8): inverse S(1/2,1/4,1/8) T(-1,-2,-3), all exact in float */
    mat4 m = {{2, 0, 0, 0}, {0, 4, 0, 0}, {0, 0, 8, 0}, {1, 2, 3, 1}}, inv;
    mat4 want = {{0.5f, 0, 0, 0}, {0, 0.25f, 0, 0}, {0, 0, 0.125f, 0}, {-0.5f, -0.5f, -0.375f, 1}};
    sm_mat4_inv(m, inv);
    EXPECT_EQUAL(&inv[0][0], &want[0][0], 16, "inverse of T S");
    NEAR(sm_mat4_det(m), 64.0, 0.0, "det of scale", 0);

    /* lower triangular (column-major rows below): det = 2 * 3 * 6 * 10 */
    mat4 tri = {{2, 1, 4, 7}, {0, 3, 5, 8}, {0, 0, 6, 9}, {0, 0, 0, 10}};
    NEAR(sm_mat4_det(tri), 360.0, 0.0, "det triangular", 0);
    /* an odd permutation (swap x and y) has det -1 and is its own inverse */
    mat4 perm = {{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    NEAR(sm_mat4_det(perm), -1.0, 0.0, "det permutation", 0);
    sm_mat4_inv(perm, inv);
    EXPECT_EQUAL(&inv[0][0], &perm[0][0], 16, "inverse of a permutation");

    /* singular: zero matrix, duplicate columns (integers: det exactly 0), zero scale */
    mat4 zero = {{0}}, dup = {{1, 2, 3, 4}, {5, 6, 7, 8}, {1, 2, 3, 4}, {0, 0, 1, 1}};
    mat4 dep = {{1, 2, 3, 4}, {5, 6, 7, 8}, {6, 8, 10, 12}, {0, 1, 0, 1}};   /* c2 = c0 + c1 */
    mat4 flat = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}, {3, 4, 5, 1}};
    mat4 *singular[] = {&zero, &dup, &dep, &flat};
    for (size_t k = 0; k < 4; k++) {
        glm_mat4_identity(inv);
        sm_mat4_inv(*singular[k], inv);
        assert_true(all_zero(&inv[0][0], 16));
        assert_true(sm_mat4_det(*singular[k]) == 0.0f);
    }
    /* an inverse beyond FLT_MAX (scale 1e-39, a subnormal) is not representable: zero */
    mat4 tiny;
    sm_mat4_scale_make((vec3){1e-39f, 1.0f, 1.0f}, tiny);
    sm_mat4_inv(tiny, inv);
    assert_true(all_zero(&inv[0][0], 16));
    /* non-finite input: all NaN */
    mat4 nanm;
    glm_mat4_identity(nanm);
    nanm[2][1] = NAN;
    sm_mat4_inv(nanm, inv);
    assert_true(all_nan(&inv[0][0], 16));
    nanm[2][1] = INFINITY;
    sm_mat4_inv(nanm, inv);
    assert_true(all_nan(&inv[0][0], 16));

    /* Very small / very large / mixed scales invert correctly: the determinant of
     * S(1e-12) is 1e-36 (1e-48 for S(1e-16)), which the unscaled cofactor formula
     * underflows or loses; likewise 1e12^4 overflows. Columns are rescaled exactly. */
    const float scales[] = {1e-16f, 1e-12f, 1e12f, 1e20f};
    for (size_t k = 0; k < 4; k++) {
        float s = scales[k];
        mat4 a = {{s, 0, 0, 0}, {0, s, 0, 0}, {0, 0, s, 0}, {5, -7, 9, 1}};
        sm_mat4_inv(a, inv);
        for (int c = 0; c < 3; c++)
            for (int rr = 0; rr < 4; rr++)
                NEAR(inv[c][rr], c == rr ? 1.0 / s : 0.0, 4.0 * U / s, "inv of scale", (int)k);
        NEAR(inv[3][0], -5.0 / s, 8.0 * U * 5.0 / s, "inv of scale, translation", (int)k);
        NEAR(inv[3][1], 7.0 / s, 8.0 * U * 7.0 / s, "inv of scale, translation", (int)k);
        NEAR(inv[3][2], -9.0 / s, 8.0 * U * 9.0 / s, "inv of scale, translation", (int)k);
        NEAR(inv[3][3], 1.0, 4.0 * U, "inv of scale, w", (int)k);
    }
    mat4 mixed = {{1e30f, 0, 0, 0}, {0, 1e-10f, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    sm_mat4_inv(mixed, inv);
    NEAR(inv[0][0], 1e-30, 4.0 * U * 1e-30, "mixed scales x", 0);
    NEAR(inv[1][1], 1e10, 4.0 * U * 1e10, "mixed scales y", 0);
    NEAR(inv[2][2], 1.0, 0.0, "mixed scales z", 0);
}

/* Rotation: entries of magnitude <= 1 from cos/sin (libm, ~1 ulp) and a normalized axis
 * (~3 u), a few more roundings: 16 u absolute. */
static void test_mat4_rotate_trs_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed0006u};
    for (int i = 0; i < N_DRAWS; i++) {
        vec3 axis;
        mat4 got, want;
        float ang = rnd(&r, -2.0f * SM_PI, 2.0f * SM_PI);
        rnd_vec(&r, axis, 3, -3.0f, 3.0f);
        if (glm_vec3_norm(axis) < 1e-3f)
            continue;
        sm_mat4_rotate_make(ang, axis, got);
        glm_rotate_make(want, ang, axis);
        for (int k = 0; k < 16; k++)
            NEAR((&got[0][0])[k], (&want[0][0])[k], 16.0 * U, "rotate_make", i);
    }
    /* a quarter turn about +z takes +x to +y */
    mat4 rz;
    vec4 x = {1, 0, 0, 1}, y;
    sm_mat4_rotate_make(SM_PI / 2.0f, (vec3){0.0f, 0.0f, 5.0f}, rz);
    sm_mat4_mulv(rz, x, y);
    NEAR(y[0], 0.0, 4.0 * U, "rot z x", 0);
    NEAR(y[1], 1.0, 4.0 * U, "rot z y", 0);
    NEAR(y[2], 0.0, 0.0, "rot z z", 0);
    NEAR(y[3], 1.0, 0.0, "rot z w", 0);
    /* zero axis: identity */
    mat4 id;
    sm_mat4_rotate_make(1.0f, (vec3){0.0f, 0.0f, 0.0f}, rz);
    glm_mat4_identity(id);
    assert_memory_equal(rz, id, sizeof(mat4));
}

/* Normal matrix against the exact inverse transpose (double): same kappa-scaled bound as
 * the inverses, on random affine transforms with non-uniform scale. */
static void test_mat4_normal(void **state)
{
    (void)state;
    splitmix r = {0x5eed0007u};
    for (int i = 0; i < N_DRAWS; i++) {
        mat4 m;
        mat3 up, got, want;
        double ref[9];
        rnd_trs(&r, m);
        glm_mat4_pick3(m, up);
        assert_true(ref_inverse(&up[0][0], 3, ref));
        double kappa = norm_inf_f(&up[0][0], 3) * norm_inf_d(ref, 3), xmax = max_abs_d(ref, 9);
        sm_mat4_normal(m, got);
        glm_mat3_inv(up, want);
        glm_mat3_transpose(want);
        for (int c = 0; c < 3; c++)
            for (int rr = 0; rr < 3; rr++) {
                NEAR(got[c][rr], ref[rr * 3 + c], 8.0 * U * kappa * xmax, "normal vs exact", i);
                NEAR(got[c][rr], want[c][rr], 16.0 * U * kappa * xmax, "normal vs cglm", i);
            }
    }
    /* a zero scale: the normal matrix is defined as zero */
    mat4 flat;
    mat3 n;
    sm_mat4_scale_make((vec3){1.0f, 0.0f, 1.0f}, flat);
    sm_mat4_normal(flat, n);
    assert_true(all_zero(&n[0][0], 9));
    /* scale (2, 4, 8): normals scale by the inverse */
    sm_mat4_scale_make((vec3){2.0f, 4.0f, 8.0f}, flat);
    sm_mat4_normal(flat, n);
    NEAR(n[0][0], 0.5, 0.0, "normal sx", 0);
    NEAR(n[1][1], 0.25, 0.0, "normal sy", 0);
    NEAR(n[2][2], 0.125, 0.0, "normal sz", 0);
}

/* >>mat3 ----------------------------------------------------------------------------------- */

/* Same bounds as for mat4 with 3-term sums (3 u per implementation, 8 u used). */
static void test_mat3_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed0008u};
    double worst = 0.0;
    for (int i = 0; i < N_DRAWS; i++) {
        mat3 a, b, got, want;
        vec3 v, gv, wv;
        double ref[9];
        rnd_vec(&r, &a[0][0], 9, -1.0f, 1.0f);
        rnd_vec(&r, &b[0][0], 9, -2.0f, 2.0f);
        rnd_vec(&r, v, 3, -10.0f, 10.0f);

        sm_mat3_mulv(a, v, gv);
        glm_mat3_mulv(a, v, wv);
        for (int rr = 0; rr < 3; rr++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++)
                s += fabs(a[k][rr] * v[k]);
            NEAR(gv[rr], wv[rr], 8.0 * U * s, "mat3_mulv", i);
        }
        sm_mat3_transpose_to(a, got);
        glm_mat3_transpose_to(a, want);
        assert_memory_equal(got, want, sizeof(mat3));

        double det = leibniz(&a[0][0], 3, true), perm = leibniz(&a[0][0], 3, false);
        NEAR(sm_mat3_det(a), det, 8.0 * U * perm, "mat3_det vs exact", i);
        NEAR(sm_mat3_det(a), glm_mat3_det(a), 16.0 * U * perm, "mat3_det vs cglm", i);

        if (!ref_inverse(&a[0][0], 3, ref))
            continue;
        double kappa = norm_inf_f(&a[0][0], 3) * norm_inf_d(ref, 3), xmax = max_abs_d(ref, 9);
        if (kappa > 1e4)
            continue;   /* ill-conditioned draw */
        sm_mat3_inv(a, got);
        glm_mat3_inv(a, want);
        for (int k = 0; k < 9; k++) {
            worst = fmax(worst, fabs((&got[0][0])[k] - ref[k]) / (U * kappa * xmax));
            NEAR((&got[0][0])[k], ref[k], 8.0 * U * kappa * xmax, "mat3_inv vs exact", i);
            NEAR((&got[0][0])[k], (&want[0][0])[k], 16.0 * U * kappa * xmax, "mat3_inv vs cglm", i);
        }
        /* aliasing */
        mat3 al;
        memcpy(al, a, sizeof al);
        sm_mat3_inv(al, al);
        EXPECT_CLOSE(&al[0][0], &got[0][0], 9, "mat3 inv dest = m");
    }
    print_message("mat3_inv: largest error / (u kappa |inv|) = %.2f (tolerance 8)\n", worst);

    mat3 sing = {{1, 2, 3}, {2, 4, 6}, {0, 1, 1}}, inv;
    sm_mat3_inv(sing, inv);
    assert_true(all_zero(&inv[0][0], 9));
    assert_true(sm_mat3_det(sing) == 0.0f);
    mat3 tiny = {{1e-20f, 0, 0}, {0, 1e-20f, 0}, {0, 0, 1e-20f}};
    sm_mat3_inv(tiny, inv);
    NEAR(inv[1][1], 1e20, 4.0 * U * 1e20, "mat3 inv tiny", 0);
    NEAR(inv[1][0], 0.0, 0.0, "mat3 inv tiny off-diagonal", 0);
    tiny[0][0] = NAN;
    sm_mat3_inv(tiny, inv);
    assert_true(all_nan(&inv[0][0], 9));
}

/* >>quaternions ---------------------------------------------------------------------------- */

/* >>camera ----------------------------------------------------------------------------------- */

/* lookat: draws where up is within ~3 degrees of the view direction are left to the
 * degenerate test; elsewhere the side vector's error is amplified by 1/sin(angle) <= 20,
 * so rotation entries get 16 u / sin, the translation that times |eye|. perspective and
 * ortho: the same closed forms, a few roundings each: relative 8 u per entry. */
static void test_camera_vs_cglm(void **state)
{
    (void)state;
    splitmix r = {0x5eed000bu};
    for (int i = 0; i < N_DRAWS; i++) {
        vec3 eye, center, up, f;
        mat4 got, want;
        rnd_vec(&r, eye, 3, -100.0f, 100.0f);
        rnd_vec(&r, center, 3, -100.0f, 100.0f);
        rnd_vec(&r, up, 3, -2.0f, 2.0f);
        glm_vec3_sub(center, eye, f);
        if (glm_vec3_norm(f) < 1e-2f || glm_vec3_norm(up) < 1e-2f)
            continue;
        double sn = glm_vec3_norm((vec3){f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                                         f[0] * up[1] - f[1] * up[0]})
                    / (glm_vec3_norm(f) * glm_vec3_norm(up));
        if (sn < 0.05)
            continue;
        sm_lookat(eye, center, up, got);
        glm_lookat(eye, center, up, want);
        double tr = 16.0 * U / sn;
        for (int c = 0; c < 4; c++)
            for (int rr = 0; rr < 4; rr++)
                NEAR(got[c][rr], want[c][rr], c < 3 ? tr : tr * 2.0 * glm_vec3_norm(eye) + 1e-30,
                     "lookat", i);

        float fovy = rnd(&r, sm_deg2rad(10.0f), sm_deg2rad(170.0f));
        float aspect = rnd(&r, 0.25f, 4.0f), zn = rnd(&r, 0.01f, 10.0f);
        float zf = zn * (float)pow(10.0, rnd(&r, 0.2f, 5.0f));
        sm_perspective(fovy, aspect, zn, zf, got);
        glm_perspective(fovy, aspect, zn, zf, want);
        for (int k = 0; k < 16; k++)
            NEAR((&got[0][0])[k], (&want[0][0])[k], 8.0 * U * fabs((&want[0][0])[k]), "perspective", i);

        float l = rnd(&r, -100.0f, 100.0f), rt = l + rnd(&r, 0.1f, 200.0f);
        float b = rnd(&r, -100.0f, 100.0f), tp = b + rnd(&r, 0.1f, 200.0f);
        float on = rnd(&r, -100.0f, 100.0f), of = on + rnd(&r, 0.1f, 200.0f);
        sm_ortho(l, rt, b, tp, on, of, got);
        glm_ortho(l, rt, b, tp, on, of, want);
        /* translation terms: -(r + l) / (r - l) cancels; scale by the operands instead */
        double sc[3] = {fabs(l) + fabs(rt), fabs(b) + fabs(tp), fabs(on) + fabs(of)};
        for (int k = 0; k < 3; k++) {
            NEAR(got[k][k], want[k][k], 8.0 * U * fabs(want[k][k]), "ortho scale", i);
            NEAR(got[3][k], want[3][k], 8.0 * U * sc[k] * fabs(want[k][k]), "ortho offset", i);
        }
        for (int c = 0; c < 4; c++)
            for (int rr = 0; rr < 4; rr++)
                if (c != rr && c != 3)
                    NEAR(got[c][rr], 0.0, 0.0, "ortho zero", i);
        NEAR(got[3][3], 1.0, 0.0, "ortho w", i);
    }
}

static void test_camera_exact(void **state)
{
    (void)state;
    mat4 m, want;

    /* 90 degrees, aspect 1, near 1, far 3: f = 1, (n+f)/(n-f) = -2, 2nf/(n-f) = -3 */
    sm_perspective(sm_deg2rad(90.0f), 1.0f, 1.0f, 3.0f, m);
    mat4 p90 = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -2, -1}, {0, 0, -3, 0}};
    for (int k = 0; k < 16; k++)
        NEAR((&m[0][0])[k], (&p90[0][0])[k], 2.0 * U, "perspective 90", k);
    /* the near plane maps to z_ndc = -1, the far plane to +1 */
    vec4 pn = {0, 0, -1, 1}, pf = {0, 0, -3, 1}, cn, cf;
    sm_mat4_mulv(m, pn, cn);
    sm_mat4_mulv(m, pf, cf);
    NEAR(cn[2] / cn[3], -1.0, 4.0 * U, "near ndc", 0);
    NEAR(cf[2] / cf[3], 1.0, 4.0 * U, "far ndc", 0);
    sm_perspective(sm_deg2rad(90.0f), 2.0f, 1.0f, 3.0f, m);
    NEAR(m[0][0], 0.5, 2.0 * U, "perspective aspect", 0);

    /* infinite far plane: the limit of the finite one */
    sm_perspective(1.0f, 1.5f, 0.5f, INFINITY, m);
    sm_perspective(1.0f, 1.5f, 0.5f, 1e30f, want);
    for (int k = 0; k < 16; k++)
        NEAR((&m[0][0])[k], (&want[0][0])[k], 4.0 * U, "infinite far", k);
    NEAR(m[2][2], -1.0, 0.0, "infinite far [2][2]", 0);
    NEAR(m[3][2], -1.0, 0.0, "infinite far [3][2]", 0);

    /* invalid parameters: the zero matrix */
    const float bad[][4] = {
        {0.0f, 1.0f, 0.1f, 10.0f},   {SM_PI, 1.0f, 0.1f, 10.0f}, {1.0f, 0.0f, 0.1f, 10.0f},
        {1.0f, -1.0f, 0.1f, 10.0f},  {1.0f, 1.0f, 0.0f, 10.0f},  {1.0f, 1.0f, -1.0f, 10.0f},
        {1.0f, 1.0f, 10.0f, 10.0f},  {1.0f, 1.0f, 10.0f, 1.0f},  {NAN, 1.0f, 0.1f, 10.0f},
        {1.0f, INFINITY, 0.1f, 10.0f}, {1.0f, 1.0f, 0.1f, NAN},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        glm_mat4_identity(m);
        sm_perspective(bad[k][0], bad[k][1], bad[k][2], bad[k][3], m);
        assert_true(all_zero(&m[0][0], 16));
    }
    sm_ortho(1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, m);
    assert_true(all_zero(&m[0][0], 16));
    sm_ortho(0.0f, 1.0f, 0.0f, 1.0f, 2.0f, 2.0f, m);
    assert_true(all_zero(&m[0][0], 16));
    sm_ortho(-1.0f, 1.0f, -1.0f, 1.0f, -1.0f, 1.0f, m);
    mat4 flipz = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -1, 0}, {0, 0, 0, 1}};
    for (int k = 0; k < 16; k++)
        NEAR((&m[0][0])[k], (&flipz[0][0])[k], 0.0, "ortho unit cube", k);

    /* from (0,0,5) looking at the origin, y up: a translation by -5 along z */
    sm_lookat((vec3){0, 0, 5}, (vec3){0, 0, 0}, (vec3){0, 1, 0}, m);
    sm_mat4_translate_make((vec3){0, 0, -5}, want);
    EXPECT_EQUAL(&m[0][0], &want[0][0], 16, "lookat down -z");
    /* looking down +x, y up: rows s = (0,0,1), u = (0,1,0), -f = (-1,0,0) */
    sm_lookat((vec3){0, 0, 0}, (vec3){3, 0, 0}, (vec3){0, 1, 0}, m);
    mat4 px = {{0, 0, -1, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 1}};
    for (int k = 0; k < 16; k++)
        NEAR((&m[0][0])[k], (&px[0][0])[k], 0.0, "lookat +x", k);
}

/* the rotation part is orthonormal with det +1 and everything is finite */
static void expect_view_matrix(mat4 m, const char *what)
{
    mat3 r, rt, p;
    expect_finite(&m[0][0], 16, what);
    glm_mat4_pick3(m, r);
    glm_mat3_transpose_to(r, rt);
    glm_mat3_mul(rt, r, p);
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++)
            NEAR(p[c][k], c == k ? 1.0 : 0.0, 16.0 * U, what, c * 3 + k);
    NEAR(glm_mat3_det(r), 1.0, 16.0 * U, what, 9);
}

static void test_lookat_degenerate(void **state)
{
    (void)state;
    mat4 m;
    vec4 c, out;
    /* eye == center: looks down world -z (the rotation is the identity here) */
    sm_lookat((vec3){1, 2, 3}, (vec3){1, 2, 3}, (vec3){0, 1, 0}, m);
    expect_view_matrix(m, "lookat eye == center");
    NEAR(m[2][2], 1.0, 0.0, "eye == center looks down -z", 0);
    /* up parallel, antiparallel, zero, nearly parallel: the camera still looks at center */
    const float ups[][3] = {{0, 1, 0}, {0, -3, 0}, {0, 0, 0}, {1e-8f, 1, 0}, {0, 1, 1e-7f}};
    for (size_t k = 0; k < sizeof ups / sizeof ups[0]; k++) {
        sm_lookat((vec3){0, 5, 0}, (vec3){0, 0, 0}, ups[k], m);
        expect_view_matrix(m, "lookat up parallel");
        glm_vec4_copy((vec4){0, 0, 0, 1}, c);
        sm_mat4_mulv(m, c, out);
        NEAR(out[0], 0.0, 8.0 * U, "center on axis x", (int)k);
        NEAR(out[1], 0.0, 8.0 * U, "center on axis y", (int)k);
        NEAR(out[2], -5.0, 8.0 * U * 5.0, "center in front", (int)k);
    }
    /* top-down along -y with up = +y: fallback up is +x (least aligned, first) */
    sm_lookat((vec3){0, 5, 0}, (vec3){0, 0, 0}, (vec3){0, 1, 0}, m);
    NEAR(m[0][1], 1.0, 0.0, "fallback up is +x", 0);
    /* random eyes and centers with up exactly along the view direction */
    splitmix r = {0x5eed000cu};
    for (int i = 0; i < 1000; i++) {
        vec3 eye, dir;
        rnd_vec(&r, eye, 3, -50.0f, 50.0f);
        rnd_unit3(&r, dir);
        sm_look(eye, dir, dir, m);
        expect_view_matrix(m, "lookat random parallel up");
        /* eye maps to the origin */
        glm_vec4_copy((vec4){eye[0], eye[1], eye[2], 1}, c);
        sm_mat4_mulv(m, c, out);
        for (int k = 0; k < 3; k++)
            NEAR(out[k], 0.0, 32.0 * U * 50.0, "eye at origin", i);
    }
}

/* >>frustum --------------------------------------------------------------------------------- */

static void rnd_viewproj(splitmix *r, mat4 vp)
{
    vec3 eye, center, up;
    mat4 view, proj;
    rnd_vec(r, eye, 3, -50.0f, 50.0f);
    rnd_vec(r, center, 3, -50.0f, 50.0f);
    rnd_unit3(r, up);
    glm_lookat(eye, center, up, view);
    glm_perspective(rnd(r, 0.3f, 2.5f), rnd(r, 0.5f, 2.5f), rnd(r, 0.05f, 2.0f),
                    rnd(r, 20.0f, 300.0f), proj);
    glm_mat4_mul(proj, view, vp);
}

/* Planes: the same arithmetic as cglm on the same matrix (one add and a normalization):
 * 8 u relative to the plane's size. Each plane's sign must also match the clip-space
 * inequality it stands for (left: w + x >= 0, right: w - x, bottom: w + y, top: w - y,
 * near: w + z, far: w - z) for random points, except within rounding of the boundary. */
static void test_frustum_planes(void **state)
{
    (void)state;
    splitmix r = {0x5eed000du};
    int nb = 0;
    for (int i = 0; i < N_DRAWS / 4; i++) {
        mat4 vp, inv;
        vec4 got[6], want[6], gc[8], wc[8];
        rnd_viewproj(&r, vp);
        sm_frustum_planes(vp, got);
        glm_frustum_planes(vp, want);
        for (int p = 0; p < 6; p++) {
            double size = glm_vec4_norm(want[p]);
            for (int k = 0; k < 4; k++)
                NEAR(got[p][k], want[p][k], 8.0 * U * size, "frustum plane", i);
            NEAR(sm_vec3_norm(got[p]), 1.0, 8.0 * U, "plane normalized", i);
        }
        for (int s = 0; s < 8; s++) {
            vec4 pt, clip;
            rnd_vec(&r, pt, 3, -400.0f, 400.0f);
            pt[3] = 1.0f;
            glm_mat4_mulv(vp, pt, clip);
            for (int p = 0; p < 6; p++) {
                double sgn = (p % 2) ? -1.0 : 1.0;
                double ref = (double)clip[3] + sgn * clip[p / 2];
                double scale = 0.0;
                for (int k = 0; k < 4; k++)
                    scale += fabs(vp[k][3] * pt[k]) + fabs(vp[k][p / 2] * pt[k]);
                BOOL_AGREE(sm_plane_distance(got[p], pt) >= 0.0f, ref >= 0.0, ref,
                           16.0 * U * scale, &nb, "plane side vs clip", i);
            }
        }
        /* corners: from the inverse, as cglm; they lie on their three planes */
        glm_mat4_inv(vp, inv);
        sm_frustum_corners(inv, gc);
        glm_frustum_corners(inv, wc);
        /* corner = x / w with x and w 4-term sums over inv's entries (NDC = +-1):
         * 4 u sum|inv| each, w relative 4 u sum|inv_w| / |w|, doubled for two libraries */
        for (int c = 0; c < 8; c++) {
            vec4 h, nd = {(c == 2 || c == 3 || c == 6 || c == 7) ? 1.0f : -1.0f,
                          (c == 1 || c == 2 || c == 5 || c == 6) ? 1.0f : -1.0f,
                          c >= 4 ? 1.0f : -1.0f, 1.0f};
            glm_mat4_mulv(inv, nd, h);
            double sw = 0.0;
            for (int k = 0; k < 4; k++)
                sw += fabs(inv[k][3]);
            for (int k = 0; k < 3; k++) {
                double sx = 0.0;
                for (int j = 0; j < 4; j++)
                    sx += fabs(inv[j][k]);
                double tol = 8.0 * U * (sx / fabs(h[3]) + fabs(wc[c][k]) * sw / fabs(h[3]));
                NEAR(gc[c][k], wc[c][k], tol, "frustum corner", i);
                NEAR(gc[c][k], h[k] / h[3], tol, "frustum corner vs x / w", i);
            }
            NEAR(gc[c][3], 1.0, 0.0, "frustum corner w", i);
        }
    }
    print_message("frustum planes: %d boundary disagreements\n", nb);

    /* identity: the unit cube's planes */
    mat4 id;
    vec4 pl[6];
    const float want_id[6][4] = {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1},
                                 {0, -1, 0, 1}, {0, 0, 1, 1}, {0, 0, -1, 1}};
    sm_mat4_identity(id);
    sm_frustum_planes(id, pl);
    for (int p = 0; p < 6; p++)
        for (int k = 0; k < 4; k++)
            NEAR(pl[p][k], want_id[p][k], 0.0, "identity planes", p);
    NEAR(sm_plane_distance(pl[SM_LEFT], (vec3){0.25f, 0, 0}), 1.25, 0.0, "plane distance", 0);
    /* a zero normal normalizes to the zero plane */
    vec4 zp = {0, 0, 0, 3};
    sm_plane_normalize(zp);
    assert_true(all_zero(zp, 4));
}

/* Sphere and box culling: against cglm's box test and a plane-by-plane sphere reference
 * on cglm's planes (the deciding margin within 16 u of the scene scale may disagree);
 * and conservative: whenever a point of the sphere / box is strictly inside the clip
 * volume, the test must say true. */
static void test_frustum_culling(void **state)
{
    (void)state;
    splitmix r = {0x5eed000eu};
    int nb = 0;
    for (int i = 0; i < N_DRAWS / 4; i++) {
        mat4 vp;
        vec4 planes[6], sp;
        rnd_viewproj(&r, vp);
        glm_frustum_planes(vp, planes);
        for (int s = 0; s < 16; s++) {
            rnd_vec(&r, sp, 3, -300.0f, 300.0f);
            sp[3] = rnd(&r, 0.0f, 60.0f);
            double margin = INFINITY;
            for (int p = 0; p < 6; p++)
                margin = fmin(margin, glm_vec3_dot(planes[p], sp) + planes[p][3] + sp[3]);
            double slack = 16.0 * U * (glm_vec3_norm(sp) + sp[3] + 300.0);
            BOOL_AGREE(sm_sphere_in_frustum(planes, sp), margin >= 0.0, margin, slack, &nb,
                       "sphere_in_frustum", i);

            /* conservative: sample points of the sphere */
            bool sphere_in = sm_sphere_in_frustum(planes, sp);
            for (int k = 0; k < 24; k++) {
                vec3 dir, pt;
                vec4 p4, clip;
                rnd_unit3(&r, dir);
                glm_vec3_scale(dir, sp[3] * cbrtf(rnd(&r, 0.0f, 1.0f)), pt);
                glm_vec3_add(pt, sp, pt);
                glm_vec4(pt, 1.0f, p4);
                glm_mat4_mulv(vp, p4, clip);
                float w = clip[3] * (1.0f - 1e-4f);
                if (fabsf(clip[0]) < w && fabsf(clip[1]) < w && fabsf(clip[2]) < w && !sphere_in)
                    fail_msg("draw %d: a point of the sphere is visible but it was culled", i);
            }
        }
    }
    print_message("culling: %d boundary disagreements of %d tests\n", nb, N_DRAWS / 4 * 16);
    assert_true(nb < N_DRAWS / 100);
}

/* >>bounds ------------------------------------------------------------------------------------ */

/* Intersections: sphere-sphere and point-sphere against cglm and an exact double
 * reference. Disagreement allowed within 16 u of the squared distances. */
static void test_intersections(void **state)
{
    (void)state;
    splitmix r = {0x5eed0010u};
    int nb = 0;
    for (int i = 0; i < N_DRAWS; i++) {
        vec4 a, b;
        vec3 p;
        rnd_vec(&r, a, 3, -10.0f, 10.0f);
        rnd_vec(&r, b, 3, -10.0f, 10.0f);
        rnd_vec(&r, p, 3, -10.0f, 10.0f);
        a[3] = rnd(&r, 0.0f, 8.0f);
        b[3] = rnd(&r, 0.0f, 8.0f);
        double d2 = 0.0, dp2 = 0.0;
        for (int k = 0; k < 3; k++) {
            d2 += ((double)a[k] - b[k]) * ((double)a[k] - b[k]);
            dp2 += ((double)a[k] - p[k]) * ((double)a[k] - p[k]);
        }
        double rr = (double)(a[3] + b[3]) * (a[3] + b[3]);
        bool ss = sm_sphere_sphere_intersects(a, b);
        BOOL_AGREE(ss, glm_sphere_sphere(a, b), d2 - rr, 16.0 * U * (d2 + rr), &nb, "sphere_sphere", i);
        BOOL_AGREE(ss, d2 <= rr, d2 - rr, 16.0 * U * (d2 + rr), &nb, "sphere_sphere exact", i);
        bool ps = sm_point_in_sphere(p, a);
        double ra = (double)a[3] * a[3];
        BOOL_AGREE(ps, glm_sphere_point(a, p), dp2 - ra, 16.0 * U * (dp2 + ra), &nb,
                   "point_in_sphere", i);
        BOOL_AGREE(ps, dp2 <= ra, dp2 - ra, 16.0 * U * (dp2 + ra), &nb, "point_in_sphere exact", i);
    }
    assert_true(nb < N_DRAWS / 100);

    /* touching counts */
    vec4 s1 = {0, 0, 0, 1}, s2 = {2, 0, 0, 1}, s3 = {2.001f, 0, 0, 1};
    assert_true(sm_sphere_sphere_intersects(s1, s2));
    assert_false(sm_sphere_sphere_intersects(s1, s3));
    assert_true(sm_point_in_sphere((vec3){1, 0, 0}, s1));
    assert_false(sm_point_in_sphere((vec3){1.001f, 0, 0}, s1));
    /* the empty box: min corner above max, so that any point merged in replaces both */
    vec3 empty[2];
    sm_aabb_empty(empty);
    for (int k = 0; k < 3; k++)
        assert_true(empty[0][k] > empty[1][k]);

}

/* >>cone ------------------------------------------------------------------------------------- */

/* Exact distance from a point to the capped cone of half angle a (<= pi/2) and height h,
 * in double: in the half-plane through the axis the solid is the triangle (0,0), (h,0),
 * (h, h tan a) and the point is (axial, perpendicular). */
static double seg_dist(double px, double py, double ax, double ay, double bx, double by)
{
    double dx = bx - ax, dy = by - ay, t = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy);
    t = fmin(fmax(t, 0.0), 1.0);
    return hypot(px - (ax + t * dx), py - (ay + t * dy));
}

static double cone_dist(const float apex[3], const float dir[3], double a, double h, const float p[3])
{
    double v[3], x = 0.0, y2 = 0.0, ta = tan(a);
    for (int k = 0; k < 3; k++) {
        v[k] = (double)p[k] - apex[k];
        x += v[k] * dir[k];
    }
    for (int k = 0; k < 3; k++)
        y2 += (v[k] - x * dir[k]) * (v[k] - x * dir[k]);
    double y = sqrt(y2);
    if (x >= 0.0 && x <= h && y <= x * ta)
        return 0.0;
    return fmin(seg_dist(x, y, 0, 0, h, h * ta),
                fmin(seg_dist(x, y, h, 0, h, h * ta), seg_dist(x, y, 0, 0, h, 0)));
}

/* Never false for a real hit (random spheres, and spheres sized to graze the cone from
 * outside within 1e-6 relative); true only within a bounded distance: a near miss lies
 * within r / sin((pi/2 - a) / 2) of the cap's rim or sqrt(1 + 1/cos^2 a) r of the apex. */
static void test_cone_sphere(void **state)
{
    (void)state;
    splitmix r = {0x5eed0012u};
    int hits = 0, misses = 0, false_pos = 0;
    for (int i = 0; i < N_DRAWS; i++) {
        vec3 apex, dir, off;
        vec4 s;
        rnd_vec(&r, apex, 3, -10.0f, 10.0f);
        rnd_unit3(&r, dir);
        float a = rnd(&r, sm_deg2rad(1.0f), sm_deg2rad(80.0f)), h = rnd(&r, 0.1f, 20.0f);
        rnd_vec(&r, off, 3, -25.0f, 25.0f);
        glm_vec3_add(apex, off, s);
        double d = cone_dist(apex, dir, a, h, s);
        if (i % 3 == 0) {
            /* grazing from outside: a real hit, 1e-6 (16 u) beyond touching, which
             * rounding in the test's distances (up to ~40 |v| u) would flip without
             * the slack */
            s[3] = (float)(d * (1.0 + 1e-6));
        } else if (i % 3 == 1 && d > 0.0) {
            s[3] = (float)(d * (1.0 - 1e-4));   /* just missing: either answer is fine */
        } else {
            s[3] = rnd(&r, 0.0f, 5.0f);
        }
        bool got = sm_cone_sphere_intersects(apex, dir, a, h, s);
        bool hit = d <= s[3];
        if (hit && !got)
            fail_msg("draw %d: cone misses a sphere it touches (distance %.9g, radius %.9g)",
                     i, d, (double)s[3]);
        double bound = fmax(1.0 / sin((SM_PI / 2.0 - a) / 2.0), sqrt(1.0 + 1.0 / (cos(a) * cos(a))));
        if (got && d > s[3] * bound * (1.0 + 1e-4) + 1e-4 * (glm_vec3_norm(off) + h))
            fail_msg("draw %d: cone hit %.6g away from a sphere of radius %.6g (bound %.3g r)",
                     i, d, (double)s[3], bound);
        hits += hit;
        misses += !got;
        false_pos += got && !hit;
    }
    print_message("cone: %d hits, %d rejected, %d conservative false positives\n", hits, misses,
                  false_pos);
    assert_true(misses > N_DRAWS / 10);

    /* hand cases: apex at 0, axis +z, 30 degrees, height 10 */
    vec3 o = {0, 0, 0}, z = {0, 0, 1};
    float a30 = sm_deg2rad(30.0f);
    assert_true(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){0, 0, 5, 0.1f}));
    assert_false(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){0, 0, -1, 0.5f}));
    assert_true(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){0, 0, -1, 1.0f}));
    assert_false(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){0, 0, 11, 0.5f}));
    assert_true(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){0, 0, 11, 1.5f}));
    /* side: (10, 0, 5) is cos30 * 10 - sin30 * 5 = 6.160 from the side */
    assert_false(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){10, 0, 5, 6.1f}));
    assert_true(sm_cone_sphere_intersects(o, z, a30, 10.0f, (vec4){10, 0, 5, 6.2f}));
    /* A thin cone (0.01 degrees) still sees a tiny sphere on its (oblique) axis far away:
     * the perpendicular distance is 900 * tan(0.01 deg) = 0.157 inside; computed as
     * sqrt(|v|^2 - a^2) it would carry an error of ~sqrt(u) |v| = 0.2 and miss it. */
    vec3 obl = {1, 2, 3};
    vec4 far_s;
    glm_vec3_normalize(obl);
    glm_vec3_scale(obl, 900.0f, far_s);
    far_s[3] = 1e-3f;
    assert_true(sm_cone_sphere_intersects(o, obl, sm_deg2rad(0.01f), 1000.0f, far_s));
    /* wider than a half-space (120 degrees): 101 degrees off the axis, behind the apex
     * plane, is inside; straight behind is 5 sin 60 = 4.33 outside */
    float a120 = sm_deg2rad(120.0f);
    assert_true(sm_cone_sphere_intersects(o, z, a120, 10.0f, (vec4){5, 0, -1, 0.1f}));
    assert_false(sm_cone_sphere_intersects(o, z, sm_deg2rad(60.0f), 10.0f, (vec4){5, 0, -1, 0.1f}));
    assert_false(sm_cone_sphere_intersects(o, z, a120, 10.0f, (vec4){0, 0, -5, 4.3f}));
    assert_true(sm_cone_sphere_intersects(o, z, a120, 10.0f, (vec4){0, 0, -5, 4.4f}));
    /* exactly a half-space */
    assert_true(sm_cone_sphere_intersects(o, z, SM_PI_2, 10.0f, (vec4){3, 0, -0.05f, 0.1f}));
    assert_false(sm_cone_sphere_intersects(o, z, SM_PI_2, 10.0f, (vec4){3, 0, -0.2f, 0.1f}));
    /* infinite height: no cap; NaN angle counts as 0 (a ray) */
    assert_true(sm_cone_sphere_intersects(o, z, a30, INFINITY, (vec4){0, 0, 1e6f, 1.0f}));
    assert_true(sm_cone_sphere_intersects(o, z, NAN, 10.0f, (vec4){0, 0.5f, 5, 0.6f}));
    assert_false(sm_cone_sphere_intersects(o, z, NAN, 10.0f, (vec4){0, 0.5f, 5, 0.4f}));
}

static void test_scalars(void **state)
{
    (void)state;
    NEAR(sm_deg2rad(180.0f), PI_D, 2.0 * U * PI_D, "deg2rad", 0);
    NEAR(sm_rad2deg(SM_PI / 2.0f), 90.0, 2.0 * U * 90.0, "rad2deg", 0);
    NEAR(SM_PI, PI_D, U * PI_D, "SM_PI", 0);
    NEAR(sm_clamp(5.0f, 0.0f, 1.0f), 1.0, 0.0, "clamp hi", 0);
    NEAR(sm_clamp(-5.0f, 0.0f, 1.0f), 0.0, 0.0, "clamp lo", 0);
    NEAR(sm_clamp(NAN, 0.0f, 1.0f), 0.0, 0.0, "clamp NaN", 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scalars),
        cmocka_unit_test(test_vec_ops_vs_cglm),
        cmocka_unit_test(test_vec_aliasing),
        cmocka_unit_test(test_vec_degenerate),
        cmocka_unit_test(test_mat4_products_vs_cglm),
        cmocka_unit_test(test_mat4_aliasing),
        cmocka_unit_test(test_mat4_inv_det_vs_cglm),
        cmocka_unit_test(test_mat4_inv_exact_and_degenerate),
        cmocka_unit_test(test_mat4_rotate_trs_vs_cglm),
        cmocka_unit_test(test_mat4_normal),
        cmocka_unit_test(test_mat3_vs_cglm),
        cmocka_unit_test(test_camera_vs_cglm),
        cmocka_unit_test(test_camera_exact),
        cmocka_unit_test(test_lookat_degenerate),
        cmocka_unit_test(test_frustum_planes),
        cmocka_unit_test(test_frustum_culling),
        cmocka_unit_test(test_intersections),
        cmocka_unit_test(test_cone_sphere),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
