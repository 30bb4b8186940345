/* Intersection and corner rounding through the C contract: bzj_intersect,
 * bzj_intersect_detailed, bzj_intersect_options_default, bzj_fillet,
 * bzj_fillet_auto_scale, bzj_fillet_deviation and bzj_fillet_chain, with
 * each error path.
 * Compiled as C11 and as C++17 and linked with libbezjoin.a by
 * tests/tests/c_programs.rs. Exits 0 when every check passes. */
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

static void expect_message(const char* word) {
    const char* m = bzj_last_error();
    CHECK(m != NULL && strstr(m, word) != NULL, "message '%s' does not name '%s'",
          m ? m : "(null)", word);
}

static BzjCurve* make(size_t degree, const double* points) {
    BzjCurve* c = NULL;
    BzjStatus s = bzj_curve_new(2, degree, points, 2 * (degree + 1), &c);
    CHECK(s == BZJ_OK && c != NULL, "bzj_curve_new failed");
    return c;
}

/* Value and first derivative of a 2D curve at t. */
static void eval1(const BzjCurve* c, double t, double out[4]) {
    EXPECT_STATUS(bzj_curve_eval(c, t, 1, out, 4), BZJ_OK);
}

static double dist(const double* a, const double* b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
}

static void test_intersect(void) {
    const double pl[] = {-2.0, 0.0, 2.0, 0.0};
    const double ql[] = {0.0, -2.0, 0.0, 2.0};
    BzjCurve* p = make(1, pl);
    BzjCurve* q = make(1, ql);
    double pairs[8];
    size_t count = 99;
    EXPECT_STATUS(bzj_intersect(p, q, pairs, 4, &count), BZJ_OK);
    CHECK(count == 1, "line-line count %zu", count);
    CHECK(fabs(pairs[0] - 0.5) < 1e-15 && fabs(pairs[1] - 0.5) < 1e-15, "line-line (%g, %g)",
          pairs[0], pairs[1]);
    /* Count-only query. */
    count = 99;
    EXPECT_STATUS(bzj_intersect(p, q, NULL, 0, &count), BZJ_OK);
    CHECK(count == 1, "count-only %zu", count);

    /* Cubic graphs over x = 3t whose y differ by 10 (t-.2)(t-.5)(t-.8):
       three crossings at u = v = 0.2, 0.5, 0.8. In Bernstein form the
       difference 10t^3 - 15t^2 + 6.6t - 0.8 has coefficients -0.8, 1.4,
       -1.4, 0.8. */
    const double qc[] = {0.0, 0.0, 1.0, 1.0, 2.0, -1.0, 3.0, 0.5};
    const double pc[] = {0.0, -0.8, 1.0, 2.4, 2.0, -2.4, 3.0, 1.3};
    BzjCurve* pcub = make(3, pc);
    BzjCurve* qcub = make(3, qc);
    EXPECT_STATUS(bzj_intersect(pcub, qcub, pairs, 2, &count), BZJ_OK);
    CHECK(count == 3, "cubic-cubic count %zu", count);
    CHECK(fabs(pairs[0] - 0.2) < 1e-13 && fabs(pairs[2] - 0.5) < 1e-13,
          "cubic-cubic u = %.17g, %.17g", pairs[0], pairs[2]);
    for (int i = 0; i < 2; i++) {
        double a[4], b[4];
        eval1(pcub, pairs[2 * i], a);
        eval1(qcub, pairs[2 * i + 1], b);
        CHECK(dist(a, b) < 1e-14, "hit %d is %g apart", i, dist(a, b));
    }

    /* Detailed: touching and overlap. */
    const double parabola[] = {-1.0, 1.0, 0.0, -1.0, 1.0, 1.0};
    const double axis[] = {-1.0, 0.0, 1.0, 0.0};
    BzjCurve* par = make(2, parabola);
    BzjCurve* ax = make(1, axis);
    BzjIntersection hits[4];
    EXPECT_STATUS(bzj_intersect_detailed(par, ax, NULL, hits, 4, &count), BZJ_OK);
    CHECK(count == 1 && hits[0].kind == BZJ_INTERSECTION_TOUCHING, "touching: %zu hits", count);
    const double a1[] = {0.0, 0.0, 2.0, 2.0};
    const double a2[] = {1.0, 1.0, 3.0, 3.0};
    BzjCurve* l1 = make(1, a1);
    BzjCurve* l2 = make(1, a2);
    BzjIntersectOptions options;
    EXPECT_STATUS(bzj_intersect_options_default(&options), BZJ_OK);
    CHECK(options.relative_distance_tolerance == 1e-9 && options.max_depth == 60,
          "default options");
    EXPECT_STATUS(bzj_intersect_detailed(l1, l2, &options, hits, 4, &count), BZJ_OK);
    CHECK(count == 1 && hits[0].kind == BZJ_INTERSECTION_OVERLAP, "overlap: %zu hits", count);
    CHECK(fabs(hits[0].u - 0.5) < 1e-14 && fabs(hits[0].u_end - 1.0) < 1e-14 &&
              fabs(hits[0].v) < 1e-14 && fabs(hits[0].v_end - 0.5) < 1e-14,
          "overlap range");
    EXPECT_STATUS(bzj_intersect_detailed(l1, l2, &options, NULL, 0, &count), BZJ_OK);
    CHECK(count == 1, "detailed count-only");

    /* Error paths. */
    EXPECT_STATUS(bzj_intersect(NULL, q, pairs, 4, &count), BZJ_ERR_NULL_POINTER);
    expect_message("p");
    EXPECT_STATUS(bzj_intersect(p, q, pairs, 4, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("count");
    EXPECT_STATUS(bzj_intersect(p, q, NULL, 4, &count), BZJ_ERR_NULL_POINTER);
    expect_message("out");
    const double p3[] = {0.0, 0.0, 0.0, 1.0, 1.0, 1.0};
    BzjCurve* c3 = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 1, p3, 6, &c3), BZJ_OK);
    EXPECT_STATUS(bzj_intersect(p, c3, pairs, 4, &count), BZJ_ERR_DIMENSION_MISMATCH);
    options.relative_distance_tolerance = NAN;
    EXPECT_STATUS(bzj_intersect_detailed(p, q, &options, hits, 4, &count), BZJ_ERR_NON_FINITE);
    expect_message("relative_distance_tolerance");
    options.relative_distance_tolerance = 2.0;
    EXPECT_STATUS(bzj_intersect_detailed(p, q, &options, hits, 4, &count),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("relative_distance_tolerance");

    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(pcub);
    bzj_curve_free(qcub);
    bzj_curve_free(par);
    bzj_curve_free(ax);
    bzj_curve_free(l1);
    bzj_curve_free(l2);
    bzj_curve_free(c3);
}

static BzjFilletOptions fillet_options(double dp, double dq, size_t kp, size_t kq) {
    BzjFilletOptions o;
    o.p_setback = dp;
    o.q_setback = dq;
    o.p_order = kp;
    o.q_order = kq;
    o.p_scale = 1.0;
    o.q_scale = 1.0;
    return o;
}

static void test_fillet(void) {
    const double pl[] = {-2.0, 0.0, 0.0, 0.5, 2.0, 0.0};
    const double ql[] = {0.0, -2.0, 0.2, 0.0, 0.0, 2.0};
    BzjCurve* p = make(2, pl);
    BzjCurve* q = make(2, ql);
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    BzjFilletOptions o = fillet_options(0.4, 0.6, 2, 1);
    o.p_scale = 1.5;
    EXPECT_STATUS(bzj_fillet(p, q, &o, &pt, &r, &qt), BZJ_OK);
    size_t degree = 0;
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 4, "blend degree %zu", degree);
    /* C^1 in the B-spline sense: R'(0) = alpha * P'(u0) and p_trimmed'(1) =
       u0 * P'(u0); R'(1) = beta * Q'(v0). */
    double a[4], b[4], c[4], d[4];
    eval1(pt, 1.0, a);
    eval1(r, 0.0, b);
    eval1(r, 1.0, c);
    eval1(qt, 0.0, d);
    CHECK(dist(a, b) < 1e-13, "P|R gap %g", dist(a, b));
    CHECK(dist(c, d) < 1e-13, "R|Q gap %g", dist(c, d));
    double cross_pr = a[2] * b[3] - a[3] * b[2];
    double cross_rq = c[2] * d[3] - c[3] * d[2];
    CHECK(fabs(cross_pr) < 1e-12 && a[2] * b[2] + a[3] * b[3] > 0.0, "P|R tangent");
    CHECK(fabs(cross_rq) < 1e-12 && c[2] * d[2] + c[3] * d[3] > 0.0, "R|Q tangent");
    /* Setback along P: arc length of p_trimmed is len(P; 0..u*) - 0.4. */
    double total = 0.0, kept = 0.0;
    double pairs[2];
    size_t count = 0;
    EXPECT_STATUS(bzj_intersect(p, q, pairs, 1, &count), BZJ_OK);
    EXPECT_STATUS(bzj_curve_length(p, 0.0, pairs[0], &total), BZJ_OK);
    EXPECT_STATUS(bzj_curve_length(pt, 0.0, 1.0, &kept), BZJ_OK);
    CHECK(fabs(total - kept - 0.4) < 1e-9, "p setback %.17g", total - kept);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);

    /* Errors: each leaves the three outputs NULL. */
    const double far[] = {5.0, -1.0, 5.0, 1.0};
    BzjCurve* f = make(1, far);
    EXPECT_STATUS(bzj_fillet(p, f, &o, &pt, &r, &qt), BZJ_ERR_NO_INTERSECTION);
    expect_message("do not cross");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    const double tangent[] = {-1.0, 0.25, 1.0, 0.25};
    BzjCurve* t = make(1, tangent);
    EXPECT_STATUS(bzj_fillet(p, t, &o, &pt, &r, &qt), BZJ_ERR_NO_INTERSECTION);
    expect_message("touch");
    BzjFilletOptions bad = fillet_options(10.0, 0.5, 1, 1);
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("p_setback");
    bad = fillet_options(0.5, 10.0, 1, 1);
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("q_setback");
    bad = fillet_options(0.5, 0.5, 3, 1);
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("p_order");
    bad = fillet_options(NAN, 0.5, 1, 1);
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_ERR_NON_FINITE);
    expect_message("p_setback");
    bad = fillet_options(0.5, 0.5, 1, 1);
    bad.q_scale = -1.0;
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("q_scale");
    EXPECT_STATUS(bzj_fillet(p, q, NULL, &pt, &r, &qt), BZJ_ERR_NULL_POINTER);
    expect_message("options");
    EXPECT_STATUS(bzj_fillet(p, q, &o, &pt, NULL, &qt), BZJ_ERR_NULL_POINTER);
    expect_message("blend");
    CHECK(pt == NULL && qt == NULL, "outputs not NULL after a null blend pointer");
    const double p3[] = {0.0, 0.0, 0.0, 1.0, 1.0, 1.0};
    BzjCurve* c3 = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 1, p3, 6, &c3), BZJ_OK);
    EXPECT_STATUS(bzj_fillet(p, c3, &o, &pt, &r, &qt), BZJ_ERR_DIMENSION_MISMATCH);

    /* Deviation mode. */
    BzjDeviationFilletOptions dev;
    dev.max_deviation = 0.1;
    dev.setback_ratio = 1.0;
    dev.p_order = 2;
    dev.q_order = 2;
    dev.p_scale = 1.0;
    dev.q_scale = 1.0;
    BzjDeviationFilletReport report;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, &report), BZJ_OK);
    CHECK(fabs(report.deviation - 0.1) <= 1e-9 * 0.1, "deviation %.17g", report.deviation);
    CHECK(report.p_setback == report.q_setback && report.p_setback > 0.0, "setbacks");
    /* No point of the blend is closer to the corner than the bound. */
    double x[2];
    EXPECT_STATUS(bzj_intersect(p, q, pairs, 1, &count), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(p, pairs[0], 0, x, 2), BZJ_OK);
    double closest = 1e300;
    for (int i = 0; i <= 4000; i++) {
        double y[2];
        EXPECT_STATUS(bzj_curve_eval(r, i / 4000.0, 0, y, 2), BZJ_OK);
        if (dist(x, y) < closest) closest = dist(x, y);
    }
    CHECK(closest >= 0.1 * (1.0 - 1e-9) && closest <= 0.1 * (1.0 + 1e-6), "closest %.17g",
          closest);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    dev.setback_ratio = 0.5;
    dev.max_deviation = 0.05;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    dev.max_deviation = 100.0;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, NULL), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("max_deviation");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    dev.max_deviation = 0.1;
    dev.setback_ratio = NAN;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, NULL), BZJ_ERR_NON_FINITE);
    expect_message("setback_ratio");
    dev.setback_ratio = 1.0;
    dev.q_order = 5;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, NULL), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("q_order");
    dev.q_order = 1;
    EXPECT_STATUS(bzj_fillet_deviation(p, f, &dev, &pt, &r, &qt, NULL), BZJ_ERR_NO_INTERSECTION);
    EXPECT_STATUS(bzj_fillet_deviation(p, q, NULL, &pt, &r, &qt, NULL), BZJ_ERR_NULL_POINTER);

    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(f);
    bzj_curve_free(t);
    bzj_curve_free(c3);
}

static void test_chain(void) {
    /* A closed triangle. */
    const double ab[] = {0.0, 0.0, 4.0, 0.0};
    const double bc[] = {4.0, 0.0, 0.0, 3.0};
    const double ca[] = {0.0, 3.0, 0.0, 0.0};
    const BzjCurve* curves[3];
    BzjCurve* owned[3];
    owned[0] = make(1, ab);
    owned[1] = make(1, bc);
    owned[2] = make(1, ca);
    for (int i = 0; i < 3; i++) curves[i] = owned[i];
    BzjFilletOptions o = fillet_options(0.5, 0.5, 1, 1);
    size_t count = 0;
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 1, NULL, 0, &count), BZJ_OK);
    CHECK(count == 6, "closed chain needs %zu pieces", count);
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 0, NULL, 0, &count), BZJ_OK);
    CHECK(count == 5, "open chain needs %zu pieces", count);
    BzjCurve* pieces[6];
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 1, pieces, 3, &count),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    CHECK(pieces[0] == NULL && pieces[2] == NULL, "handles not NULL after an error");
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 1, pieces, 6, &count), BZJ_OK);
    for (int i = 0; i < 6; i++) {
        double a[4], b[4];
        eval1(pieces[i], 1.0, a);
        eval1(pieces[(i + 1) % 6], 0.0, b);
        CHECK(dist(a, b) < 1e-13, "pieces %d and %d are %g apart", i, (i + 1) % 6, dist(a, b));
        double cross = a[2] * b[3] - a[3] * b[2];
        CHECK(fabs(cross) < 1e-12 * (fabs(a[2]) + fabs(a[3])) * (fabs(b[2]) + fabs(b[3])),
              "pieces %d and %d not tangent", i, (i + 1) % 6);
    }
    for (int i = 0; i < 6; i++) bzj_curve_free(pieces[i]);

    /* Errors. */
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 5, pieces, 6, &count), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("closed");
    EXPECT_STATUS(bzj_fillet_chain(curves, 1, &o, 0, pieces, 6, &count), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("at least 2");
    const BzjCurve* with_null[3];
    with_null[0] = owned[0];
    with_null[1] = NULL;
    with_null[2] = owned[2];
    EXPECT_STATUS(bzj_fillet_chain(with_null, 3, &o, 0, pieces, 6, &count), BZJ_ERR_NULL_POINTER);
    expect_message("curves[1]");
    /* The count-only query refuses what the real call would refuse. */
    count = 77;
    EXPECT_STATUS(bzj_fillet_chain(with_null, 3, &o, 0, NULL, 0, &count), BZJ_ERR_NULL_POINTER);
    expect_message("curves[1]");
    CHECK(count == 77, "count written by a refused query: %zu", count);
    EXPECT_STATUS(bzj_fillet_chain(curves, 1, &o, 0, NULL, 0, &count), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("at least 2");
    EXPECT_STATUS(bzj_fillet_chain(NULL, 3, &o, 0, pieces, 6, &count), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 0, pieces, 6, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &o, 0, NULL, 6, &count), BZJ_ERR_NULL_POINTER);
    BzjFilletOptions longer = fillet_options(2.5, 2.5, 1, 1);
    EXPECT_STATUS(bzj_fillet_chain(curves, 3, &longer, 1, pieces, 6, &count),
                  BZJ_ERR_INVALID_ARGUMENT);
    const double far[] = {10.0, 10.0, 11.0, 10.0};
    BzjCurve* f = make(1, far);
    const BzjCurve* apart[2];
    apart[0] = owned[0];
    apart[1] = f;
    EXPECT_STATUS(bzj_fillet_chain(apart, 2, &o, 0, pieces, 6, &count), BZJ_ERR_NO_INTERSECTION);
    expect_message("corner 0");
    for (int i = 0; i < 3; i++) bzj_curve_free(owned[i]);
    bzj_curve_free(f);
}

/* Two fast lines written as cubics (speed 8, crossing at the origin), C^3
 * with setback 0.5: scale 1 puts the blend's second control point past the
 * corner (x > 0); the automatic scale keeps every control point in the
 * corner's quadrant and joins with R'(0) = s * P'(u0). */
static void test_fillet_auto_scale(void) {
    const double pl[] = {-4.0, 0.0, -4.0 / 3.0, 0.0, 4.0 / 3.0, 0.0, 4.0, 0.0};
    const double ql[] = {0.0, -4.0, 0.0, -4.0 / 3.0, 0.0, 4.0 / 3.0, 0.0, 4.0};
    BzjCurve* p = make(3, pl);
    BzjCurve* q = make(3, ql);
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    BzjFilletOptions o = fillet_options(0.5, 0.5, 3, 3);
    double points[16];
    EXPECT_STATUS(bzj_fillet(p, q, &o, &pt, &r, &qt), BZJ_OK);
    EXPECT_STATUS(bzj_curve_points(r, points, 16), BZJ_OK);
    CHECK(points[2] > 0.0, "scale 1: R_1.x = %g, expected past the corner", points[2]);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);

    o.p_scale = -1.0; /* ignored, not validated */
    o.q_scale = NAN;
    double s = -1.0;
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &o, &pt, &r, &qt, &s), BZJ_OK);
    CHECK(s > 0.0 && s < 1.0, "chosen scale %g", s);
    EXPECT_STATUS(bzj_curve_points(r, points, 16), BZJ_OK);
    for (int i = 0; i < 8; i++) {
        CHECK(points[2 * i] <= 1e-15 && points[2 * i + 1] >= -1e-15,
              "control point %d (%g, %g) outside the corner", i, points[2 * i],
              points[2 * i + 1]);
    }
    double a[4], b[4];
    eval1(pt, 1.0, a); /* u0 * P'(u0) */
    eval1(r, 0.0, b);  /* s * P'(u0) */
    double u0 = 0.5 - 0.5 / 8.0;
    CHECK(fabs(b[2] - s * a[2] / u0) < 1e-12 * fabs(b[2]) && fabs(b[3]) < 1e-12,
          "R'(0) = (%g, %g), s P'(u0) = %g", b[2], b[3], s * a[2] / u0);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    /* scale_out may be NULL. */
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &o, &pt, &r, &qt, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    /* Errors as bzj_fillet's. */
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, NULL, &pt, &r, &qt, &s), BZJ_ERR_NULL_POINTER);
    expect_message("options");
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &o, NULL, &r, &qt, &s), BZJ_ERR_NULL_POINTER);
    expect_message("p_trimmed");
    CHECK(r == NULL && qt == NULL, "outputs not NULL after a null pointer");
    BzjFilletOptions bad = fillet_options(9.0, 0.5, 3, 3);
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &bad, &pt, &r, &qt, &s), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("p_setback");
    bad = fillet_options(0.5, 0.5, 3, 4);
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &bad, &pt, &r, &qt, &s), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("q_order");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    bzj_curve_free(p);
    bzj_curve_free(q);
}

int main(void) {
    test_intersect();
    test_fillet();
    test_fillet_auto_scale();
    test_chain();
    if (failures != 0) {
        fprintf(stderr, "fillet.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("fillet.c: all checks passed\n");
    return 0;
}
