/* C test of the merge functions: bzj_merge, bzj_merge_to_degree,
 * bzj_merge_chain, including every error path; each successful two-curve
 * merge of the second part is checked by splitting the result at mu and by
 * resampling the reported deviation. Returns 0 on success,
 * non-zero with a message otherwise. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bezjoin.h"

static int failures = 0;

#define CHECK(cond, ...)                                        \
    do {                                                        \
        if (!(cond)) {                                          \
            fprintf(stderr, "merge.c:%d: FAILED %s: ", __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                       \
            fprintf(stderr, " (last error: %s)\n", bzj_last_error()); \
            failures++;                                         \
        }                                                       \
    } while (0)

#define EXPECT_STATUS(call, expected)                                       \
    do {                                                                    \
        BzjStatus status_ = (call);                                         \
        CHECK(status_ == (expected), "%s returned %s, expected %s", #call,  \
              bzj_status_name(status_), bzj_status_name(expected));         \
    } while (0)

static BzjCurve *make(size_t dim, size_t degree, const double *pts) {
    BzjCurve *c = NULL;
    BzjStatus s = bzj_curve_new(dim, degree, pts, (degree + 1) * dim, &c);
    if (s != BZJ_OK) {
        fprintf(stderr, "bzj_curve_new failed: %s\n", bzj_last_error());
        return NULL;
    }
    return c;
}

static double max_point_diff(const BzjCurve *a, const BzjCurve *b) {
    double pa[64], pb[64];
    size_t da = 0, db = 0, na = 0, nb = 0;
    bzj_curve_dim(a, &da);
    bzj_curve_dim(b, &db);
    bzj_curve_degree(a, &na);
    bzj_curve_degree(b, &nb);
    if (da != db || na != nb) return INFINITY;
    bzj_curve_points(a, pa, 64);
    bzj_curve_points(b, pb, 64);
    double worst = 0.0;
    for (size_t i = 0; i < (na + 1) * da; i++) {
        double d = fabs(pa[i] - pb[i]);
        if (d > worst) worst = d;
    }
    return worst;
}

static BzjMergeOptions default_options(void) {
    BzjMergeOptions o;
    memset(&o, 0, sizeof o);
    o.metric = BZJ_METRIC_DISCRETE;
    o.split = BZJ_SPLIT_HALF;
    o.mu = 0.5;
    return o;
}

/* Largest absolute control-point coordinate of a curve. */
static double coordinate_scale(const BzjCurve *c) {
    double pts[64];
    size_t d = 0, n = 0;
    bzj_curve_dim(c, &d);
    bzj_curve_degree(c, &n);
    if ((n + 1) * d > 64) return INFINITY;
    bzj_curve_points(c, pts, 64);
    double s = 0.0;
    for (size_t i = 0; i < (n + 1) * d; i++) s = fmax(s, fabs(pts[i]));
    return s;
}

static double distance2(const double *a, const double *b) {
    return hypot(a[0] - b[0], a[1] - b[1]);
}

/* Largest distance between R and "P then Q" with `samples` intervals on
 * each: R(mu u) against P(u), R(mu + (1 - mu) v) against Q(v). */
static double sampled_deviation(const BzjCurve *r, const BzjCurve *p, const BzjCurve *q, double mu,
                                int samples) {
    double worst = 0.0;
    for (int k = 0; k <= samples; k++) {
        double s = (double)k / samples, a[2], b[2];
        bzj_curve_eval(r, mu * s, 0, a, 2);
        bzj_curve_eval(p, s, 0, b, 2);
        worst = fmax(worst, distance2(a, b));
        bzj_curve_eval(r, mu + (1.0 - mu) * s, 0, a, 2);
        bzj_curve_eval(q, s, 0, b, 2);
        worst = fmax(worst, distance2(a, b));
    }
    return worst;
}

/* What every successful merge promises, checked from C: merged split at
 * report.mu gives back p_hat and q_hat (control points, 1e-12 relative to
 * the coordinate scale), the metric value is finite and >= 0, and
 * report.max_deviation is the sampled distance between the merged curve and
 * "P then Q" (257 samples each, as documented; a 16x finer sampling finds
 * at most a little more). */
static void check_merge_result(const char *label, const BzjCurve *p, const BzjCurve *q,
                               const BzjCurve *merged, const BzjCurve *p_hat,
                               const BzjCurve *q_hat, const BzjMergeReport *report,
                               size_t expected_degree) {
    if (!merged || !p_hat || !q_hat) {
        CHECK(0, "%s: missing outputs", label);
        return;
    }
    size_t degree = 0;
    bzj_curve_degree(merged, &degree);
    CHECK(degree == expected_degree, "%s: degree %zu, expected %zu", label, degree,
          expected_degree);
    bzj_curve_degree(p_hat, &degree);
    CHECK(degree == expected_degree, "%s: p_hat degree %zu", label, degree);
    bzj_curve_degree(q_hat, &degree);
    CHECK(degree == expected_degree, "%s: q_hat degree %zu", label, degree);
    CHECK(report->mu > 0.0 && report->mu < 1.0, "%s: mu %g", label, report->mu);
    CHECK(isfinite(report->metric_value) && report->metric_value >= 0.0, "%s: metric %g", label,
          report->metric_value);
    BzjCurve *left = NULL, *right = NULL;
    EXPECT_STATUS(bzj_curve_split(merged, report->mu, &left, &right), BZJ_OK);
    double scale = fmax(coordinate_scale(p_hat), coordinate_scale(q_hat));
    double dl = max_point_diff(left, p_hat) / scale;
    double dr = max_point_diff(right, q_hat) / scale;
    CHECK(dl <= 1e-12 && dr <= 1e-12, "%s: split at mu differs from p_hat by %g, q_hat by %g",
          label, dl, dr);
    bzj_curve_free(left);
    bzj_curve_free(right);
    double same = sampled_deviation(merged, p, q, report->mu, 256);
    double fine = sampled_deviation(merged, p, q, report->mu, 4096);
    CHECK(isfinite(report->max_deviation) && report->max_deviation > 0.0, "%s: deviation %g",
          label, report->max_deviation);
    CHECK(fabs(same - report->max_deviation) <= 1e-12 * scale,
          "%s: max_deviation %.17g, sampled here %.17g", label, report->max_deviation, same);
    CHECK(fine >= report->max_deviation - 1e-12 * scale &&
              fine <= report->max_deviation * (1.0 + 1e-3),
          "%s: max_deviation %.17g, finely sampled %.17g", label, report->max_deviation, fine);
    printf("%s: mu %.6f, metric %.3g, split-back %.1e / %.1e, deviation %.6g (257 samples "
           "here %.6g, 4097 samples %.6g)\n",
           label, report->mu, report->metric_value, dl, dr, report->max_deviation, same, fine);
}

/* bzj_merge_to_degree and unequal degrees, checked by the split-back, and
 * the parameter errors of the keep points and of mu. */
static void test_merge_results_and_parameter_errors(void) {
    const double p_pts[] = {0.0, 0.0, 1.0, 1.0, 2.0, 1.0, 3.0, 0.0};
    const double q_pts[] = {3.1, 0.1, 4.0, -1.0, 5.0, -1.0, 6.0, 0.5};
    const double q5_pts[] = {3.1, 0.1, 3.5, -0.8, 4.2, -1.2, 5.0, -0.4, 5.6, 0.9, 6.0, 0.5};
    BzjCurve *a = make(2, 3, p_pts), *b = make(2, 3, q_pts), *b5 = make(2, 5, q5_pts);
    BzjCurve *merged = NULL, *p_hat = NULL, *q_hat = NULL;
    BzjMergeReport report;

    /* Degree 6 on request, polygon split, integral metric. */
    BzjMergeOptions o = default_options();
    o.split = BZJ_SPLIT_POLYGON;
    o.metric = BZJ_METRIC_L2;
    EXPECT_STATUS(bzj_merge_to_degree(a, b, &o, 6, &merged, &p_hat, &q_hat, &report), BZJ_OK);
    check_merge_result("to degree 6", a, b, merged, p_hat, q_hat, &report, 6);
    /* More freedom than the degree-3 merge: no larger a change. */
    BzjMergeReport report3;
    BzjCurve *merged3 = NULL;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged3, NULL, NULL, &report3), BZJ_OK);
    CHECK(report.mu == report3.mu && report.metric_value <= report3.metric_value * (1.0 + 1e-12),
          "degree 6 metric %g above degree 3 metric %g", report.metric_value,
          report3.metric_value);
    bzj_curve_free(merged3);
    bzj_curve_free(merged);
    bzj_curve_free(p_hat);
    bzj_curve_free(q_hat);

    /* A cubic and a quintic: the cubic is elevated, the result has degree 5. */
    o = default_options();
    o.split = BZJ_SPLIT_GIVEN;
    o.mu = 0.45;
    EXPECT_STATUS(bzj_merge(a, b5, &o, &merged, &p_hat, &q_hat, &report), BZJ_OK);
    CHECK(report.mu == 0.45, "given mu came back as %g", report.mu);
    check_merge_result("cubic + quintic", a, b5, merged, p_hat, q_hat, &report, 5);
    bzj_curve_free(merged);
    bzj_curve_free(p_hat);
    bzj_curve_free(q_hat);
    /* The other way round (the same path backwards: quintic first), optimal mu. */
    BzjCurve *a_back = NULL, *b5_back = NULL;
    EXPECT_STATUS(bzj_curve_reverse(a, &a_back), BZJ_OK);
    EXPECT_STATUS(bzj_curve_reverse(b5, &b5_back), BZJ_OK);
    o.split = BZJ_SPLIT_OPTIMAL;
    EXPECT_STATUS(bzj_merge(b5_back, a_back, &o, &merged, &p_hat, &q_hat, &report), BZJ_OK);
    check_merge_result("quintic + cubic, optimal mu", b5_back, a_back, merged, p_hat, q_hat,
                       &report, 5);
    bzj_curve_free(merged);
    bzj_curve_free(p_hat);
    bzj_curve_free(q_hat);
    bzj_curve_free(a_back);
    bzj_curve_free(b5_back);

    /* Keep-point parameters: NaN and infinities, outside [0, 1]; mu <= 0. */
    merged = NULL;
    BzjKeepPoint kp = {0.5, 0};
    const double non_finite[] = {NAN, INFINITY, -INFINITY};
    for (int side = 0; side < 2; side++) {
        const char *name = side == 0 ? "p_points[0].param" : "q_points[0].param";
        o = default_options();
        if (side == 0) {
            o.p_points = &kp;
            o.p_point_count = 1;
        } else {
            o.q_points = &kp;
            o.q_point_count = 1;
        }
        for (int k = 0; k < 3; k++) {
            kp.param = non_finite[k];
            EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NON_FINITE);
            CHECK(strstr(bzj_last_error(), name) != NULL, "message does not name %s", name);
            CHECK(merged == NULL, "merged not NULL after an error");
        }
        const double outside[] = {-0.1, -1e-300, 1.0 + 1e-15, 2.0};
        for (int k = 0; k < 4; k++) {
            kp.param = outside[k];
            EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL),
                          BZJ_ERR_INVALID_ARGUMENT);
            CHECK(strstr(bzj_last_error(), name) != NULL && strstr(bzj_last_error(), "[0, 1]"),
                  "message does not name %s and its range", name);
        }
        /* The ends of [0, 1] are allowed. */
        kp.param = side == 0 ? 0.0 : 1.0;
        EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_OK);
        bzj_curve_free(merged);
        merged = NULL;
    }
    o = default_options();
    o.split = BZJ_SPLIT_GIVEN;
    const double bad_mu[] = {0.0, -0.0, -0.25, -1e-300};
    for (int k = 0; k < 4; k++) {
        o.mu = bad_mu[k];
        EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(strstr(bzj_last_error(), "mu") != NULL && strstr(bzj_last_error(), "(0, 1)"),
              "message does not name mu and its range");
    }
    o.mu = -INFINITY;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NON_FINITE);
    /* The same checks in bzj_merge_to_degree. */
    o.mu = 0.0;
    EXPECT_STATUS(bzj_merge_to_degree(a, b, &o, 5, &merged, NULL, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    o = default_options();
    kp.param = NAN;
    o.p_points = &kp;
    o.p_point_count = 1;
    EXPECT_STATUS(bzj_merge_to_degree(a, b, &o, 5, &merged, NULL, NULL, NULL), BZJ_ERR_NON_FINITE);
    CHECK(merged == NULL, "merged not NULL after errors");

    bzj_curve_free(a);
    bzj_curve_free(b);
    bzj_curve_free(b5);
}

int main(void) {
    /* One cubic, split at t = 0.3: merging the pieces gives it back. */
    const double original_pts[] = {0.0, 0.0, 1.0, 2.0, 3.0, 2.5, 4.0, 0.0};
    BzjCurve *original = make(2, 3, original_pts);
    BzjCurve *p = NULL, *q = NULL;
    EXPECT_STATUS(bzj_curve_split(original, 0.3, &p, &q), BZJ_OK);

    BzjMergeOptions o = default_options();
    o.split = BZJ_SPLIT_OPTIMAL;
    o.metric = BZJ_METRIC_L2;
    BzjCurve *merged = NULL, *p_hat = NULL, *q_hat = NULL;
    BzjMergeReport report;
    EXPECT_STATUS(bzj_merge(p, q, &o, &merged, &p_hat, &q_hat, &report), BZJ_OK);
    CHECK(fabs(report.mu - 0.3) < 1e-6, "optimal mu %g, expected 0.3", report.mu);
    CHECK(report.max_deviation < 1e-9, "deviation %g", report.max_deviation);
    CHECK(merged && max_point_diff(merged, original) < 1e-8, "merged differs from the original");
    CHECK(p_hat && max_point_diff(p_hat, p) < 1e-8, "p_hat differs from p");
    bzj_curve_free(merged);
    bzj_curve_free(p_hat);
    bzj_curve_free(q_hat);

    /* Two unrelated cubics, given mu, constraints; outputs optional. */
    const double p_pts[] = {0.0, 0.0, 1.0, 1.0, 2.0, 1.0, 3.0, 0.0};
    const double q_pts[] = {3.1, 0.1, 4.0, -1.0, 5.0, -1.0, 6.0, 0.5};
    BzjCurve *a = make(2, 3, p_pts), *b = make(2, 3, q_pts);
    BzjKeepPoint keep_on_p = {0.25, 1};
    o = default_options();
    o.split = BZJ_SPLIT_GIVEN;
    o.mu = 0.4;
    o.fix_ends = true;
    o.p_points = &keep_on_p;
    o.p_point_count = 1;
    merged = NULL;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_OK);
    if (merged) {
        double start[2], expected[2];
        bzj_curve_eval(merged, 0.0, 0, start, 2);
        bzj_curve_eval(a, 0.0, 0, expected, 2);
        CHECK(fabs(start[0] - expected[0]) < 1e-12 && fabs(start[1] - expected[1]) < 1e-12,
              "fix_ends did not keep the first point");
        /* The kept point: R(mu * 0.25) == P(0.25). */
        double r_val[2], p_val[2];
        bzj_curve_eval(merged, 0.4 * 0.25, 0, r_val, 2);
        bzj_curve_eval(a, 0.25, 0, p_val, 2);
        CHECK(fabs(r_val[0] - p_val[0]) < 1e-10 && fabs(r_val[1] - p_val[1]) < 1e-10,
              "kept point moved");
    }
    bzj_curve_free(merged);

    /* Polygon split and higher degree on request. */
    o = default_options();
    o.split = BZJ_SPLIT_POLYGON;
    merged = NULL;
    EXPECT_STATUS(bzj_merge_to_degree(a, b, &o, 6, &merged, NULL, NULL, &report), BZJ_OK);
    size_t degree = 0;
    if (merged) bzj_curve_degree(merged, &degree);
    CHECK(degree == 6, "degree %zu, expected 6", degree);
    CHECK(report.mu > 0.0 && report.mu < 1.0, "mu %g", report.mu);
    bzj_curve_free(merged);
    merged = (BzjCurve *)1; /* must be cleared on error */
    EXPECT_STATUS(bzj_merge_to_degree(a, b, &o, 2, &merged, NULL, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    CHECK(merged == NULL, "merged not cleared on error");

    /* Error paths of bzj_merge. */
    o = default_options();
    merged = NULL;
    EXPECT_STATUS(bzj_merge(NULL, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge(a, NULL, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge(a, b, NULL, &merged, NULL, NULL, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge(a, b, &o, NULL, NULL, NULL, NULL), BZJ_ERR_NULL_POINTER);
    o.p_point_count = 2; /* NULL array with a count */
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NULL_POINTER);
    o = default_options();
    o.split = BZJ_SPLIT_GIVEN;
    o.mu = 1.0;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "mu") != NULL, "message does not name mu");
    o.mu = NAN;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_NON_FINITE);
    o = default_options();
    BzjKeepPoint bad_param = {1.5, 0};
    o.q_points = &bad_param;
    o.q_point_count = 1;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "q_points[0].param") != NULL, "message does not name the point");
    BzjKeepPoint bad_order = {0.5, 4};
    o.q_points = &bad_order;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    o = default_options();
    o.keep_p = true;
    o.keep_q = true;
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INCONSISTENT);
    CHECK(strstr(bzj_last_error(), "keep Q unchanged") != NULL, "message does not name the constraint");
    /* Redundant but consistent: keep P and fix ends on pieces of one curve. */
    o.keep_q = false;
    o.fix_ends = true;
    o.split = BZJ_SPLIT_GIVEN;
    o.mu = 0.3;
    EXPECT_STATUS(bzj_merge(p, q, &o, &merged, NULL, NULL, NULL), BZJ_OK);
    bzj_curve_free(merged);
    merged = NULL;
    /* Invalid enum and bool values through the raw bytes. */
    o = default_options();
    {
        int32_t bad = 7;
        memcpy(&o.metric, &bad, sizeof bad);
    }
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    o = default_options();
    {
        int32_t bad = -1;
        memcpy(&o.split, &bad, sizeof bad);
    }
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    o = default_options();
    {
        unsigned char bad = 2;
        memcpy(&o.keep_p, &bad, 1);
    }
    EXPECT_STATUS(bzj_merge(a, b, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);
    /* Dimension mismatch. */
    const double line3[] = {0.0, 0.0, 0.0, 1.0, 1.0, 1.0};
    BzjCurve *c3 = make(3, 1, line3);
    o = default_options();
    EXPECT_STATUS(bzj_merge(a, c3, &o, &merged, NULL, NULL, NULL), BZJ_ERR_DIMENSION_MISMATCH);
    /* Polygon split with a zero-length polygon. */
    const double dot[] = {3.0, 0.0};
    BzjCurve *point = make(2, 0, dot);
    o.split = BZJ_SPLIT_POLYGON;
    EXPECT_STATUS(bzj_merge(a, point, &o, &merged, NULL, NULL, NULL), BZJ_ERR_INVALID_ARGUMENT);

    /* Chain: three pieces of one curve merge back into it. */
    BzjCurve *left = NULL, *middle = NULL, *right = NULL;
    bzj_curve_segment(original, 0.0, 0.2, &left);
    bzj_curve_segment(original, 0.2, 0.7, &middle);
    bzj_curve_segment(original, 0.7, 1.0, &right);
    const BzjCurve *chain[3] = {left, middle, right};
    const double inner[2] = {0.2, 0.7};
    BzjChainMergeOptions co;
    memset(&co, 0, sizeof co);
    co.metric = BZJ_METRIC_L2;
    co.split = BZJ_CHAIN_SPLIT_GIVEN;
    co.breakpoints = inner;
    co.breakpoint_count = 2;
    BzjCurve *pieces[3] = {NULL, NULL, NULL};
    double breakpoints[4];
    BzjChainMergeReport chain_report;
    merged = NULL;
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, pieces, 3, breakpoints, 4, &chain_report),
                  BZJ_OK);
    CHECK(merged && max_point_diff(merged, original) < 1e-9, "chain did not merge back");
    CHECK(chain_report.max_deviation < 1e-9, "chain deviation %g", chain_report.max_deviation);
    CHECK(breakpoints[0] == 0.0 && breakpoints[1] == 0.2 && breakpoints[3] == 1.0,
          "breakpoints %g %g %g %g", breakpoints[0], breakpoints[1], breakpoints[2], breakpoints[3]);
    CHECK(pieces[1] && max_point_diff(pieces[1], middle) < 1e-9, "middle piece changed");
    bzj_curve_free(merged);
    for (int k = 0; k < 3; k++) bzj_curve_free(pieces[k]);

    /* Chain with keep flags and keep points, uniform split. */
    bool keep_flags[3] = {false, false, false};
    BzjChainKeepPoint ckp = {2, 0.5, 1};
    co.split = BZJ_CHAIN_SPLIT_UNIFORM;
    co.keep = keep_flags;
    co.keep_points = &ckp;
    co.keep_point_count = 1;
    co.fix_ends = true;
    co.degree = 5;
    const BzjCurve *unrelated[3] = {a, b, left};
    merged = NULL;
    EXPECT_STATUS(bzj_merge_chain(unrelated, 3, &co, &merged, NULL, 0, NULL, 0, NULL), BZJ_OK);
    degree = 0;
    if (merged) bzj_curve_degree(merged, &degree);
    CHECK(degree == 5, "chain degree %zu", degree);
    bzj_curve_free(merged);

    /* Chain error paths. */
    memset(&co, 0, sizeof co);
    co.split = BZJ_CHAIN_SPLIT_UNIFORM;
    merged = NULL;
    EXPECT_STATUS(bzj_merge_chain(NULL, 3, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge_chain(chain, 3, NULL, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, NULL, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_NULL_POINTER);
    const BzjCurve *with_null[2] = {a, NULL};
    EXPECT_STATUS(bzj_merge_chain(with_null, 2, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_merge_chain(chain, 1, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, pieces, 2, NULL, 0, NULL),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, NULL, 0, breakpoints, 3, NULL),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    co.split = BZJ_CHAIN_SPLIT_GIVEN;
    const double unordered[2] = {0.6, 0.4};
    co.breakpoints = unordered;
    co.breakpoint_count = 2;
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "breakpoints[1]") != NULL, "message does not name the breakpoint");
    co.breakpoint_count = 1;
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    const double with_nan[2] = {0.3, NAN};
    co.breakpoints = with_nan;
    co.breakpoint_count = 2;
    EXPECT_STATUS(bzj_merge_chain(chain, 3, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_NON_FINITE);
    memset(&co, 0, sizeof co);
    co.split = BZJ_CHAIN_SPLIT_UNIFORM;
    bool keep_all[2] = {true, true};
    co.keep = keep_all;
    const BzjCurve *pair[2] = {a, b};
    EXPECT_STATUS(bzj_merge_chain(pair, 2, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INCONSISTENT);
    co.keep = NULL;
    BzjChainKeepPoint no_such_curve = {5, 0.5, 0};
    co.keep_points = &no_such_curve;
    co.keep_point_count = 1;
    EXPECT_STATUS(bzj_merge_chain(pair, 2, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    co.keep_points = NULL;
    co.keep_point_count = 0;
    {
        int32_t bad = 9;
        memcpy(&co.split, &bad, sizeof bad);
    }
    EXPECT_STATUS(bzj_merge_chain(pair, 2, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    const BzjCurve *mixed[2] = {a, c3};
    co.split = BZJ_CHAIN_SPLIT_UNIFORM;
    EXPECT_STATUS(bzj_merge_chain(mixed, 2, &co, &merged, NULL, 0, NULL, 0, NULL),
                  BZJ_ERR_DIMENSION_MISMATCH);
    CHECK(merged == NULL, "merged not NULL after errors");

    bzj_curve_free(left);
    bzj_curve_free(middle);
    bzj_curve_free(right);
    bzj_curve_free(point);
    bzj_curve_free(c3);
    bzj_curve_free(a);
    bzj_curve_free(b);
    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(original);
    test_merge_results_and_parameter_errors();
    if (failures) {
        fprintf(stderr, "merge.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("merge.c: all checks passed\n");
    return 0;
}
