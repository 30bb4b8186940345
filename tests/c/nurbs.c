/* NURBS handles through the C contract (shared/spec/c-api.md, "NURBS
 * curves"): every new function with each of its error statuses, and the
 * NURBS rules of the curve functions (degree, dim, points, eval, eval_many,
 * elevate, split, segment, reverse, length), of bzj_connect and
 * bzj_connect_auto_scale, of intersection and the fillets (bzj_fillet,
 * bzj_fillet_vertex, bzj_fillet_chain) and of the B-spline merge
 * (bzj_merge, bzj_merge_to_degree, bzj_merge_chain). Values are judged by
 * an independent rational de Boor evaluator written here. Compiled as C11 and as C++17 by tests/tests/c_programs.rs
 * (linked with libbezjoin.a) and run under valgrind memcheck by
 * scripts/ci-embedding.sh: every handle is released. Exits 0 when every
 * check passes. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bezjoin.h"

static int failures = 0;

#define CHECK(cond, ...)                                                     \
    do {                                                                     \
        if (!(cond)) {                                                       \
            failures++;                                                      \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);             \
            fprintf(stderr, __VA_ARGS__);                                    \
            fprintf(stderr, " (last error: %s)\n", bzj_last_error());        \
        }                                                                    \
    } while (0)

#define EXPECT_STATUS(call, expected)                                         \
    do {                                                                      \
        BzjStatus s_ = (call);                                                \
        CHECK(s_ == (expected), "%s returned %d (%s), expected %s", #call,    \
              (int)s_, bzj_status_name((int32_t)s_), #expected);              \
    } while (0)

static const double PI = 3.14159265358979323846;

/* The message must mention `word`. */
static void expect_message(const char* word) {
    const char* m = bzj_last_error();
    CHECK(m != NULL && strstr(m, word) != NULL, "message '%s' does not name '%s'",
          m ? m : "(null)", word);
}

/* A non-NULL address that is no handle: an out-pointer's slot must be
   cleared on every error. */
static BzjCurve* garbage(void) { return (BzjCurve*)&failures; }

/* ---- an independent evaluator: rational de Boor on homogeneous points ---- */

enum { MAX_P = 8, MAX_DIM = 3 };

typedef struct Spline {
    size_t dim, degree, count;  /* count: poles */
    const double* poles;        /* count * dim */
    const double* weights;      /* count, or NULL */
    const double* knots;        /* count + degree + 1 */
} Spline;

/* C(u) from the span on the right of u (the left at the domain's end). */
static void de_boor(const Spline* s, double u, double* out) {
    size_t p = s->degree, k = p;
    while (k + 1 < s->count && s->knots[k + 1] <= u) {
        k++;
    }
    double d[MAX_P + 1][MAX_DIM + 1];
    for (size_t j = 0; j <= p; j++) {
        size_t i = j + k - p;
        double w = s->weights ? s->weights[i] : 1.0;
        for (size_t c = 0; c < s->dim; c++) {
            d[j][c] = w * s->poles[i * s->dim + c];
        }
        d[j][s->dim] = w;
    }
    for (size_t r = 1; r <= p; r++) {
        for (size_t j = p; j >= r; j--) {
            double lo = s->knots[j + k - p], hi = s->knots[j + 1 + k - r];
            double a = (u - lo) / (hi - lo);
            for (size_t c = 0; c <= s->dim; c++) {
                d[j][c] = (1.0 - a) * d[j - 1][c] + a * d[j][c];
            }
        }
    }
    for (size_t c = 0; c < s->dim; c++) {
        out[c] = d[p][c] / d[p][s->dim];
    }
}

/* ---- helpers over the C API ---- */

static BzjCurve* nurbs(const Spline* s) {
    BzjCurve* c = NULL;
    EXPECT_STATUS(bzj_nurbs_new(s->dim, s->degree, s->poles, s->count * s->dim, s->weights,
                                s->weights ? s->count : 0, s->knots,
                                s->count + s->degree + 1, &c),
                  BZJ_OK);
    CHECK(c != NULL, "bzj_nurbs_new gave a handle");
    return c;
}

static void eval(const BzjCurve* c, double t, size_t order, size_t dim, double* out) {
    EXPECT_STATUS(bzj_curve_eval(c, t, order, out, (order + 1) * dim), BZJ_OK);
}

static void domain(const BzjCurve* c, double* first, double* last) {
    *first = *last = NAN;
    EXPECT_STATUS(bzj_curve_domain(c, first, last), BZJ_OK);
}

static int is_nurbs(const BzjCurve* c) {
    bool out = false;
    EXPECT_STATUS(bzj_curve_is_nurbs(c, &out), BZJ_OK);
    return out ? 1 : 0;
}

static double distance(const double* a, const double* b, size_t dim) {
    double s = 0.0;
    for (size_t c = 0; c < dim; c++) {
        s += (a[c] - b[c]) * (a[c] - b[c]);
    }
    return sqrt(s);
}

static double norm(const double* a, size_t dim) {
    double s = 0.0;
    for (size_t c = 0; c < dim; c++) {
        s += a[c] * a[c];
    }
    return sqrt(s);
}

/* `piece` equals `whole` at the same parameters (values and first
   derivatives) at 23 points inside the piece's domain, away from the ends. */
static void expect_same_parameters(const BzjCurve* piece, const BzjCurve* whole, size_t dim,
                                   const char* what) {
    double a, b;
    domain(piece, &a, &b);
    for (int i = 0; i < 23; i++) {
        double u = a + (b - a) * (i + 0.41) / 23.0;
        double x[2 * MAX_DIM], y[2 * MAX_DIM];
        eval(piece, u, 1, dim, x);
        eval(whole, u, 1, dim, y);
        double e0 = distance(x, y, dim), e1 = distance(x + dim, y + dim, dim);
        CHECK(e0 <= 1e-12 * (1.0 + norm(y, dim)), "%s: value at %g differs by %g", what, u, e0);
        CHECK(e1 <= 1e-10 * (1.0 + norm(y + dim, dim)), "%s: derivative at %g differs by %g",
              what, u, e1);
    }
}

/* ---- the curves of the tests ---- */

/* A rational quadratic of 5 poles, 3 spans [0,1], [1,2.5], [2.5,4]; the
   first span's weights are all 1 (a polynomial span), the others not. */
static const double RQ_POLES[] = {0, 0, 1, 2, 3, 3, 5, 1, 6, -1};
static const double RQ_WEIGHTS[] = {1.0, 1.0, 1.0, 0.5, 1.0};
static const double RQ_KNOTS[] = {0, 0, 0, 1, 2.5, 4, 4, 4};

/* An unclamped uniform cubic B-spline, 6 poles, domain [3, 6], 3 spans. */
static const double UC_POLES[] = {0, 0, 0, 1, 1, 1, 2, -1, 0, 3, 0, 2, 4, 2, 1, 5, 1, -1};
static const double UC_KNOTS[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};

/* A clamped cubic B-spline with a double interior knot (C1 there). */
static const double BS_POLES[] = {8, 0, 9, 1, 10, 3, 11, 2, 12, 0, 13, 1};
static const double BS_KNOTS[] = {0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1};

static Spline rq(void) {
    Spline s = {2, 2, 5, RQ_POLES, RQ_WEIGHTS, RQ_KNOTS};
    return s;
}
static Spline uc(void) {
    Spline s = {3, 3, 6, UC_POLES, NULL, UC_KNOTS};
    return s;
}
static Spline bs(void) {
    Spline s = {2, 3, 6, BS_POLES, NULL, BS_KNOTS};
    return s;
}

/* ---- bzj_nurbs_new ---- */

static void test_new(void) {
    const Spline s = rq();
    BzjCurve* c = nurbs(&s);
    size_t n = 0;
    EXPECT_STATUS(bzj_curve_degree(c, &n), BZJ_OK);
    CHECK(n == 2, "degree %zu", n);
    EXPECT_STATUS(bzj_curve_dim(c, &n), BZJ_OK);
    CHECK(n == 2, "dim %zu", n);
    EXPECT_STATUS(bzj_curve_pole_count(c, &n), BZJ_OK);
    CHECK(n == 5, "pole count %zu", n);
    double poles[10];
    EXPECT_STATUS(bzj_curve_points(c, poles, 10), BZJ_OK);
    CHECK(memcmp(poles, RQ_POLES, sizeof poles) == 0, "poles round trip");
    EXPECT_STATUS(bzj_curve_points(c, poles, 9), BZJ_ERR_BUFFER_TOO_SMALL);
    for (int i = 0; i <= 40; i++) {
        double u = 4.0 * i / 40.0, got[2], want[2];
        eval(c, u, 0, 2, got);
        de_boor(&s, u, want);
        CHECK(distance(got, want, 2) < 1e-13 * (1.0 + norm(want, 2)), "C(%g) off by %g", u,
              distance(got, want, 2));
    }

    /* Every error, and the out slot cleared each time. */
    const double* P = RQ_POLES;
    const double* W = RQ_WEIGHTS;
    const double* K = RQ_KNOTS;
    BzjCurve* bad = garbage();
    EXPECT_STATUS(bzj_nurbs_new(2, 2, P, 10, W, 5, K, 8, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("out");
    EXPECT_STATUS(bzj_nurbs_new(2, 2, NULL, 10, W, 5, K, 8, &bad), BZJ_ERR_NULL_POINTER);
    CHECK(bad == NULL, "out cleared (poles NULL)");
    expect_message("poles");
    bad = garbage();
    EXPECT_STATUS(bzj_nurbs_new(2, 2, P, 10, W, 5, NULL, 8, &bad), BZJ_ERR_NULL_POINTER);
    CHECK(bad == NULL, "out cleared (knots NULL)");
    expect_message("knots");
    bad = garbage();
    EXPECT_STATUS(bzj_nurbs_new(2, 2, P, 10, NULL, 5, K, 8, &bad), BZJ_ERR_NULL_POINTER);
    CHECK(bad == NULL, "out cleared (weights NULL)");
    expect_message("weights");
    struct {
        size_t dim, degree, poles_len, weights_len, knots_len;
        const char* word;
    } shapes[] = {
        {0, 2, 10, 5, 8, "dim"},
        {2, 0, 10, 5, 8, "degree"},
        {2, 4097, 10, 5, 8, "degree"},
        {2, 2, 9, 5, 8, "poles"},        /* not a multiple of dim */
        {2, 5, 10, 5, 11, "poles"},      /* 5 poles, fewer than degree + 1 */
        {2, 2, 10, 4, 8, "weights"},     /* weights_len neither 0 nor 5 */
        {2, 2, 10, 5, 7, "knots"},       /* knots_len not 5 + 2 + 1 */
        {2, 2, 10, 5, 9, "knots"},
        {1, 1, SIZE_MAX, 0, 8, "values are more than any array of doubles"},
        {1, 1, SIZE_MAX / 4, 0, SIZE_MAX / 4 + 2, "poles: "}, /* from the numbers alone */
        {2, 2, 10, 4, 7, "poles has 10 values, expected 8"}, /* weights and knots agree */
        {2, 2, SIZE_MAX - 1, 4, 7, "poles: "},
        {SIZE_MAX, 2, 10, 5, 8, "poles"},
    };
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        bad = garbage();
        EXPECT_STATUS(bzj_nurbs_new(shapes[i].dim, shapes[i].degree, P, shapes[i].poles_len, W,
                                    shapes[i].weights_len, K, shapes[i].knots_len, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        CHECK(bad == NULL, "out cleared (shape %zu)", i);
        expect_message(shapes[i].word);
    }
    {
        double p2[10], w2[5], k2[8];
        memcpy(p2, P, sizeof p2);
        memcpy(w2, W, sizeof w2);
        memcpy(k2, K, sizeof k2);
        p2[3] = NAN;
        bad = garbage();
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_NON_FINITE);
        CHECK(bad == NULL, "out cleared (NaN pole)");
        expect_message("poles[3]");
        p2[3] = P[3];
        w2[1] = INFINITY;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_NON_FINITE);
        expect_message("weights[1]");
        w2[1] = 0.0;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("weights[1]");
        w2[1] = -1.0;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("weights[1]");
        w2[1] = W[1];
        k2[5] = NAN;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_NON_FINITE);
        expect_message("knots[5]");
        k2[5] = 0.5; /* decreasing */
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p2, 10, w2, 5, k2, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("knots");
        expect_message("decrease");
        CHECK(bad == NULL, "out cleared (bad knots)");
    }
    {
        /* Interior multiplicity 3 > degree 2. */
        const double k3[] = {0, 0, 0, 1, 1, 1, 4, 4, 4};
        const double p3[] = {0, 0, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0};
        bad = garbage();
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p3, 12, NULL, 0, k3, 9, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("interior knot 1 has multiplicity 3");
        /* End multiplicity 4 > degree + 1. */
        const double k4[] = {0, 0, 0, 0, 1, 2, 2, 2, 2};
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p3, 12, NULL, 0, k4, 9, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("end knot 0 has multiplicity 4");
        /* An empty domain [knots[2], knots[3]] = [2, 2]. */
        const double k5[] = {0, 1, 2, 2, 3, 4};
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p3, 6, NULL, 0, k5, 6, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("empty");
        /* An interval whose reciprocal overflows. */
        const double k6[] = {0, 0, 5e-324, 5e-324};
        EXPECT_STATUS(bzj_nurbs_new(2, 1, p3, 4, NULL, 0, k6, 4, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("too short");
        /* Finite knots whose span overflows (9e307 - -9e307), and a domain
           whose ends' sum does (the map of reverse): both refused; 8.9e307
           is answered, P(0) = (1.5, 0.5) as on [-1, 1]. */
        const double wide[] = {-9e307, -9e307, -9e307, 0, 9e307, 9e307, 9e307};
        const double pw[] = {0, 0, 1, 1, 2, 0, 3, 1};
        EXPECT_STATUS(bzj_nurbs_new(2, 2, pw, 8, NULL, 0, wide, 7, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("too far apart");
        const double high[] = {1e308, 1e308, 1e308, 1.5e308, 1.7e308, 1.7e308, 1.7e308};
        EXPECT_STATUS(bzj_nurbs_new(2, 2, pw, 8, NULL, 0, high, 7, &bad), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("too far apart");
        CHECK(bad == NULL, "out cleared (bad knot vectors)");
        const double fits[] = {-8.9e307, -8.9e307, -8.9e307, 0, 8.9e307, 8.9e307, 8.9e307};
        BzjCurve* wide_ok = NULL;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, pw, 8, NULL, 0, fits, 7, &wide_ok), BZJ_OK);
        double at0[2] = {0, 0};
        EXPECT_STATUS(bzj_curve_eval(wide_ok, 0.0, 0, at0, 2), BZJ_OK);
        CHECK(fabs(at0[0] - 1.5) <= 1e-12 && fabs(at0[1] - 0.5) <= 1e-12, "P(0) = (%g, %g)",
              at0[0], at0[1]);
        bzj_curve_free(wide_ok);
        /* weights_len == 0: no weights, `weights` not read. */
        BzjCurve* poly = NULL;
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p3, 12, (const double*)&failures, 0,
                                    k4 + 1, 7, &poly),
                      BZJ_ERR_INVALID_ARGUMENT); /* 7 knots for 6 poles: refused */
        const double k7[] = {0, 0, 0, 1, 2, 3, 4, 4, 4};
        EXPECT_STATUS(bzj_nurbs_new(2, 2, p3, 12, (const double*)&failures, 0, k7, 9, &poly),
                      BZJ_OK);
        bool rational = true;
        EXPECT_STATUS(bzj_curve_is_rational(poly, &rational), BZJ_OK);
        CHECK(!rational, "no weights: not rational");
        bzj_curve_free(poly);
    }
    bzj_curve_free(c);
}

/* ---- the inspection functions ---- */

static void test_inspection(void) {
    const Spline s = rq();
    BzjCurve* c = nurbs(&s);
    const double bez_points[] = {0, 0, 1, 2, 3, 3, 4, 0};
    BzjCurve* b = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 3, bez_points, 8, &b), BZJ_OK);
    const double equal_w[] = {2.0, 2.0, 2.0, 2.0, 2.0};
    Spline sw = s;
    sw.weights = equal_w;
    BzjCurve* cw = nurbs(&sw);

    bool flag = false;
    EXPECT_STATUS(bzj_curve_is_nurbs(c, &flag), BZJ_OK);
    CHECK(flag, "a NURBS handle");
    EXPECT_STATUS(bzj_curve_is_nurbs(b, &flag), BZJ_OK);
    CHECK(!flag, "a Bezier handle");
    EXPECT_STATUS(bzj_curve_is_rational(c, &flag), BZJ_OK);
    CHECK(flag, "rational");
    EXPECT_STATUS(bzj_curve_is_rational(b, &flag), BZJ_OK);
    CHECK(!flag, "a Bezier is not rational");
    EXPECT_STATUS(bzj_curve_is_rational(cw, &flag), BZJ_OK);
    CHECK(!flag, "equal weights: not rational");
    EXPECT_STATUS(bzj_curve_is_nurbs(NULL, &flag), BZJ_ERR_NULL_POINTER);
    expect_message("c is a null pointer");
    EXPECT_STATUS(bzj_curve_is_nurbs(c, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("out");
    EXPECT_STATUS(bzj_curve_is_rational(NULL, &flag), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_is_rational(c, NULL), BZJ_ERR_NULL_POINTER);

    size_t n = 0;
    EXPECT_STATUS(bzj_curve_pole_count(b, &n), BZJ_OK);
    CHECK(n == 4, "Bezier pole count %zu", n);
    EXPECT_STATUS(bzj_curve_pole_count(NULL, &n), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_pole_count(c, NULL), BZJ_ERR_NULL_POINTER);

    /* knots: size query, short buffer, NULL buffer, values. */
    double knots[12];
    size_t count = 0;
    EXPECT_STATUS(bzj_curve_knots(c, NULL, 0, &count), BZJ_OK);
    CHECK(count == 8, "knot count %zu", count);
    for (int i = 0; i < 12; i++) {
        knots[i] = -7.0;
    }
    count = 0;
    EXPECT_STATUS(bzj_curve_knots(c, knots, 7, &count), BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(count == 8, "count written on BUFFER_TOO_SMALL: %zu", count);
    CHECK(knots[0] == -7.0 && knots[6] == -7.0, "nothing written on BUFFER_TOO_SMALL");
    expect_message("out");
    count = 0;
    EXPECT_STATUS(bzj_curve_knots(c, knots, 0, &count), BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(count == 8 && knots[0] == -7.0, "a real buffer of length 0 is too small");
    EXPECT_STATUS(bzj_curve_knots(c, NULL, 8, &count), BZJ_ERR_NULL_POINTER);
    expect_message("out");
    EXPECT_STATUS(bzj_curve_knots(NULL, knots, 12, &count), BZJ_ERR_NULL_POINTER);
    expect_message("c is a null pointer");
    EXPECT_STATUS(bzj_curve_knots(c, knots, 12, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("count");
    CHECK(knots[0] == -7.0, "nothing written on NULL count");
    EXPECT_STATUS(bzj_curve_knots(c, knots, 12, &count), BZJ_OK);
    CHECK(count == 8 && memcmp(knots, RQ_KNOTS, sizeof RQ_KNOTS) == 0 && knots[8] == -7.0,
          "knots round trip");
    EXPECT_STATUS(bzj_curve_knots(b, knots, 12, &count), BZJ_OK);
    CHECK(count == 8, "Bezier knot count %zu", count);
    for (int i = 0; i < 8; i++) {
        CHECK(knots[i] == (i < 4 ? 0.0 : 1.0), "Bezier knot %d = %g", i, knots[i]);
    }

    /* weights */
    double w[6] = {-1, -1, -1, -1, -1, -1};
    EXPECT_STATUS(bzj_curve_weights(c, w, 4), BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(w[0] == -1.0, "nothing written on BUFFER_TOO_SMALL");
    EXPECT_STATUS(bzj_curve_weights(c, NULL, 5), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_weights(NULL, w, 5), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_weights(c, w, 6), BZJ_OK);
    CHECK(memcmp(w, RQ_WEIGHTS, sizeof RQ_WEIGHTS) == 0 && w[5] == -1.0, "weights round trip");
    EXPECT_STATUS(bzj_curve_weights(cw, w, 5), BZJ_OK);
    for (int i = 0; i < 5; i++) {
        CHECK(w[i] == 1.0, "equal weights are reported as 1: w[%d] = %g", i, w[i]);
    }
    EXPECT_STATUS(bzj_curve_weights(b, w, 4), BZJ_OK);
    CHECK(w[0] == 1.0 && w[3] == 1.0, "Bezier weights 1");
    {
        /* Reported weights give the same curve. */
        BzjCurve* again = NULL;
        double poles[10];
        EXPECT_STATUS(bzj_curve_points(cw, poles, 10), BZJ_OK);
        EXPECT_STATUS(bzj_nurbs_new(2, 2, poles, 10, w, 5, RQ_KNOTS, 8, &again), BZJ_OK);
        expect_same_parameters(again, cw, 2, "equal weights rebuilt");
        bzj_curve_free(again);
    }

    /* domain */
    double first = -1, last = -1;
    EXPECT_STATUS(bzj_curve_domain(c, &first, &last), BZJ_OK);
    CHECK(first == 0.0 && last == 4.0, "domain [%g, %g]", first, last);
    EXPECT_STATUS(bzj_curve_domain(b, &first, &last), BZJ_OK);
    CHECK(first == 0.0 && last == 1.0, "Bezier domain [%g, %g]", first, last);
    first = last = -1;
    EXPECT_STATUS(bzj_curve_domain(NULL, &first, &last), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_domain(c, NULL, &last), BZJ_ERR_NULL_POINTER);
    expect_message("first");
    EXPECT_STATUS(bzj_curve_domain(c, &first, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("last");
    CHECK(first == -1.0 && last == -1.0, "nothing written on error");
    {
        const Spline u = uc();
        BzjCurve* cu = nurbs(&u);
        domain(cu, &first, &last);
        CHECK(first == 3.0 && last == 6.0, "unclamped domain [%g, %g]", first, last);
        bzj_curve_free(cu);
    }

    /* to_nurbs */
    BzjCurve* bn = garbage();
    EXPECT_STATUS(bzj_curve_to_nurbs(NULL, &bn), BZJ_ERR_NULL_POINTER);
    CHECK(bn == NULL, "out cleared");
    EXPECT_STATUS(bzj_curve_to_nurbs(b, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_to_nurbs(b, &bn), BZJ_OK);
    CHECK(is_nurbs(bn), "to_nurbs gives a NURBS handle");
    expect_same_parameters(bn, b, 2, "to_nurbs of a Bezier");
    EXPECT_STATUS(bzj_curve_knots(bn, knots, 12, &count), BZJ_OK);
    CHECK(count == 8 && knots[3] == 0.0 && knots[4] == 1.0, "to_nurbs knots");
    BzjCurve* cn = NULL;
    EXPECT_STATUS(bzj_curve_to_nurbs(c, &cn), BZJ_OK);
    expect_same_parameters(cn, c, 2, "to_nurbs of a NURBS");
    {
        const double point[] = {1.5, -2.5};
        BzjCurve* dot = NULL;
        BzjCurve* dn = NULL;
        EXPECT_STATUS(bzj_curve_new(2, 0, point, 2, &dot), BZJ_OK);
        EXPECT_STATUS(bzj_curve_to_nurbs(dot, &dn), BZJ_OK);
        EXPECT_STATUS(bzj_curve_degree(dn, &n), BZJ_OK);
        CHECK(n == 1, "a point becomes degree 1: %zu", n);
        double v[2];
        eval(dn, 0.7, 0, 2, v);
        /* Evaluated as the degree-1 Bezier curve of two equal poles (the
           Bezier kernel, not a convex combination): the point to rounding. */
        CHECK(fabs(v[0] - 1.5) <= 4.0 * DBL_EPSILON * 1.5 && fabs(v[1] + 2.5) <= 4.0 * DBL_EPSILON * 2.5,
              "the point (%.17g, %.17g)", v[0], v[1]);
        bzj_curve_free(dn);
        bzj_curve_free(dot);
    }
    bzj_curve_free(cn);
    bzj_curve_free(bn);
    bzj_curve_free(cw);
    bzj_curve_free(b);
    bzj_curve_free(c);
}

/* ---- bzj_curve_bezier_spans ---- */

/* The spans of `c` (domain knots `breaks`, `n` spans) evaluate equal to it:
   a Bezier span at s, the curve at a + (b - a) s, with derivatives scaled
   by (b - a)^k; a NURBS span at the same parameter. */
static void expect_spans(const BzjCurve* c, size_t dim, const double* breaks, size_t n,
                         int expect_bezier_mask, const char* what) {
    BzjCurve* spans[8];
    size_t count = 0;
    EXPECT_STATUS(bzj_curve_bezier_spans(c, NULL, 0, &count), BZJ_OK);
    CHECK(count == n, "%s: %zu spans, expected %zu", what, count, n);
    if (count != n || n > 8) {
        return;
    }
    EXPECT_STATUS(bzj_curve_bezier_spans(c, spans, 8, &count), BZJ_OK);
    for (size_t i = 0; i < n; i++) {
        int bezier = !is_nurbs(spans[i]);
        CHECK(bezier == ((expect_bezier_mask >> i) & 1), "%s: span %zu Bezier = %d", what, i,
              bezier);
        double a = breaks[i], b = breaks[i + 1], first, last;
        domain(spans[i], &first, &last);
        if (bezier) {
            CHECK(first == 0.0 && last == 1.0, "%s: Bezier span on [0, 1]", what);
        } else {
            CHECK(first == a && last == b, "%s: span %zu domain [%g, %g], expected [%g, %g]",
                  what, i, first, last, a, b);
        }
        for (int j = 0; j <= 10; j++) {
            double s = (j + 0.5) / 11.0, u = a + (b - a) * s;
            double x[2 * MAX_DIM], y[2 * MAX_DIM];
            eval(spans[i], bezier ? s : u, 1, dim, x);
            eval(c, u, 1, dim, y);
            double factor = bezier ? 1.0 / (b - a) : 1.0;
            for (size_t k = 0; k < dim; k++) {
                x[dim + k] *= factor;
            }
            CHECK(distance(x, y, dim) < 1e-12 * (1.0 + norm(y, dim)),
                  "%s: span %zu at %g: value off by %g", what, i, u, distance(x, y, dim));
            CHECK(distance(x + dim, y + dim, dim) < 1e-10 * (1.0 + norm(y + dim, dim)),
                  "%s: span %zu at %g: derivative off by %g", what, i, u,
                  distance(x + dim, y + dim, dim));
        }
        bzj_curve_free(spans[i]);
    }
}

static void test_spans(void) {
    const Spline s = rq();
    BzjCurve* c = nurbs(&s);
    const double rq_breaks[] = {0, 1, 2.5, 4};
    /* Span 0 has weights 1, 1, 1: a Bezier handle; spans 1, 2 rational. */
    expect_spans(c, 2, rq_breaks, 3, 1, "rational quadratic");
    const Spline u = uc();
    BzjCurve* cu = nurbs(&u);
    const double uc_breaks[] = {3, 4, 5, 6};
    expect_spans(cu, 3, uc_breaks, 3, 7, "unclamped cubic");
    const Spline p = bs();
    BzjCurve* cb = nurbs(&p);
    const double bs_breaks[] = {0, 0.5, 1};
    expect_spans(cb, 2, bs_breaks, 2, 3, "cubic with a double knot");
    const double bez_points[] = {0, 0, 1, 2, 3, 3, 4, 0};
    BzjCurve* b = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 3, bez_points, 8, &b), BZJ_OK);
    const double bez_breaks[] = {0, 1};
    expect_spans(b, 2, bez_breaks, 1, 1, "Bezier");

    /* Errors: short capacity (slots cleared, none written), NULLs. */
    BzjCurve* slots[3] = {garbage(), garbage(), garbage()};
    size_t count = 0;
    EXPECT_STATUS(bzj_curve_bezier_spans(c, slots, 2, &count), BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(count == 3, "count written on BUFFER_TOO_SMALL: %zu", count);
    CHECK(slots[0] == NULL && slots[1] == NULL, "the 2 slots cleared, no handle written");
    CHECK(slots[2] == garbage(), "no slot beyond the capacity touched");
    expect_message("out");
    slots[0] = garbage();
    EXPECT_STATUS(bzj_curve_bezier_spans(c, slots, 0, &count), BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(slots[0] == garbage(), "capacity 0: nothing touched");
    count = 0;
    EXPECT_STATUS(bzj_curve_bezier_spans(c, NULL, 3, &count), BZJ_ERR_NULL_POINTER);
    CHECK(count == 3, "count written before the NULL out is refused");
    expect_message("out");
    slots[0] = garbage();
    EXPECT_STATUS(bzj_curve_bezier_spans(NULL, slots, 1, &count), BZJ_ERR_NULL_POINTER);
    CHECK(slots[0] == NULL, "slot cleared on NULL c");
    expect_message("c is a null pointer");
    slots[0] = garbage();
    EXPECT_STATUS(bzj_curve_bezier_spans(c, slots, 1, NULL), BZJ_ERR_NULL_POINTER);
    CHECK(slots[0] == NULL, "slot cleared on NULL count");
    expect_message("count");
    bzj_curve_free(b);
    bzj_curve_free(cb);
    bzj_curve_free(cu);
    bzj_curve_free(c);
}

/* ---- bzj_nurbs_ellipse_arc ---- */

static void test_ellipse(void) {
    const double centre[] = {1.0, -2.0};
    const double x_axis[] = {1.0, 0.0};
    const double y_axis[] = {0.0, 1.0};
    BzjCurve* quarter = NULL;
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, y_axis, 2.0, 2.0, 0.0, PI / 2,
                                        &quarter),
                  BZJ_OK);
    double first, last, v[6];
    domain(quarter, &first, &last);
    CHECK(first == 0.0 && last == PI / 2, "quarter domain [%g, %g]", first, last);
    bool rational = false;
    EXPECT_STATUS(bzj_curve_is_rational(quarter, &rational), BZJ_OK);
    CHECK(rational, "a circle arc is rational");
    size_t n = 0;
    EXPECT_STATUS(bzj_curve_degree(quarter, &n), BZJ_OK);
    CHECK(n == 2, "conics are quadratic: %zu", n);
    double worst = 0.0;
    for (int i = 0; i <= 200; i++) {
        eval(quarter, PI / 2 * i / 200.0, 0, 2, v);
        double r = hypot(v[0] - 1.0, v[1] + 2.0);
        worst = fmax(worst, fabs(r - 2.0));
    }
    CHECK(worst <= 1e-14 * 2.0, "quarter circle off the circle by %g (radius 2)", worst);
    eval(quarter, 0.0, 0, 2, v);
    CHECK(fabs(v[0] - 3.0) < 1e-15 && fabs(v[1] + 2.0) < 1e-15, "starts at angle 0");
    eval(quarter, PI / 2, 0, 2, v);
    CHECK(fabs(v[0] - 1.0) < 1e-15 && fabs(v[1] - 0.0) < 1e-15, "ends at angle pi/2");
    /* Arc length: a quarter of the circle of radius 2 is pi. */
    {
        double len = 0.0;
        EXPECT_STATUS(bzj_curve_length(quarter, 0.0, PI / 2, &len), BZJ_OK);
        CHECK(fabs(len - PI) < 1e-12 * PI, "quarter circle length %.17g vs pi", len);
    }
    /* Tangent at the start along +y. */
    eval(quarter, 0.0, 1, 2, v);
    CHECK(fabs(v[2]) < 1e-14 * fabs(v[3]) && v[3] > 0.0, "tangent (%g, %g)", v[2], v[3]);

    /* A 3D ellipse, and a full turn (closed). */
    const double c3[] = {0.5, 0.25, -1.0};
    const double s = sqrt(0.5);
    const double x3[] = {s, s, 0.0};
    const double y3[] = {0.0, 0.0, 1.0};
    BzjCurve* ellipse = NULL;
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(3, c3, x3, y3, 3.0, 1.5, -1.0, -1.0 + 2 * PI, &ellipse),
                  BZJ_OK);
    domain(ellipse, &first, &last);
    worst = 0.0;
    for (int i = 0; i <= 400; i++) {
        eval(ellipse, first + (last - first) * i / 400.0, 0, 3, v);
        double d[3] = {v[0] - c3[0], v[1] - c3[1], v[2] - c3[2]};
        double ex = (d[0] * x3[0] + d[1] * x3[1] + d[2] * x3[2]) / 3.0;
        double ey = (d[0] * y3[0] + d[1] * y3[1] + d[2] * y3[2]) / 1.5;
        double off_plane = d[0] * s - d[1] * s; /* along x3 x y3 */
        worst = fmax(worst, fmax(fabs(ex * ex + ey * ey - 1.0), fabs(off_plane)));
    }
    CHECK(worst < 1e-14 * 4, "ellipse off by %g", worst);
    eval(ellipse, first, 0, 3, v);
    eval(ellipse, last, 0, 3, v + 3);
    CHECK(distance(v, v + 3, 3) < 4e-15, "a full turn is closed (%g)", distance(v, v + 3, 3));
    size_t count = 0;
    EXPECT_STATUS(bzj_curve_bezier_spans(ellipse, NULL, 0, &count), BZJ_OK);
    CHECK(count == 4, "a full turn has 4 spans: %zu", count);

    /* Errors, each with the out slot cleared. */
    BzjCurve* bad = garbage();
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, y_axis, 2, 2, 0, 1, NULL),
                  BZJ_ERR_NULL_POINTER);
    expect_message("out");
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, NULL, x_axis, y_axis, 2, 2, 0, 1, &bad),
                  BZJ_ERR_NULL_POINTER);
    CHECK(bad == NULL, "out cleared");
    expect_message("centre");
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, NULL, y_axis, 2, 2, 0, 1, &bad),
                  BZJ_ERR_NULL_POINTER);
    expect_message("x_axis");
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, NULL, 2, 2, 0, 1, &bad),
                  BZJ_ERR_NULL_POINTER);
    expect_message("y_axis");
    struct {
        size_t dim;
        double rx, ry, a0, a1;
        BzjStatus status;
        const char* word;
    } cases[] = {
        {1, 2, 2, 0, 1, BZJ_ERR_INVALID_ARGUMENT, "dim"},
        {4, 2, 2, 0, 1, BZJ_ERR_INVALID_ARGUMENT, "dim"}, /* the 2-double arrays are not read */
        {SIZE_MAX, 2, 2, 0, 1, BZJ_ERR_INVALID_ARGUMENT, "dim"},
        {2, 0, 2, 0, 1, BZJ_ERR_INVALID_ARGUMENT, "x_radius"},
        {2, 2, -1, 0, 1, BZJ_ERR_INVALID_ARGUMENT, "y_radius"},
        {2, NAN, 2, 0, 1, BZJ_ERR_NON_FINITE, "x_radius"},
        {2, 2, INFINITY, 0, 1, BZJ_ERR_NON_FINITE, "y_radius"},
        {2, 2, 2, NAN, 1, BZJ_ERR_NON_FINITE, "a0"},
        {2, 2, 2, 0, INFINITY, BZJ_ERR_NON_FINITE, "a1"},
        {2, 2, 2, 1, 1, BZJ_ERR_INVALID_ARGUMENT, "a1"},
        {2, 2, 2, 1, 0.5, BZJ_ERR_INVALID_ARGUMENT, "a1"},
        {2, 2, 2, 0, 2 * 3.15, BZJ_ERR_INVALID_ARGUMENT, "a1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bad = garbage();
        EXPECT_STATUS(bzj_nurbs_ellipse_arc(cases[i].dim, centre, x_axis, y_axis, cases[i].rx,
                                            cases[i].ry, cases[i].a0, cases[i].a1, &bad),
                      cases[i].status);
        CHECK(bad == NULL, "out cleared (case %zu)", i);
        expect_message(cases[i].word);
    }
    {
        const double long_axis[] = {1.0, 0.1};
        const double skew_axis[] = {0.1, 0.99498743710662};
        const double nan_centre[] = {0.0, NAN};
        EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, long_axis, y_axis, 2, 2, 0, 1, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("x_axis");
        expect_message("unit");
        EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, skew_axis, 2, 2, 0, 1, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("orthogonal");
        EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, nan_centre, x_axis, y_axis, 2, 2, 0, 1, &bad),
                      BZJ_ERR_NON_FINITE);
        expect_message("centre[1]");
        CHECK(bad == NULL, "out cleared (bad vectors)");
    }
    bzj_curve_free(ellipse);
    bzj_curve_free(quarter);
}

/* ---- the curve functions on NURBS handles ---- */

static void test_eval(void) {
    const Spline s = rq();
    BzjCurve* c = nurbs(&s);
    const Spline u = uc();
    BzjCurve* cu = nurbs(&u);
    double v[8 * MAX_DIM];

    /* Values against de Boor on the unclamped curve (domain [3, 6]). */
    for (int i = 0; i <= 30; i++) {
        double t = 3.0 + 3.0 * i / 30.0, want[3];
        eval(cu, t, 0, 3, v);
        de_boor(&u, t, want);
        CHECK(distance(v, want, 3) < 1e-13 * (1.0 + norm(want, 3)), "unclamped C(%g)", t);
    }
    /* First derivative against a central difference, inside a span. */
    {
        double t = 1.7, h = 1e-5, lo[2], hi[2];
        eval(c, t, 1, 2, v);
        de_boor(&s, t - h, lo);
        de_boor(&s, t + h, hi);
        for (int k = 0; k < 2; k++) {
            double fd = (hi[k] - lo[k]) / (2 * h);
            CHECK(fabs(v[2 + k] - fd) < 1e-7 * (1.0 + fabs(fd)), "C'(1.7)[%d] %g vs %g", k,
                  v[2 + k], fd);
        }
    }
    /* Any max_order: a polynomial's derivatives above the degree are 0,
       a rational curve's are not. */
    eval(cu, 4.5, 6, 3, v);
    for (int k = 4; k <= 6; k++) {
        CHECK(norm(v + 3 * k, 3) == 0.0, "cubic derivative %d = 0", k);
    }
    CHECK(norm(v + 9, 3) > 0.0, "third derivative of the cubic is not 0");
    eval(c, 3.0, 5, 2, v);
    CHECK(norm(v + 2 * 5, 2) > 0.0, "5th derivative of the rational span is not 0");

    /* t outside the domain, NaN, short buffer, NULLs. */
    EXPECT_STATUS(bzj_curve_eval(cu, 2.5, 0, v, 3), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("t = 2.5");
    expect_message("[3, 6]");
    EXPECT_STATUS(bzj_curve_eval(cu, 6.000001, 0, v, 3), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("t");
    EXPECT_STATUS(bzj_curve_eval(c, -1e-300, 0, v, 2), BZJ_ERR_INVALID_ARGUMENT);
    EXPECT_STATUS(bzj_curve_eval(c, NAN, 0, v, 2), BZJ_ERR_NON_FINITE);
    expect_message("t");
    EXPECT_STATUS(bzj_curve_eval(c, 1.0, 2, v, 5), BZJ_ERR_BUFFER_TOO_SMALL);
    EXPECT_STATUS(bzj_curve_eval(c, 1.0, 0, NULL, 2), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_eval(c, 1.0, SIZE_MAX, v, 2), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("max_order");
    /* The ends of the domain are in it. */
    EXPECT_STATUS(bzj_curve_eval(cu, 3.0, 1, v, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(cu, 6.0, 1, v, 6), BZJ_OK);

    /* eval_many: every block as bzj_curve_eval, ts[i] checked and named. */
    {
        const double ts[] = {0.0, 0.5, 1.0, 2.5, 3.999, 4.0};
        double many[6 * 3 * 2], one[3 * 2];
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 6, 2, many, 36), BZJ_OK);
        for (int i = 0; i < 6; i++) {
            eval(c, ts[i], 2, 2, one);
            CHECK(memcmp(one, many + 6 * i, sizeof one) == 0, "eval_many block %d", i);
        }
        const double bad_ts[] = {0.5, 1.0, 4.5, -1.0};
        many[0] = -9.0;
        EXPECT_STATUS(bzj_curve_eval_many(c, bad_ts, 4, 0, many, 8), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("ts[2] = 4.5");
        CHECK(many[0] == -9.0, "nothing written when a parameter is refused");
        const double nan_ts[] = {0.5, 9.0, NAN};
        EXPECT_STATUS(bzj_curve_eval_many(c, nan_ts, 3, 0, many, 6), BZJ_ERR_NON_FINITE);
        expect_message("ts[2]");
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 6, 0, many, 11), BZJ_ERR_BUFFER_TOO_SMALL);
        EXPECT_STATUS(bzj_curve_eval_many(c, NULL, 0, 3, NULL, 0), BZJ_OK);
    }
    bzj_curve_free(cu);
    bzj_curve_free(c);
}

static void test_operations(void) {
    const Spline s = rq();
    BzjCurve* c = nurbs(&s);
    double first, last, v[4], w[4];

    /* elevate: every span raised, same curve, still rational. */
    BzjCurve* e = NULL;
    EXPECT_STATUS(bzj_curve_elevate(c, 4, &e), BZJ_OK);
    size_t n = 0;
    EXPECT_STATUS(bzj_curve_degree(e, &n), BZJ_OK);
    CHECK(n == 4, "elevated degree %zu", n);
    CHECK(is_nurbs(e), "elevated NURBS stays NURBS");
    bool rational = false;
    EXPECT_STATUS(bzj_curve_is_rational(e, &rational), BZJ_OK);
    CHECK(rational, "elevated rational stays rational");
    domain(e, &first, &last);
    CHECK(first == 0.0 && last == 4.0, "elevated domain [%g, %g]", first, last);
    expect_same_parameters(e, c, 2, "elevate");
    bzj_curve_free(e);
    {
        const Spline u = uc();
        BzjCurve* cu = nurbs(&u);
        EXPECT_STATUS(bzj_curve_elevate(cu, 5, &e), BZJ_OK);
        expect_same_parameters(e, cu, 3, "elevate unclamped");
        size_t count = 0;
        EXPECT_STATUS(bzj_curve_bezier_spans(e, NULL, 0, &count), BZJ_OK);
        CHECK(count == 3, "elevation keeps the 3 spans: %zu", count);
        bzj_curve_free(e);
        bzj_curve_free(cu);
    }
    EXPECT_STATUS(bzj_curve_elevate(c, 2, &e), BZJ_OK);
    expect_same_parameters(e, c, 2, "elevate to the same degree");
    bzj_curve_free(e);
    e = garbage();
    EXPECT_STATUS(bzj_curve_elevate(c, 1, &e), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(e == NULL, "out cleared (below the degree)");
    expect_message("new_degree");
    e = garbage();
    EXPECT_STATUS(bzj_curve_elevate(c, 4097, &e), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("new_degree");
    EXPECT_STATUS(bzj_curve_elevate(c, SIZE_MAX, &e), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(e == NULL, "out cleared (impossible degree)");
    expect_message("4096");
    EXPECT_STATUS(bzj_curve_elevate(c, 3, NULL), BZJ_ERR_NULL_POINTER);

    /* split keeps the parameters: [0, t] and [t, 4], inside a span and at a knot. */
    const double cuts[] = {1.7, 2.5};
    for (int i = 0; i < 2; i++) {
        BzjCurve *left = NULL, *right = NULL;
        EXPECT_STATUS(bzj_curve_split(c, cuts[i], &left, &right), BZJ_OK);
        CHECK(is_nurbs(left) && is_nurbs(right), "split pieces are NURBS");
        domain(left, &first, &last);
        CHECK(first == 0.0 && last == cuts[i], "left domain [%g, %g]", first, last);
        domain(right, &first, &last);
        CHECK(first == cuts[i] && last == 4.0, "right domain [%g, %g]", first, last);
        expect_same_parameters(left, c, 2, "split left");
        expect_same_parameters(right, c, 2, "split right");
        eval(left, cuts[i], 0, 2, v);
        eval(right, cuts[i], 0, 2, w);
        CHECK(distance(v, w, 2) < 1e-14 * (1.0 + norm(v, 2)), "pieces meet at %g", cuts[i]);
        bzj_curve_free(left);
        bzj_curve_free(right);
    }
    {
        BzjCurve *left = garbage(), *right = garbage();
        EXPECT_STATUS(bzj_curve_split(c, 0.0, &left, &right), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(left == NULL && right == NULL, "split outs cleared");
        expect_message("t = 0");
        expect_message("(0, 4)");
        EXPECT_STATUS(bzj_curve_split(c, 4.0, &left, &right), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("t = 4");
        EXPECT_STATUS(bzj_curve_split(c, 5.0, &left, &right), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("t");
        EXPECT_STATUS(bzj_curve_split(c, NAN, &left, &right), BZJ_ERR_NON_FINITE);
        expect_message("t = NaN");
        EXPECT_STATUS(bzj_curve_split(c, 1.0, &left, NULL), BZJ_ERR_NULL_POINTER);
        CHECK(left == NULL, "left cleared when right is NULL");
        expect_message("right");
        EXPECT_STATUS(bzj_curve_split(NULL, 1.0, &left, &right), BZJ_ERR_NULL_POINTER);
    }

    /* segment keeps the parameters: domain [a, b]. */
    const double ranges[][2] = {{0.3, 3.1}, {1.0, 2.5}, {0.0, 4.0}, {2.0, 4.0}};
    for (int i = 0; i < 4; i++) {
        BzjCurve* seg = NULL;
        EXPECT_STATUS(bzj_curve_segment(c, ranges[i][0], ranges[i][1], &seg), BZJ_OK);
        domain(seg, &first, &last);
        CHECK(first == ranges[i][0] && last == ranges[i][1], "segment domain [%g, %g]", first,
              last);
        expect_same_parameters(seg, c, 2, "segment");
        eval(seg, ranges[i][0], 0, 2, v);
        eval(c, ranges[i][0], 0, 2, w);
        CHECK(distance(v, w, 2) < 1e-14 * (1.0 + norm(w, 2)), "segment starts at C(a)");
        bzj_curve_free(seg);
    }
    {
        BzjCurve* seg = garbage();
        EXPECT_STATUS(bzj_curve_segment(c, 2.0, 2.0, &seg), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(seg == NULL, "segment out cleared");
        expect_message("b");
        EXPECT_STATUS(bzj_curve_segment(c, 3.0, 1.0, &seg), BZJ_ERR_INVALID_ARGUMENT);
        EXPECT_STATUS(bzj_curve_segment(c, -0.5, 1.0, &seg), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("a = -0.5");
        EXPECT_STATUS(bzj_curve_segment(c, 1.0, 4.5, &seg), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("b = 4.5");
        EXPECT_STATUS(bzj_curve_segment(c, 1.0, NAN, &seg), BZJ_ERR_NON_FINITE);
        expect_message("b");
        EXPECT_STATUS(bzj_curve_segment(c, 1.0, 2.0, NULL), BZJ_ERR_NULL_POINTER);
    }

    /* reverse: u -> first + last - u on the same domain. */
    {
        const Spline u = uc();
        BzjCurve* cu = nurbs(&u);
        BzjCurve* r = NULL;
        EXPECT_STATUS(bzj_curve_reverse(cu, &r), BZJ_OK);
        CHECK(is_nurbs(r), "reversed NURBS");
        domain(r, &first, &last);
        CHECK(first == 3.0 && last == 6.0, "reversed domain [%g, %g]", first, last);
        for (int i = 0; i <= 20; i++) {
            double t = 3.0 + 3.0 * (i + 0.3) / 21.0, a[6], b[6];
            eval(r, t, 1, 3, a);
            eval(cu, 9.0 - t, 1, 3, b);
            CHECK(distance(a, b, 3) < 1e-13 * (1.0 + norm(b, 3)), "R(%g) = C(%g)", t, 9.0 - t);
            for (int k = 0; k < 3; k++) {
                b[3 + k] = -b[3 + k];
            }
            CHECK(distance(a + 3, b + 3, 3) < 1e-11 * (1.0 + norm(b + 3, 3)),
                  "R'(%g) = -C'(%g)", t, 9.0 - t);
        }
        bzj_curve_free(r);
        bzj_curve_free(cu);
        EXPECT_STATUS(bzj_curve_reverse(c, NULL), BZJ_ERR_NULL_POINTER);
    }

    /* length: a and b in the domain, signed, additive over a split. */
    {
        double len = -3.0, part1 = 0.0, part2 = 0.0, back = 0.0;
        EXPECT_STATUS(bzj_curve_length(c, 0.0, 4.0, &len), BZJ_OK);
        EXPECT_STATUS(bzj_curve_length(c, 0.0, 1.7, &part1), BZJ_OK);
        EXPECT_STATUS(bzj_curve_length(c, 1.7, 4.0, &part2), BZJ_OK);
        EXPECT_STATUS(bzj_curve_length(c, 4.0, 0.0, &back), BZJ_OK);
        CHECK(fabs(part1 + part2 - len) < 1e-12 * len, "lengths add up: %.17g + %.17g vs %.17g",
              part1, part2, len);
        CHECK(back == -len, "signed length %g vs %g", back, len);
        /* The chord polygon through 4001 points is a lower bound, close. */
        double poly = 0.0, prev[2], cur[2];
        eval(c, 0.0, 0, 2, prev);
        for (int i = 1; i <= 4000; i++) {
            eval(c, 4.0 * i / 4000.0, 0, 2, cur);
            poly += distance(prev, cur, 2);
            prev[0] = cur[0];
            prev[1] = cur[1];
        }
        CHECK(poly <= len && len - poly < 1e-5 * len, "length %.17g, inscribed polygon %.17g",
              len, poly);
        double untouched = -3.0;
        EXPECT_STATUS(bzj_curve_length(c, -0.5, 2.0, &untouched), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("a = -0.5");
        EXPECT_STATUS(bzj_curve_length(c, 0.0, 4.5, &untouched), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("b = 4.5");
        EXPECT_STATUS(bzj_curve_length(c, NAN, 2.0, &untouched), BZJ_ERR_NON_FINITE);
        expect_message("a");
        EXPECT_STATUS(bzj_curve_length(c, 0.0, 2.0, NULL), BZJ_ERR_NULL_POINTER);
        CHECK(untouched == -3.0, "length untouched on error");
    }
    bzj_curve_free(c);
}

/* ---- connect: any curve, orders above the degree, jets from the sides ---- */

/* R^(k)(tr) = C^(k) from `jet` (order + 1 rows), k = 0..order. */
static void expect_jet(const BzjCurve* r, double tr, const double* jet, size_t order, size_t dim,
                       const char* what) {
    double rv[8 * MAX_DIM];
    eval(r, tr, order, dim, rv);
    for (size_t k = 0; k <= order; k++) {
        double e = distance(rv + k * dim, jet + k * dim, dim);
        double size = 1.0 + norm(jet + k * dim, dim);
        CHECK(e <= 1e-8 * size, "%s: derivative %zu off by %g (size %g)", what, k, e, size);
    }
}

static void test_connect(void) {
    /* P: a circle arc in 2D, 3 spans, ending at its knot pi/2 from the left. */
    const double centre[] = {0.0, 0.0};
    const double x_axis[] = {1.0, 0.0};
    const double y_axis[] = {0.0, 1.0};
    BzjCurve* arc = NULL;
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, y_axis, 1.0, 1.0, 0.0, 1.5 * PI, &arc),
                  BZJ_OK);
    /* Q: the cubic B-spline with a double knot at 0.5 (a C1 joint), left
       from its knot 0.5 to the right. */
    const Spline sq = bs();
    BzjCurve* q = nurbs(&sq);

    const size_t kp = 4, kq = 5; /* both above the degrees 2 and 3 */
    double knots[10];
    size_t knot_count = 0;
    EXPECT_STATUS(bzj_curve_knots(arc, knots, 10, &knot_count), BZJ_OK);
    CHECK(knot_count == 10 && fabs(knots[3] - PI / 2) < 1e-15, "the arc's knot %g", knots[3]);
    double u0 = knots[3], v0 = 0.5;
    /* P's jet from the left of u0: the piece on [0, u0] evaluated at its end.
       Q's jet from the right of v0: the curve evaluated at the knot. */
    double p_jet[8 * 2], q_jet[8 * 2], other[8 * 2];
    {
        BzjCurve *left = NULL, *right = NULL;
        EXPECT_STATUS(bzj_curve_split(arc, u0, &left, &right), BZJ_OK);
        eval(left, u0, kp, 2, p_jet);
        eval(arc, u0, kp, 2, other); /* the right side at the knot */
        double jump = distance(p_jet + 2 * 2, other + 2 * 2, 2);
        CHECK(jump > 1e-3, "the arc's second derivative jumps at its knot (%g)", jump);
        bzj_curve_free(left);
        bzj_curve_free(right);
    }
    eval(q, v0, kq, 2, q_jet);
    {
        BzjCurve *left = NULL, *right = NULL;
        EXPECT_STATUS(bzj_curve_split(q, v0, &left, &right), BZJ_OK);
        eval(left, v0, kq, 2, other); /* Q from the left, which must not be used */
        CHECK(distance(q_jet + 2 * 2, other + 2 * 2, 2) > 1e-3,
              "the B-spline's second derivative jumps at its double knot");
        bzj_curve_free(left);
        bzj_curve_free(right);
    }
    BzjConnectOptions options = {kp, kq, 1.0, 1.0, NULL, 0};
    BzjCurve* r = garbage();
    EXPECT_STATUS(bzj_connect(arc, u0, q, v0, &options, &r), BZJ_OK);
    CHECK(r != NULL && !is_nurbs(r), "connect gives a Bezier handle");
    size_t degree = 0;
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == kp + kq + 1, "degree %zu", degree);
    expect_jet(r, 0.0, p_jet, kp, 2, "R at 0 against P from the left");
    expect_jet(r, 1.0, q_jet, kq, 2, "R at 1 against Q from the right");
    bzj_curve_free(r);

    /* Inside a span (no side to choose), with scales. */
    options.p_order = 3;
    options.q_order = 4;
    options.p_scale = 0.5;
    options.q_scale = 2.0;
    EXPECT_STATUS(bzj_connect(arc, 4.0, q, 0.2, &options, &r), BZJ_OK);
    {
        double jet[8 * 2];
        eval(arc, 4.0, 3, 2, jet);
        for (int k = 0; k <= 3; k++) {
            jet[2 * k] *= pow(0.5, k);
            jet[2 * k + 1] *= pow(0.5, k);
        }
        expect_jet(r, 0.0, jet, 3, 2, "R at 0, alpha = 0.5");
        eval(q, 0.2, 4, 2, jet);
        for (int k = 0; k <= 4; k++) {
            jet[2 * k] *= pow(2.0, k);
            jet[2 * k + 1] *= pow(2.0, k);
        }
        expect_jet(r, 1.0, jet, 4, 2, "R at 1, beta = 2");
    }
    bzj_curve_free(r);

    /* A Bezier P with an order above its degree, connected to the arc. */
    {
        const double line_points[] = {-3.0, 0.0, -1.0, 0.5};
        BzjCurve* line = NULL;
        EXPECT_STATUS(bzj_curve_new(2, 1, line_points, 4, &line), BZJ_OK);
        BzjConnectOptions o = {3, 3, 1.0, 1.0, NULL, 0};
        EXPECT_STATUS(bzj_connect(line, 1.0, arc, 0.0, &o, &r), BZJ_OK);
        double jet[4 * 2];
        eval(line, 1.0, 3, 2, jet);
        expect_jet(r, 0.0, jet, 3, 2, "R at 0 against a line (derivatives 2, 3 are 0)");
        eval(arc, 0.0, 3, 2, jet);
        expect_jet(r, 1.0, jet, 3, 2, "R at 1 against the arc's start");
        bzj_curve_free(r);
        bzj_curve_free(line);
    }

    /* auto scale with NURBS handles. */
    double scale = 0.0;
    options.p_order = 2;
    options.q_order = 2;
    EXPECT_STATUS(bzj_connect_auto_scale(arc, 1.5 * PI, q, 0.0, &options, &r, &scale), BZJ_OK);
    CHECK(scale > 0.0 && r != NULL && !is_nurbs(r), "auto scale %g", scale);
    {
        double jet[3 * 2];
        eval(arc, 1.5 * PI, 2, 2, jet);
        for (int k = 0; k <= 2; k++) {
            jet[2 * k] *= pow(scale, k);
            jet[2 * k + 1] *= pow(scale, k);
        }
        expect_jet(r, 0.0, jet, 2, 2, "auto-scaled R at 0");
    }
    bzj_curve_free(r);

    /* u0, v0 outside each curve's domain. */
    r = garbage();
    EXPECT_STATUS(bzj_connect(arc, 5.0, q, 0.5, &options, &r), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(r == NULL, "out cleared");
    expect_message("u0 = 5");
    EXPECT_STATUS(bzj_connect(arc, 1.0, q, 1.5, &options, &r), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("v0 = 1.5");
    EXPECT_STATUS(bzj_connect(arc, NAN, q, 0.5, &options, &r), BZJ_ERR_NON_FINITE);
    expect_message("u0");
    EXPECT_STATUS(bzj_connect_auto_scale(arc, -0.1, q, 0.5, &options, &r, &scale),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("u0");
    {
        const Spline u3 = uc(); /* 3D */
        BzjCurve* c3 = nurbs(&u3);
        EXPECT_STATUS(bzj_connect(arc, 1.0, c3, 4.0, &options, &r), BZJ_ERR_DIMENSION_MISMATCH);
        CHECK(r == NULL, "out cleared");
        bzj_curve_free(c3);
    }
    bzj_curve_free(q);
    bzj_curve_free(arc);
}

/* ---- intersection and fillets of NURBS handles ---- */

static BzjCurve* circle_arc(double cx, double cy, double r, double a0, double a1) {
    const double centre[] = {cx, cy};
    const double x_axis[] = {1.0, 0.0};
    const double y_axis[] = {0.0, 1.0};
    BzjCurve* c = NULL;
    EXPECT_STATUS(bzj_nurbs_ellipse_arc(2, centre, x_axis, y_axis, r, r, a0, a1, &c), BZJ_OK);
    return c;
}

static BzjCurve* line(double x0, double y0, double x1, double y1) {
    const double points[] = {x0, y0, x1, y1};
    BzjCurve* c = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 1, points, 4, &c), BZJ_OK);
    return c;
}

static BzjFilletOptions fillet_options(double setback, size_t order) {
    BzjFilletOptions fo;
    memset(&fo, 0, sizeof fo);
    fo.p_setback = setback;
    fo.q_setback = setback;
    fo.p_order = order;
    fo.q_order = order;
    fo.p_scale = 1.0;
    fo.q_scale = 1.0;
    return fo;
}

/* The blend R joins P at u0 (R^(k)(0) = P^(k)(u0) with scale 1) and Q at
   v0 (R^(k)(1) = Q^(k)(v0)); u0 is the end of p_trimmed's domain, v0 the
   start of q_trimmed's (NURBS pieces keep the parameters: P and Q are
   NURBS handles here). */
static void expect_fillet_joins(const BzjCurve* p, const BzjCurve* q, const BzjCurve* pt,
                                const BzjCurve* bl, const BzjCurve* qt, size_t order,
                                const char* what) {
    CHECK(is_nurbs(pt) && is_nurbs(qt), "%s: NURBS inputs give NURBS pieces", what);
    double a, u0, v0, b;
    domain(pt, &a, &u0);
    domain(qt, &v0, &b);
    double jp[8], jq[8], r0[8], r1[8];
    eval(p, u0, order, 2, jp);
    eval(q, v0, order, 2, jq);
    eval(bl, 0.0, order, 2, r0);
    eval(bl, 1.0, order, 2, r1);
    for (size_t k = 0; k <= order; k++) {
        double size = fmax(1.0, norm(jp + 2 * k, 2));
        CHECK(distance(jp + 2 * k, r0 + 2 * k, 2) <= 1e-9 * size, "%s: P|R order %zu", what, k);
        size = fmax(1.0, norm(jq + 2 * k, 2));
        CHECK(distance(jq + 2 * k, r1 + 2 * k, 2) <= 1e-9 * size, "%s: R|Q order %zu", what, k);
    }
    /* the trimmed pieces are the inputs on their ranges */
    double x[2], y[2];
    for (int i = 0; i <= 8; i++) {
        double u = a + (u0 - a) * i / 8.0;
        eval(pt, u, 0, 2, x);
        eval(p, u, 0, 2, y);
        CHECK(distance(x, y, 2) <= 1e-12, "%s: p_trimmed at %g", what, u);
        double v = v0 + (b - v0) * i / 8.0;
        eval(qt, v, 0, 2, x);
        eval(q, v, 0, 2, y);
        CHECK(distance(x, y, 2) <= 1e-12, "%s: q_trimmed at %g", what, v);
    }
}

static void test_intersect_and_fillet(void) {
    /* A full circle (centre (1, 2), radius 3) and the line y = 2.5: two
       crossings at x = 1 -+ sqrt(8.75), v in the circle's domain. */
    BzjCurve* full = circle_arc(1.0, 2.0, 3.0, 0.0, 2.0 * PI);
    BzjCurve* l = line(-5.0, 2.5, 7.0, 2.5);
    double pairs[8];
    size_t count = 0;
    EXPECT_STATUS(bzj_intersect(l, full, pairs, 4, &count), BZJ_OK);
    CHECK(count == 2, "line x circle: %zu hits", count);
    for (size_t i = 0; i < count && i < 2; i++) {
        double x[2], y[2];
        eval(l, pairs[2 * i], 0, 2, x);
        eval(full, pairs[2 * i + 1], 0, 2, y);
        CHECK(distance(x, y, 2) <= 1e-12, "hit %zu: the curves meet", i);
        double want = i == 0 ? 1.0 - sqrt(8.75) : 1.0 + sqrt(8.75);
        CHECK(fabs(x[0] - want) <= 1e-12 && fabs(x[1] - 2.5) <= 1e-12, "hit %zu at x = %g", i,
              x[0]);
        CHECK(pairs[2 * i + 1] >= 0.0 && pairs[2 * i + 1] <= 2.0 * PI, "v in the domain");
    }
    {
        BzjIntersection hits[4];
        EXPECT_STATUS(bzj_intersect_detailed(full, l, NULL, hits, 4, &count), BZJ_OK);
        CHECK(count == 2 && hits[0].kind == BZJ_INTERSECTION_CROSSING && hits[1].kind == BZJ_INTERSECTION_CROSSING,
              "two crossings (%zu)", count);
    }
    /* y = 5 touches the circle at (1, 5). */
    {
        BzjCurve* t = line(-5.0, 5.0, 7.0, 5.0);
        BzjIntersection hits[4];
        EXPECT_STATUS(bzj_intersect_detailed(t, full, NULL, hits, 4, &count), BZJ_OK);
        CHECK(count == 1 && hits[0].kind == BZJ_INTERSECTION_TOUCHING, "tangent line touches (%zu)",
              count);
        bzj_curve_free(t);
    }

    /* Two crossing circle arcs, C^1..C^3: the pieces are NURBS with the
       inputs' parameters, the blend a Bezier curve. */
    BzjCurve* a = circle_arc(0.0, 0.0, 1.0, -2.5, 1.2);
    BzjCurve* b = circle_arc(1.2, 0.0, 1.0, 1.5, 4.5);
    for (size_t k = 1; k <= 3; k++) {
        BzjFilletOptions fo = fillet_options(0.15, k);
        BzjCurve *pt = garbage(), *bl = garbage(), *qt = garbage();
        EXPECT_STATUS(bzj_fillet(a, b, &fo, &pt, &bl, &qt), BZJ_OK);
        CHECK(is_nurbs(pt) && !is_nurbs(bl) && is_nurbs(qt), "kinds kept");
        double first, u0;
        domain(pt, &first, &u0);
        CHECK(first == -2.5, "p_trimmed starts where P starts: %g", first);
        expect_fillet_joins(a, b, pt, bl, qt, k, "two arcs");
        bzj_curve_free(pt);
        bzj_curve_free(bl);
        bzj_curve_free(qt);
    }

    /* The deviation fillet of the two arcs: the blend passes within
       max_deviation of the crossing, just inside it; NURBS pieces. */
    {
        BzjDeviationFilletOptions dfo;
        memset(&dfo, 0, sizeof dfo);
        dfo.max_deviation = 0.02;
        dfo.setback_ratio = 1.0;
        dfo.p_order = 2;
        dfo.q_order = 2;
        dfo.p_scale = 1.0;
        dfo.q_scale = 1.0;
        BzjDeviationFilletReport report;
        BzjCurve *pt = garbage(), *bl = garbage(), *qt = garbage();
        EXPECT_STATUS(bzj_fillet_deviation(a, b, &dfo, &pt, &bl, &qt, &report), BZJ_OK);
        CHECK(report.deviation <= 0.02 && report.deviation >= 0.02 * (1.0 - 1e-9),
              "deviation %.17g within (1 - 1e-9) of 0.02", report.deviation);
        CHECK(is_nurbs(pt) && is_nurbs(qt) && !is_nurbs(bl), "deviation fillet kinds");
        expect_fillet_joins(a, b, pt, bl, qt, 2, "deviation fillet");
        bzj_curve_free(pt);
        bzj_curve_free(bl);
        bzj_curve_free(qt);
    }

    /* A sketch vertex: a quarter arc ending at (0, 1) and a line leaving
       (0, 1 + 3e-8) downwards; C^2 even though the line is degree 1. */
    BzjCurve* arc = circle_arc(0.0, 0.0, 1.0, 0.0, PI / 2);
    BzjCurve* down = NULL; /* as a NURBS handle: q_trimmed keeps parameters */
    {
        BzjCurve* bezier_line = line(0.0, 1.0 + 3e-8, 0.0, -2.0);
        EXPECT_STATUS(bzj_curve_to_nurbs(bezier_line, &down), BZJ_OK);
        bzj_curve_free(bezier_line);
    }
    {
        BzjFilletOptions fo = fillet_options(0.2, 2);
        BzjCurve *pt = garbage(), *bl = garbage(), *qt = garbage();
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &fo, 1e-7, &pt, &bl, &qt), BZJ_OK);
        expect_fillet_joins(arc, down, pt, bl, qt, 2, "vertex");
        double first, u0, len = 0.0;
        domain(pt, &first, &u0);
        EXPECT_STATUS(bzj_curve_length(arc, u0, PI / 2, &len), BZJ_OK);
        CHECK(fabs(len - 0.2) <= 1e-10, "the setback is the arc length: %.17g", len);
        bzj_curve_free(pt);
        bzj_curve_free(bl);
        bzj_curve_free(qt);

        /* errors: the gap, NULLs, bad numbers; the outs are cleared */
        pt = garbage(), bl = garbage(), qt = garbage();
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &fo, 1e-9, &pt, &bl, &qt),
                      BZJ_ERR_NO_INTERSECTION);
        expect_message("gap");
        CHECK(pt == NULL && bl == NULL && qt == NULL, "vertex outs cleared");
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &fo, -1.0, &pt, &bl, &qt),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("gap");
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &fo, NAN, &pt, &bl, &qt), BZJ_ERR_NON_FINITE);
        EXPECT_STATUS(bzj_fillet_vertex(NULL, down, &fo, 1e-7, &pt, &bl, &qt),
                      BZJ_ERR_NULL_POINTER);
        expect_message("p");
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, NULL, 1e-7, &pt, &bl, &qt),
                      BZJ_ERR_NULL_POINTER);
        expect_message("options");
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &fo, 1e-7, NULL, &bl, &qt),
                      BZJ_ERR_NULL_POINTER);
        expect_message("p_trimmed");
        BzjFilletOptions too_long = fillet_options(5.0, 2);
        EXPECT_STATUS(bzj_fillet_vertex(arc, down, &too_long, 1e-7, &pt, &bl, &qt),
                      BZJ_ERR_INVALID_ARGUMENT);
        expect_message("p_setback");
        {
            const Spline u3 = uc(); /* 3D */
            BzjCurve* c3 = nurbs(&u3);
            EXPECT_STATUS(bzj_fillet_vertex(arc, c3, &fo, 1e-7, &pt, &bl, &qt),
                          BZJ_ERR_DIMENSION_MISMATCH);
            bzj_curve_free(c3);
        }
        CHECK(pt == NULL && bl == NULL && qt == NULL, "vertex outs cleared after errors");
    }

    /* A closed wire of the arc and two lines, every vertex rounded. */
    {
        BzjCurve* to_origin = line(0.0, 1.0, 0.0, 0.0);
        BzjCurve* across = line(0.0, 0.0, 1.0, 0.0);
        const BzjCurve* wire[3] = {arc, to_origin, across};
        BzjFilletOptions fo = fillet_options(0.1, 2);
        BzjCurve* pieces[6];
        count = 0;
        EXPECT_STATUS(bzj_fillet_chain(wire, 3, &fo, 1, NULL, 0, &count), BZJ_OK);
        CHECK(count == 6, "closed chain of 3: %zu pieces", count);
        EXPECT_STATUS(bzj_fillet_chain(wire, 3, &fo, 1, pieces, 6, &count), BZJ_OK);
        CHECK(is_nurbs(pieces[0]) && !is_nurbs(pieces[1]) && !is_nurbs(pieces[2]),
              "the arc stays NURBS, blends and lines are Bezier");
        for (int i = 0; i < 6; i++) {
            double f0, l0, f1, l1, end[2], start[2];
            domain(pieces[i], &f0, &l0);
            domain(pieces[(i + 1) % 6], &f1, &l1);
            eval(pieces[i], l0, 0, 2, end);
            eval(pieces[(i + 1) % 6], f1, 0, 2, start);
            CHECK(distance(end, start, 2) <= 1e-10, "pieces %d and %d meet", i, (i + 1) % 6);
        }
        expect_same_parameters(pieces[0], arc, 2, "chain arc piece");
        for (int i = 0; i < 6; i++) bzj_curve_free(pieces[i]);
        bzj_curve_free(to_origin);
        bzj_curve_free(across);
    }
    bzj_curve_free(arc);
    bzj_curve_free(down);
    bzj_curve_free(a);
    bzj_curve_free(b);
    bzj_curve_free(l);
    bzj_curve_free(full);
}

/* ---- bzj_merge and bzj_merge_chain on B-splines (mathematics.md section 6) ---- */

/* The derivatives 0..3 of R at the join from each side's piece, scaled to
   R's parameter: (1-mu)^r (bP-aP)^r P^(r)(bP) against mu^r (bQ-aQ)^r
   Q^(r)(aQ); the largest mismatch relative to the largest value. */
static double join_mismatch(const BzjCurve* ph, const BzjCurve* qh, double mu) {
    double ap, bp, aq, bq;
    domain(ph, &ap, &bp);
    domain(qh, &aq, &bq);
    double left[8], right[8];
    eval(ph, bp, 3, 2, left);
    eval(qh, aq, 3, 2, right);
    double worst = 0.0, size = 0.0;
    for (int r = 0; r <= 3; r++) {
        double sl = pow((1.0 - mu) * (bp - ap), r), sr = pow(mu * (bq - aq), r);
        for (int c = 0; c < 2; c++) {
            double x = sl * left[2 * r + c], y = sr * right[2 * r + c];
            worst = fmax(worst, fabs(x - y));
            size = fmax(size, fmax(fabs(x), fabs(y)));
        }
    }
    return worst / size;
}

static void test_merge(void) {
    /* a split B-spline merged back at the split's own mu is the original */
    const Spline w = bs();
    BzjCurve* whole = nurbs(&w);
    BzjCurve *left = NULL, *right = NULL;
    const double t = 0.37; /* not a knot */
    EXPECT_STATUS(bzj_curve_split(whole, t, &left, &right), BZJ_OK);
    BzjMergeOptions mo;
    memset(&mo, 0, sizeof mo);
    mo.metric = BZJ_METRIC_L2;
    mo.split = BZJ_SPLIT_GIVEN;
    mo.mu = t; /* the domain is [0, 1] */
    BzjCurve *merged = NULL, *ph = NULL, *qh = NULL;
    BzjMergeReport report;
    EXPECT_STATUS(bzj_merge(left, right, &mo, &merged, &ph, &qh, &report), BZJ_OK);
    CHECK(is_nurbs(merged) && is_nurbs(ph) && is_nurbs(qh), "B-spline merge gives NURBS handles");
    CHECK(report.mu == t && report.max_deviation <= 1e-12, "merged back: deviation %g",
          report.max_deviation);
    size_t count = 0;
    double knots[16];
    EXPECT_STATUS(bzj_curve_knots(merged, knots, 16, &count), BZJ_OK);
    CHECK(count == 10, "merged back: %zu knots", count);
    for (size_t i = 0; i < count && i < 10; i++) {
        CHECK(fabs(knots[i] - BS_KNOTS[i]) <= 1e-15, "merged back: knot %zu is %g", i, knots[i]);
    }
    for (int i = 0; i <= 20; i++) {
        double u = i / 20.0, x[2], y[2];
        eval(merged, u, 0, 2, x);
        de_boor(&w, u, y);
        CHECK(distance(x, y, 2) <= 1e-12, "merged back at %g: %g", u, distance(x, y, 2));
    }
    bzj_curve_free(merged);
    bzj_curve_free(ph);
    bzj_curve_free(qh);

    /* two B-splines that were never one curve, of degrees 3 and 2 (the
       polynomial quadratic on RQ's knots), with the optimal mu */
    const Spline quad = {2, 2, 5, RQ_POLES, NULL, RQ_KNOTS};
    BzjCurve* q = nurbs(&quad);
    mo.split = BZJ_SPLIT_OPTIMAL;
    mo.fix_ends = true;
    EXPECT_STATUS(bzj_merge(whole, q, &mo, &merged, &ph, &qh, &report), BZJ_OK);
    size_t poles = 0;
    EXPECT_STATUS(bzj_curve_pole_count(merged, &poles), BZJ_OK);
    /* 6 + 8 - 3 - 1: elevation keeps the quadratic C1 at its knots, so
       its knots 1 and 2.5 become double (8 poles as a cubic) */
    CHECK(poles == 10, "merged pole count %zu", poles);
    CHECK(report.mu > 0.0 && report.mu < 1.0, "optimal mu %g", report.mu);
    EXPECT_STATUS(bzj_curve_knots(merged, knots, 16, &count), BZJ_OK);
    for (size_t i = 4; i + 4 < count; i++) {
        CHECK(fabs(knots[i] - report.mu) > 1e-9, "no knot at the join (knot %zu = %g)", i,
              knots[i]);
    }
    double mismatch = join_mismatch(ph, qh, report.mu);
    CHECK(mismatch <= 1e-9, "C3 across the join: %g", mismatch);
    double x[2], y[2];
    eval(merged, 0.0, 0, 2, x);
    de_boor(&w, 0.0, y);
    CHECK(distance(x, y, 2) <= 1e-12, "fix ends: first point moved by %g", distance(x, y, 2));
    eval(merged, 1.0, 0, 2, x);
    de_boor(&quad, 4.0, y);
    CHECK(distance(x, y, 2) <= 1e-12, "fix ends: last point moved by %g", distance(x, y, 2));
    bzj_curve_free(merged);
    bzj_curve_free(ph);
    bzj_curve_free(qh);

    /* a Bezier handle with a NURBS handle: merged as B-splines */
    const double bez_points[] = {13, 1, 14, 2, 15, 0, 16, 1};
    BzjCurve* b = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 3, bez_points, 8, &b), BZJ_OK);
    mo.fix_ends = false;
    EXPECT_STATUS(bzj_merge_to_degree(whole, b, &mo, 4, &merged, NULL, NULL, &report), BZJ_OK);
    CHECK(is_nurbs(merged), "Bezier with NURBS gives a NURBS");
    size_t degree = 0;
    EXPECT_STATUS(bzj_curve_degree(merged, &degree), BZJ_OK);
    CHECK(degree == 4, "merge_to_degree: degree %zu", degree);
    bzj_curve_free(merged);

    /* a rational curve is refused by name, outputs cleared */
    const Spline s = rq();
    BzjCurve* n = nurbs(&s);
    merged = garbage();
    ph = garbage();
    qh = garbage();
    EXPECT_STATUS(bzj_merge(n, b, &mo, &merged, &ph, &qh, NULL), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(merged == NULL && ph == NULL && qh == NULL, "merge outs cleared");
    expect_message("p: the curve is rational");

    /* a chain: the whole curve cut in three and merged back */
    BzjCurve *first = NULL, *rest = NULL, *second = NULL, *third = NULL;
    EXPECT_STATUS(bzj_curve_split(whole, 0.3, &first, &rest), BZJ_OK);
    EXPECT_STATUS(bzj_curve_split(rest, 0.71, &second, &third), BZJ_OK);
    BzjChainMergeOptions cmo;
    memset(&cmo, 0, sizeof cmo);
    cmo.metric = BZJ_METRIC_DISCRETE;
    cmo.split = BZJ_CHAIN_SPLIT_GIVEN;
    const double inner[2] = {0.3, 0.71};
    cmo.breakpoints = inner;
    cmo.breakpoint_count = 2;
    const BzjCurve* chain[3] = {first, second, third};
    BzjCurve* pieces[3] = {NULL, NULL, NULL};
    double breakpoints[4];
    BzjChainMergeReport chain_report;
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &cmo, &merged, pieces, 3, breakpoints, 4,
                                  &chain_report),
                  BZJ_OK);
    CHECK(chain_report.max_deviation <= 1e-12, "chain merged back: deviation %g",
          chain_report.max_deviation);
    for (int i = 0; i <= 20; i++) {
        double u = i / 20.0;
        eval(merged, u, 0, 2, x);
        de_boor(&w, u, y);
        CHECK(distance(x, y, 2) <= 1e-12, "chain merged back at %g: %g", u, distance(x, y, 2));
    }
    for (int j = 0; j < 3; j++) {
        CHECK(is_nurbs(pieces[j]), "chain piece %d is NURBS", j);
        bzj_curve_free(pieces[j]);
    }
    bzj_curve_free(merged);
    bzj_curve_free(first);
    bzj_curve_free(rest);
    bzj_curve_free(second);
    bzj_curve_free(third);
    bzj_curve_free(n);
    bzj_curve_free(b);
    bzj_curve_free(q);
    bzj_curve_free(left);
    bzj_curve_free(right);
    bzj_curve_free(whole);
}

int main(void) {
    test_new();
    test_inspection();
    test_spans();
    test_ellipse();
    test_eval();
    test_operations();
    test_connect();
    test_intersect_and_fillet();
    test_merge();
    if (failures) {
        fprintf(stderr, "nurbs.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("nurbs.c: all checks passed\n");
    return 0;
}
