/* C test of the on-curve-point spline (mathematics.md section 4):
 * bzj_lagrange_spline (the published contract) and bzj_lagrange_spline_degree.
 * Checks defining properties through the C ABI only: the given points lie on
 * the returned Bezier segments, derivatives agree across every node in the
 * global parameter, and every error path returns its status with NULL
 * handles (nothing written for BZJ_ERR_BUFFER_TOO_SMALL).
 * Returns 0 on success, 1 with a message on the first failure. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bezjoin.h"

#define DIM 2
#define NODES 6
#define SEGS (NODES - 1)

static int failures = 0;

#define CHECK(cond, ...)                                   \
    do {                                                   \
        if (!(cond)) {                                     \
            fprintf(stderr, "lagrange.c:%d: ", __LINE__);  \
            fprintf(stderr, __VA_ARGS__);                  \
            fprintf(stderr, "\n");                         \
            failures++;                                    \
            return 1;                                      \
        }                                                  \
    } while (0)

static const double nodes[NODES * DIM] = {0.0, 0.0, 1.0, 0.6, 2.1, 0.2,
                                          3.0, 1.1, 4.2, 0.9, 5.0, 0.0};
/* inner points of segment 0 at u = 1/3, 2/3 */
static const double first_inner[2 * DIM] = {0.3, 0.3, 0.7, 0.5};
/* u = 2/3 point of segments 1..4 */
static const double second_inner[(NODES - 2) * DIM] = {1.8, 0.35, 2.7, 0.8,
                                                       3.8, 1.05, 4.75, 0.4};

static double dist(const double* a, const double* b) {
    double s = 0.0;
    for (int c = 0; c < DIM; c++) s += (a[c] - b[c]) * (a[c] - b[c]);
    return sqrt(s);
}

static void free_all(BzjCurve** h, size_t n) {
    for (size_t i = 0; i < n; i++) {
        bzj_curve_free(h[i]);
        h[i] = NULL;
    }
}

static int all_null(BzjCurve** h, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (h[i] != NULL) return 0;
    return 1;
}

/* point on segment s at u (value only) */
static int eval_at(BzjCurve* c, double u, size_t order, double* out) {
    return bzj_curve_eval(c, u, order, out, (order + 1) * DIM) == BZJ_OK;
}

/* C^k across every node: derivative m of the left piece at 1 over h_l^m
 * equals that of the right piece at 0 over h_r^m, relative 1e-10. */
static int check_continuity(BzjCurve** seg, size_t nseg, const double* x, size_t k) {
    double left[6 * DIM], right[6 * DIM];
    for (size_t i = 1; i < nseg; i++) {
        double hl = x[i] - x[i - 1], hr = x[i + 1] - x[i];
        CHECK(eval_at(seg[i - 1], 1.0, k, left) && eval_at(seg[i], 0.0, k, right),
              "eval failed: %s", bzj_last_error());
        for (size_t m = 0; m <= k; m++) {
            double a[DIM], b[DIM];
            for (int c = 0; c < DIM; c++) {
                a[c] = left[m * DIM + c] / pow(hl, (double)m);
                b[c] = right[m * DIM + c] / pow(hr, (double)m);
            }
            double size = fmax(hypot(a[0], a[1]), hypot(b[0], b[1]));
            CHECK(dist(a, b) <= 1e-10 * fmax(size, 1.0),
                  "node %zu order %zu: jump %g", i, m, dist(a, b));
        }
    }
    return 0;
}

static void chord_params(double* x) {
    x[0] = 0.0;
    for (int i = 1; i < NODES; i++) x[i] = x[i - 1] + dist(&nodes[(i - 1) * DIM], &nodes[i * DIM]);
}

static int test_contract_function(void) {
    BzjCurve* seg[SEGS + 1] = {NULL};
    double x[NODES];
    chord_params(x);
    BzjStatus s = bzj_lagrange_spline(DIM, NODES, nodes, NULL, first_inner, second_inner, seg,
                                      SEGS + 1);
    CHECK(s == BZJ_OK, "bzj_lagrange_spline: %s %s", bzj_status_name(s), bzj_last_error());
    CHECK(seg[SEGS] == NULL, "entry past node_count - 1 was written");
    for (int i = 0; i < SEGS; i++) {
        size_t degree = 0;
        CHECK(bzj_curve_degree(seg[i], &degree) == BZJ_OK && degree == 3, "segment %d not cubic", i);
        double p[DIM];
        /* nodes at u = 0 and 1 */
        CHECK(eval_at(seg[i], 0.0, 0, p) && dist(p, &nodes[i * DIM]) <= 1e-12 * 5.0,
              "segment %d misses node %d", i, i);
        CHECK(eval_at(seg[i], 1.0, 0, p) && dist(p, &nodes[(i + 1) * DIM]) <= 1e-12 * 5.0,
              "segment %d misses node %d", i, i + 1);
        /* given inner points */
        if (i == 0) {
            CHECK(eval_at(seg[0], 1.0 / 3.0, 0, p) && dist(p, &first_inner[0]) <= 5e-12,
                  "segment 0 misses first_inner[0]");
            CHECK(eval_at(seg[0], 2.0 / 3.0, 0, p) && dist(p, &first_inner[DIM]) <= 5e-12,
                  "segment 0 misses first_inner[1]");
        } else {
            CHECK(eval_at(seg[i], 2.0 / 3.0, 0, p) && dist(p, &second_inner[(i - 1) * DIM]) <= 5e-12,
                  "segment %d misses its second_inner point", i);
        }
    }
    if (check_continuity(seg, SEGS, x, 1)) return 1;

    /* same data with explicit uniform parameters */
    double uniform[NODES] = {0, 1, 2, 3, 4, 5};
    free_all(seg, SEGS);
    s = bzj_lagrange_spline(DIM, NODES, nodes, uniform, first_inner, second_inner, seg, SEGS);
    CHECK(s == BZJ_OK, "with params: %s", bzj_last_error());
    if (check_continuity(seg, SEGS, uniform, 1)) return 1;

    /* the general function with degree 3, C1, no flags is the same spline */
    BzjCurve* other[SEGS] = {NULL};
    s = bzj_lagrange_spline_degree(DIM, 3, 1, 0, NODES, nodes, uniform, first_inner, second_inner,
                                   other, SEGS);
    CHECK(s == BZJ_OK, "degree 3 general: %s", bzj_last_error());
    for (int i = 0; i < SEGS; i++) {
        double a[4 * DIM], b[4 * DIM];
        CHECK(bzj_curve_points(seg[i], a, 4 * DIM) == BZJ_OK &&
                  bzj_curve_points(other[i], b, 4 * DIM) == BZJ_OK,
              "points");
        CHECK(memcmp(a, b, sizeof a) == 0, "segment %d differs between the two functions", i);
    }
    free_all(seg, SEGS);
    free_all(other, SEGS);

    /* two nodes: second_inner may be NULL */
    s = bzj_lagrange_spline(DIM, 2, nodes, NULL, first_inner, NULL, seg, 1);
    CHECK(s == BZJ_OK && seg[0] != NULL, "two nodes: %s", bzj_last_error());
    free_all(seg, 1);
    return 0;
}

static int test_higher_degree(void) {
    /* degree 5, C2: give u = 3/5, 4/5 of every later segment */
    double start[4 * DIM], free_pts[(NODES - 2) * 2 * DIM];
    for (int j = 1; j <= 4; j++)
        for (int c = 0; c < DIM; c++)
            start[(j - 1) * DIM + c] = nodes[c] + (nodes[DIM + c] - nodes[c]) * j / 5.0 + 0.05 * j;
    for (int s = 1; s < SEGS; s++)
        for (int q = 0; q < 2; q++)
            for (int c = 0; c < DIM; c++) {
                double t = (3.0 + q) / 5.0;
                free_pts[((s - 1) * 2 + q) * DIM + c] =
                    nodes[s * DIM + c] + (nodes[(s + 1) * DIM + c] - nodes[s * DIM + c]) * t - 0.03;
            }
    double x[NODES];
    chord_params(x);
    BzjCurve* seg[SEGS] = {NULL};
    BzjStatus s = bzj_lagrange_spline_degree(DIM, 5, 2, 0, NODES, nodes, NULL, start, free_pts, seg,
                                             SEGS);
    CHECK(s == BZJ_OK, "degree 5 C2: %s %s", bzj_status_name(s), bzj_last_error());
    for (int i = 1; i < SEGS; i++) {
        double p[DIM];
        CHECK(eval_at(seg[i], 0.6, 0, p) && dist(p, &free_pts[(i - 1) * 2 * DIM]) <= 1e-11,
              "degree 5 segment %d misses its u = 3/5 point", i);
    }
    if (check_continuity(seg, SEGS, x, 2)) return 1;
    free_all(seg, SEGS);

    /* backward, cubic: the last segment's inner points are given, then the
     * u = 1/3 point of each earlier segment */
    s = bzj_lagrange_spline_degree(DIM, 3, 1, BZJ_LAGRANGE_BACKWARD, NODES, nodes, NULL, first_inner,
                                   second_inner, seg, SEGS);
    CHECK(s == BZJ_OK, "backward: %s", bzj_last_error());
    if (check_continuity(seg, SEGS, x, 1)) return 1;
    free_all(seg, SEGS);

    /* mirrored on a short chain works ... */
    s = bzj_lagrange_spline_degree(DIM, 3, 1, BZJ_LAGRANGE_MIRRORED, NODES, nodes, NULL, first_inner,
                                   second_inner, seg, SEGS);
    CHECK(s == BZJ_OK, "mirrored: %s", bzj_last_error());
    if (check_continuity(seg, SEGS, x, 1)) return 1;
    free_all(seg, SEGS);

    /* ... and a long one is refused (errors double per node) */
    enum { LONG = 60 };
    static double long_nodes[LONG], long_params[LONG], long_free[LONG - 2];
    static BzjCurve* long_seg[LONG - 1];
    for (int i = 0; i < LONG; i++) {
        long_nodes[i] = sin(0.3 * i);
        long_params[i] = i;
    }
    for (int i = 0; i < LONG - 2; i++) long_free[i] = 0.5 * (long_nodes[i + 1] + long_nodes[i + 2]);
    double long_start[2] = {0.1, 0.2};
    for (int i = 0; i < LONG - 1; i++) long_seg[i] = (BzjCurve*)long_nodes; /* sentinel */
    s = bzj_lagrange_spline_degree(1, 3, 1, BZJ_LAGRANGE_MIRRORED, LONG, long_nodes, long_params,
                                   long_start, long_free, long_seg, LONG - 1);
    CHECK(s == BZJ_ERR_ILL_CONDITIONED, "long mirrored chain: got %s", bzj_status_name(s));
    CHECK(all_null(long_seg, LONG - 1), "handles not cleared after ILL_CONDITIONED");
    s = bzj_lagrange_spline_degree(1, 3, 1, 0, LONG, long_nodes, long_params, long_start, long_free,
                                   long_seg, LONG - 1);
    CHECK(s == BZJ_OK, "long stable chain: %s", bzj_last_error());
    free_all(long_seg, LONG - 1);
    return 0;
}

/* Expect `status` with every handle NULL and a message containing `word`. */
static int expect_error(BzjStatus got, BzjStatus want, BzjCurve** seg, size_t n, const char* word,
                        const char* what) {
    CHECK(got == want, "%s: got %s, want %s (%s)", what, bzj_status_name(got), bzj_status_name(want),
          bzj_last_error());
    CHECK(all_null(seg, n), "%s: handles not NULL", what);
    CHECK(strstr(bzj_last_error(), word) != NULL, "%s: message '%s' does not name '%s'", what,
          bzj_last_error(), word);
    return 0;
}

static void poison(BzjCurve** seg, size_t n) {
    for (size_t i = 0; i < n; i++) seg[i] = (BzjCurve*)&nodes[0];
}

static int test_errors(void) {
    BzjCurve* seg[SEGS];
    BzjStatus s;

#define EXPECT(call, want, word, what)                                     \
    do {                                                                   \
        poison(seg, SEGS);                                                 \
        s = (call);                                                        \
        if (expect_error(s, want, seg, SEGS, word, what)) return 1;        \
    } while (0)

    EXPECT(bzj_lagrange_spline(DIM, NODES, NULL, NULL, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_NULL_POINTER, "nodes", "NULL nodes");
    EXPECT(bzj_lagrange_spline(DIM, NODES, nodes, NULL, NULL, second_inner, seg, SEGS),
           BZJ_ERR_NULL_POINTER, "first_inner", "NULL first_inner");
    EXPECT(bzj_lagrange_spline(DIM, NODES, nodes, NULL, first_inner, NULL, seg, SEGS),
           BZJ_ERR_NULL_POINTER, "second_inner", "NULL second_inner");
    s = bzj_lagrange_spline(DIM, NODES, nodes, NULL, first_inner, second_inner, NULL, SEGS);
    CHECK(s == BZJ_ERR_NULL_POINTER && strstr(bzj_last_error(), "out_segments"),
          "NULL out_segments: %s", bzj_status_name(s));

    /* fewer than 2 nodes */
    s = bzj_lagrange_spline(DIM, 1, nodes, NULL, first_inner, NULL, seg, SEGS);
    CHECK(s == BZJ_ERR_INVALID_ARGUMENT && strstr(bzj_last_error(), "node_count"),
          "one node: %s", bzj_status_name(s));
    /* dim 0 */
    EXPECT(bzj_lagrange_spline(0, NODES, nodes, NULL, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "dim", "dim 0");
    /* params not strictly increasing */
    const double bad_params[NODES] = {0, 1, 2, 2, 4, 5};
    EXPECT(bzj_lagrange_spline(DIM, NODES, nodes, bad_params, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "params[3]", "repeated parameter");
    /* coincident consecutive nodes with chord length */
    double twin[NODES * DIM];
    memcpy(twin, nodes, sizeof twin);
    twin[2 * DIM] = twin[DIM];
    twin[2 * DIM + 1] = twin[DIM + 1];
    EXPECT(bzj_lagrange_spline(DIM, NODES, twin, NULL, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "coincide", "coincident nodes");
    /* non-finite values */
    double nan_inner[2 * DIM];
    memcpy(nan_inner, first_inner, sizeof nan_inner);
    nan_inner[3] = NAN;
    EXPECT(bzj_lagrange_spline(DIM, NODES, nodes, NULL, nan_inner, second_inner, seg, SEGS),
           BZJ_ERR_NON_FINITE, "first_inner[3]", "NaN in first_inner");
    double inf_nodes[NODES * DIM];
    memcpy(inf_nodes, nodes, sizeof inf_nodes);
    inf_nodes[5] = INFINITY;
    EXPECT(bzj_lagrange_spline(DIM, NODES, inf_nodes, NULL, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_NON_FINITE, "nodes[5]", "infinite node");
    double nan_params[NODES] = {0, 1, NAN, 3, 4, 5};
    EXPECT(bzj_lagrange_spline(DIM, NODES, nodes, nan_params, first_inner, second_inner, seg, SEGS),
           BZJ_ERR_NON_FINITE, "params[2]", "NaN parameter");

    /* buffer too small: nothing written */
    poison(seg, SEGS);
    s = bzj_lagrange_spline(DIM, NODES, nodes, NULL, first_inner, second_inner, seg, SEGS - 1);
    CHECK(s == BZJ_ERR_BUFFER_TOO_SMALL, "small buffer: got %s", bzj_status_name(s));
    for (int i = 0; i < SEGS; i++)
        CHECK(seg[i] == (BzjCurve*)&nodes[0], "small buffer: entry %d was written", i);

    /* the general function: degree, continuity, flags */
    EXPECT(bzj_lagrange_spline_degree(DIM, 6, 1, 0, NODES, nodes, NULL, first_inner, second_inner,
                                      seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "degree", "degree 6");
    EXPECT(bzj_lagrange_spline_degree(DIM, 2, 1, 0, NODES, nodes, NULL, first_inner, second_inner,
                                      seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "degree", "degree 2");
    EXPECT(bzj_lagrange_spline_degree(DIM, 3, 2, 0, NODES, nodes, NULL, first_inner, second_inner,
                                      seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "continuity", "C2 cubic");
    EXPECT(bzj_lagrange_spline_degree(DIM, 4, 0, 0, NODES, nodes, NULL, first_inner, second_inner,
                                      seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "continuity", "C0");
    EXPECT(bzj_lagrange_spline_degree(DIM, 3, 1, 4, NODES, nodes, NULL, first_inner, second_inner,
                                      seg, SEGS),
           BZJ_ERR_INVALID_ARGUMENT, "flags", "unknown flag");
    /* degree 4 C1 needs 3 start points: a NULL start_inner is caught */
    EXPECT(bzj_lagrange_spline_degree(DIM, 4, 1, 0, NODES, nodes, NULL, NULL, second_inner, seg,
                                      SEGS),
           BZJ_ERR_NULL_POINTER, "start_inner", "NULL start_inner");
    /* the general function also writes nothing when the buffer is short */
    poison(seg, SEGS);
    s = bzj_lagrange_spline_degree(DIM, 3, 1, 0, NODES, nodes, NULL, first_inner, second_inner, seg,
                                   2);
    CHECK(s == BZJ_ERR_BUFFER_TOO_SMALL && seg[0] == (BzjCurve*)&nodes[0],
          "general small buffer: %s", bzj_status_name(s));
#undef EXPECT
    return 0;
}

int main(void) {
    if (test_contract_function() || test_higher_degree() || test_errors() || failures) {
        fprintf(stderr, "lagrange.c: FAILED\n");
        return 1;
    }
    printf("lagrange.c: all checks passed\n");
    return 0;
}
