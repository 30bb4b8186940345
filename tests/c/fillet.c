/* Intersection and corner rounding through the C contract: bzj_intersect,
 * bzj_intersect_detailed, bzj_intersect_options_default, bzj_fillet,
 * bzj_fillet_auto_scale, bzj_fillet_vertex_auto_scale, bzj_fillet_balanced_scale,
 * bzj_fillet_vertex_balanced_scale, bzj_fillet_chain_balanced_scale, bzj_fillet_deviation,
 * bzj_fillet_deviation_auto_scale,
 * bzj_fillet_chain and bzj_fillet_chain_auto_scale (closed
 * and open chains, one above the parallel threshold of 64 corners, checked
 * for C^k with cuts computed here), with each error path.
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
    /* An order above the degree is accepted, as for connect (P is a
       quadratic: its third derivative, 0, is matched too). */
    bad = fillet_options(0.5, 0.5, 3, 1);
    EXPECT_STATUS(bzj_fillet(p, q, &bad, &pt, &r, &qt), BZJ_OK);
    {
        size_t blend_degree = 0;
        EXPECT_STATUS(bzj_curve_degree(r, &blend_degree), BZJ_OK);
        CHECK(blend_degree == 3 + 1 + 1, "blend degree %zu, expected 5", blend_degree);
    }
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
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
    /* A strict bound: within 0.1, and within 1e-9 relative of it. */
    CHECK(report.deviation <= 0.1 && report.deviation >= 0.1 * (1.0 - 1e-9), "deviation %.17g",
          report.deviation);
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
    /* An order above the degree is accepted, as for connect. */
    dev.q_order = 3;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
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
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    /* Orders above the degrees are accepted, as for connect. */
    bad = fillet_options(0.5, 0.5, 3, 4);
    EXPECT_STATUS(bzj_fillet_auto_scale(p, q, &bad, &pt, &r, &qt, &s), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    bzj_curve_free(p);
    bzj_curve_free(q);
}

/* The balanced scale at a vertex: lines 1000 and 10 long meeting at a right
 * angle, setback 1, give the blend of lines 10 and 10 (the cuts are the
 * same points, only the edges' speeds differ), with both ends of the blend
 * at one speed; the one-s automatic scale does not. bzj_fillet_balanced_scale
 * at a crossing: the scales written, errors as bzj_fillet's. */
/* |a - b| <= tol * max(1, |b|) */
static int close_to(double a, double b, double tol) {
    return fabs(a - b) <= tol * fmax(1.0, fabs(b));
}

/* The plane blend r leaves its two ends at one speed: |r'(0)| = |r'(1)|. */
static void check_one_speed(const BzjCurve* r, const char* what) {
    double a[4], b[4];
    eval1(r, 0.0, a);
    eval1(r, 1.0, b);
    CHECK(close_to(hypot(a[2], a[3]), hypot(b[2], b[3]), 1e-12), "%s: end speeds %g and %g",
          what, hypot(a[2], a[3]), hypot(b[2], b[3]));
}

static void test_fillet_balanced_scale(void) {
    const double long_edge[] = {-1000.0, 0.0, 0.0, 0.0};
    const double short_edge[] = {-10.0, 0.0, 0.0, 0.0};
    const double up[] = {0.0, 0.0, 0.0, 10.0};
    BzjCurve* p_long = make(1, long_edge);
    BzjCurve* p_short = make(1, short_edge);
    BzjCurve* q = make(1, up);
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    BzjFilletOptions o = fillet_options(1.0, 1.0, 2, 2);
    o.p_scale = NAN; /* ignored, not validated */
    double equal[12], unequal[12];
    double alpha = -1.0, beta = -1.0;
    EXPECT_STATUS(bzj_fillet_vertex_balanced_scale(p_short, q, &o, 0.0, &pt, &r, &qt, &alpha,
                                                   &beta), BZJ_OK);
    CHECK(close_to(alpha, beta, 1e-12), "equal speeds, scales %g and %g", alpha, beta);
    EXPECT_STATUS(bzj_curve_points(r, equal, 12), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_vertex_balanced_scale(p_long, q, &o, 0.0, &pt, &r, &qt, &alpha,
                                                   &beta), BZJ_OK);
    CHECK(close_to(alpha * 1000.0, beta * 10.0, 1e-12), "speeds %g and %g", alpha * 1000.0,
          beta * 10.0);
    EXPECT_STATUS(bzj_curve_points(r, unequal, 12), BZJ_OK);
    for (int i = 0; i < 12; i++) {
        CHECK(fabs(unequal[i] - equal[i]) < 1e-12, "control coordinate %d: %g vs %g", i,
              unequal[i], equal[i]);
    }
    check_one_speed(r, "vertex, lines 1000 and 10");
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p_long, q, &o, 0.0, &pt, &r, &qt, NULL), BZJ_OK);
    EXPECT_STATUS(bzj_curve_points(r, unequal, 12), BZJ_OK);
    double moved = 0.0;
    for (int i = 0; i < 12; i++) moved = fmax(moved, fabs(unequal[i] - equal[i]));
    CHECK(moved > 1e-2, "the automatic scale moved the blend by only %g", moved);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    /* Errors as bzj_fillet_vertex's, NULL scale outputs allowed. */
    EXPECT_STATUS(bzj_fillet_vertex_balanced_scale(p_long, q, &o, -1.0, &pt, &r, &qt, NULL,
                                                   NULL), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("gap");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    EXPECT_STATUS(bzj_fillet_vertex_balanced_scale(p_long, q, &o, 0.0, &pt, NULL, &qt, NULL,
                                                   NULL), BZJ_ERR_NULL_POINTER);
    expect_message("blend");

    /* At a crossing: two crossing cubics (lines), scales written. */
    const double pl[] = {-4.0, 0.0, -4.0 / 3.0, 0.0, 4.0 / 3.0, 0.0, 4.0, 0.0};
    const double ql[] = {0.0, -4.0, 0.0, -2.0, 0.0, 2.0, 0.0, 4.0};
    BzjCurve* p = make(3, pl);
    BzjCurve* qc = make(3, ql);
    BzjFilletOptions c = fillet_options(0.5, 0.5, 3, 3);
    EXPECT_STATUS(bzj_fillet_balanced_scale(p, qc, &c, &pt, &r, &qt, &alpha, &beta), BZJ_OK);
    CHECK(alpha > 0.0 && beta > 0.0 && isfinite(alpha * beta), "scales %g and %g", alpha, beta);
    check_one_speed(r, "crossing");
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_balanced_scale(p, qc, NULL, &pt, &r, &qt, NULL, NULL),
                  BZJ_ERR_NULL_POINTER);
    expect_message("options");
    BzjFilletOptions bad = fillet_options(9.0, 0.5, 3, 3);
    EXPECT_STATUS(bzj_fillet_balanced_scale(p, qc, &bad, &pt, &r, &qt, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("p_setback");
    bzj_curve_free(p);
    bzj_curve_free(qc);
    bzj_curve_free(p_long);
    bzj_curve_free(p_short);
    bzj_curve_free(q);
}

/* The default that never loops, at a wire's vertex: a 40 and a 20 long edge
 * meeting at the origin, setback 2. The paper's scale 1 throws the blend's
 * control points out of the corner (their speed is 40 and 20 against a
 * setback of 2: a loop); the automatic scale keeps every control point in
 * the triangle of the two cuts and the vertex, so the blend (inside its
 * control polygon's hull) cannot loop and is shorter than the two legs. */
static void test_fillet_vertex_auto_scale(void) {
    const double long_edge[] = {-40.0, 0.0, 0.0, 0.0};
    const double short_edge[] = {0.0, 0.0, 0.0, 20.0};
    BzjCurve* p = make(1, long_edge);
    BzjCurve* q = make(1, short_edge);
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    BzjFilletOptions o = fillet_options(2.0, 2.0, 2, 2);
    double points[12];
    int outside = 0;
    EXPECT_STATUS(bzj_fillet_vertex(p, q, &o, 1e-9, &pt, &r, &qt), BZJ_OK);
    EXPECT_STATUS(bzj_curve_points(r, points, 12), BZJ_OK);
    for (int i = 0; i < 6; i++) {
        double x = points[2 * i], y = points[2 * i + 1];
        outside += x > 1e-12 || y < -1e-12 || y > x + 2.0 + 1e-12;
    }
    CHECK(outside > 0, "scale 1 kept every control point in the corner");
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);

    o.p_scale = NAN; /* ignored, not validated */
    o.q_scale = -1.0;
    double s = -1.0;
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p, q, &o, 1e-9, &pt, &r, &qt, &s), BZJ_OK);
    CHECK(s > 0.0 && s < 1.0, "chosen scale %g", s);
    EXPECT_STATUS(bzj_curve_points(r, points, 12), BZJ_OK);
    for (int i = 0; i < 6; i++) {
        double x = points[2 * i], y = points[2 * i + 1];
        CHECK(x <= 1e-12 && y >= -1e-12 && y <= x + 2.0 + 1e-12,
              "control point %d (%g, %g) outside the corner's triangle", i, x, y);
    }
    double length = 0.0;
    EXPECT_STATUS(bzj_curve_length(r, 0.0, 1.0, &length), BZJ_OK);
    CHECK(length > 2.0 * sqrt(2.0) && length < 4.0, "blend length %g", length);
    double a[4], b[4];
    eval1(pt, 1.0, a);
    eval1(r, 0.0, b);
    CHECK(dist(a, b) < 1e-14, "blend starts at the cut");
    CHECK(fabs(b[3]) < 1e-12 && b[2] > 0.0, "tangent at the cut: (%g, %g)", b[2], b[3]);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p, q, &o, 1e-9, &pt, &r, &qt, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    /* Errors as bzj_fillet_vertex's. */
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p, q, &o, -1.0, &pt, &r, &qt, &s),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("gap");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(q, p, &o, 1e-9, &pt, &r, &qt, &s),
                  BZJ_ERR_NO_INTERSECTION);
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p, q, NULL, 1e-9, &pt, &r, &qt, &s),
                  BZJ_ERR_NULL_POINTER);
    expect_message("options");
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(p, q, &o, 1e-9, &pt, NULL, &qt, &s),
                  BZJ_ERR_NULL_POINTER);
    expect_message("blend");
    bzj_curve_free(p);
    bzj_curve_free(q);
}

/* bzj_fillet_chain_auto_scale on a closed triangle whose edges are fast
 * (cubics of speed 3x the edge): every corner gets its own positive scale,
 * written in corner order, the pieces close up with matching tangents,
 * and the count query and errors are bzj_fillet_chain's. */
/* The closed triangle (0,0), (4,0), (0,3) of cubic edges of speeds 4, 5 and 3:
 * `owned` gets the handles, `curves` the same as const pointers. */
static void fast_triangle(BzjCurve* owned[3], const BzjCurve* curves[3]) {
    const double ab[] = {0.0, 0.0, 4.0 / 3.0, 0.0, 8.0 / 3.0, 0.0, 4.0, 0.0};
    const double bc[] = {4.0, 0.0, 8.0 / 3.0, 1.0, 4.0 / 3.0, 2.0, 0.0, 3.0};
    const double ca[] = {0.0, 3.0, 0.0, 2.0, 0.0, 1.0, 0.0, 0.0};
    owned[0] = make(3, ab);
    owned[1] = make(3, bc);
    owned[2] = make(3, ca);
    for (int i = 0; i < 3; i++) curves[i] = owned[i];
}

static void test_chain_auto_scale(void) {
    BzjCurve* owned[3];
    const BzjCurve* curves[3];
    fast_triangle(owned, curves);
    BzjFilletOptions o = fillet_options(0.5, 0.5, 2, 2);
    o.p_scale = NAN; /* ignored */
    size_t count = 0;
    double scales[3] = {-1.0, -1.0, -1.0};
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, &o, 1, NULL, 0, &count, scales), BZJ_OK);
    CHECK(count == 6, "closed chain needs %zu pieces", count);
    CHECK(scales[0] == -1.0, "scales written by a count query");
    BzjCurve* pieces[6];
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, &o, 1, pieces, 6, &count, scales),
                  BZJ_OK);
    for (int i = 0; i < 3; i++) CHECK(scales[i] > 0.0 && scales[i] < 10.0, "scale %d: %g", i, scales[i]);
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
    /* The same corners one by one: the chain's scale is the pair's. */
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    double s = 0.0;
    EXPECT_STATUS(bzj_fillet_vertex_auto_scale(owned[0], owned[1], &o, 1e-12, &pt, &r, &qt, &s),
                  BZJ_OK);
    CHECK(fabs(s - scales[0]) <= 1e-12 * s, "corner 0: chain %g, pair %g", scales[0], s);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, &o, 0, pieces, 5, &count, NULL), BZJ_OK);
    CHECK(count == 5, "open chain: %zu pieces", count);
    for (int i = 0; i < 5; i++) bzj_curve_free(pieces[i]);
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, &o, 1, pieces, 5, &count, scales),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, &o, 7, pieces, 6, &count, scales),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("closed");
    EXPECT_STATUS(bzj_fillet_chain_auto_scale(curves, 3, NULL, 1, pieces, 6, &count, scales),
                  BZJ_ERR_NULL_POINTER);
    expect_message("options");
    for (int i = 0; i < 3; i++) bzj_curve_free(owned[i]);
}

/* bzj_fillet_chain_balanced_scale on the triangle of test_chain_auto_scale
 * (cubic edges of different speeds): alpha, beta of corner i at 2i, 2i+1, each
 * corner's pair equal to bzj_fillet_vertex_balanced_scale's, every blend
 * leaving both its edges at one speed, the pieces closed up; the count query
 * and errors as bzj_fillet_chain's. */
static void test_chain_balanced_scale(void) {
    BzjCurve* owned[3];
    const BzjCurve* curves[3];
    fast_triangle(owned, curves);
    BzjFilletOptions o = fillet_options(0.5, 0.5, 2, 2);
    o.q_scale = NAN; /* ignored */
    size_t count = 0;
    double scales[6] = {-1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
    EXPECT_STATUS(bzj_fillet_chain_balanced_scale(curves, 3, &o, 1, NULL, 0, &count, scales),
                  BZJ_OK);
    CHECK(count == 6 && scales[0] == -1.0, "count query: %zu pieces, scales[0] %g", count,
          scales[0]);
    BzjCurve* pieces[6];
    EXPECT_STATUS(bzj_fillet_chain_balanced_scale(curves, 3, &o, 1, pieces, 6, &count, scales),
                  BZJ_OK);
    for (int i = 0; i < 6; i++) {
        double a[4], b[4];
        eval1(pieces[i], 1.0, a);
        eval1(pieces[(i + 1) % 6], 0.0, b);
        CHECK(dist(a, b) < 1e-13, "pieces %d and %d are %g apart", i, (i + 1) % 6, dist(a, b));
    }
    for (int corner = 0; corner < 3; corner++) {
        check_one_speed(pieces[2 * corner + 1], "chain corner");
        BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
        double alpha = 0.0, beta = 0.0;
        EXPECT_STATUS(bzj_fillet_vertex_balanced_scale(owned[corner], owned[(corner + 1) % 3], &o,
                                                       1e-12, &pt, &r, &qt, &alpha, &beta),
                      BZJ_OK);
        CHECK(close_to(alpha, scales[2 * corner], 1e-12) &&
                  close_to(beta, scales[2 * corner + 1], 1e-12),
              "corner %d: chain (%g, %g), pair (%g, %g)", corner, scales[2 * corner],
              scales[2 * corner + 1], alpha, beta);
        bzj_curve_free(pt);
        bzj_curve_free(r);
        bzj_curve_free(qt);
    }
    CHECK(!close_to(scales[0], scales[1], 1e-3), "corner 0: the edges' speeds differ, scales %g %g",
          scales[0], scales[1]);
    for (int i = 0; i < 6; i++) bzj_curve_free(pieces[i]);
    EXPECT_STATUS(bzj_fillet_chain_balanced_scale(curves, 3, &o, 1, pieces, 5, &count, scales),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    EXPECT_STATUS(bzj_fillet_chain_balanced_scale(curves, 3, NULL, 1, pieces, 6, &count, NULL),
                  BZJ_ERR_NULL_POINTER);
    expect_message("options");
    for (int i = 0; i < 3; i++) bzj_curve_free(owned[i]);
}

/* bzj_fillet_deviation_auto_scale: two lines 60 and 40 long crossing at
 * right angles at the origin, deviation 0.1. With the paper's scale 1 the
 * blend needs setbacks longer than the arc's to reach the deviation and
 * leaves the corner; with the automatic scale it stays in the triangle of
 * the cuts and the crossing, within the same deviation window. */
static void test_fillet_deviation_auto_scale(void) {
    const double pl[] = {-50.0, 0.0, 10.0, 0.0};
    const double ql[] = {0.0, -10.0, 0.0, 30.0};
    BzjCurve* p = make(1, pl);
    BzjCurve* q = make(1, ql);
    BzjDeviationFilletOptions dev;
    memset(&dev, 0, sizeof dev);
    dev.max_deviation = 0.1;
    dev.setback_ratio = 1.0;
    dev.p_order = 2;
    dev.q_order = 2;
    dev.p_scale = 1.0;
    dev.q_scale = 1.0;
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    BzjDeviationFilletReport paper, automatic;
    EXPECT_STATUS(bzj_fillet_deviation(p, q, &dev, &pt, &r, &qt, &paper), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    dev.p_scale = NAN; /* ignored */
    double s = -1.0;
    EXPECT_STATUS(bzj_fillet_deviation_auto_scale(p, q, &dev, &pt, &r, &qt, &automatic, &s),
                  BZJ_OK);
    CHECK(s > 0.0 && s < 1.0, "chosen scale %g", s);
    CHECK(automatic.deviation <= 0.1 && automatic.deviation >= 0.1 * (1.0 - 1e-9),
          "deviation %.17g", automatic.deviation);
    /* a 90-degree corner's arc with that deviation has setback 0.1 / (sqrt 2 - 1) = 0.24 */
    CHECK(automatic.p_setback < 2.0 * 0.1 / (sqrt(2.0) - 1.0) && paper.p_setback > automatic.p_setback,
          "setbacks: automatic %g, scale 1 %g", automatic.p_setback, paper.p_setback);
    double points[12];
    EXPECT_STATUS(bzj_curve_points(r, points, 12), BZJ_OK);
    double d = automatic.p_setback;
    for (int i = 0; i < 6; i++) {
        double x = points[2 * i], y = points[2 * i + 1];
        CHECK(x <= 1e-12 && y >= -1e-12 && y <= x + d + 1e-12,
              "control point %d (%g, %g) outside the corner's triangle", i, x, y);
    }
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_deviation_auto_scale(p, q, &dev, &pt, &r, &qt, NULL, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    dev.max_deviation = -1.0;
    EXPECT_STATUS(bzj_fillet_deviation_auto_scale(p, q, &dev, &pt, &r, &qt, NULL, &s),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("max_deviation");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    EXPECT_STATUS(bzj_fillet_deviation_auto_scale(p, q, NULL, &pt, &r, &qt, NULL, &s),
                  BZJ_ERR_NULL_POINTER);
    bzj_curve_free(p);
    bzj_curve_free(q);
}

/* ---- Open chains through bzj_fillet_chain, checked independently. ---- */

static unsigned long long rng_state = 0x2545F4914F6CDD1DULL;
static double rnd(double a, double b) {
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * (double)(rng_state >> 11) / 9007199254740992.0;
}

#define MAX_CHAIN 80

/* A zigzag of n cubics: curve i runs along the segment from node i to node
 * i + 1, extended by `over` times its length beyond both nodes, with its
 * inner control points bent off the segment. With over = 0 consecutive
 * curves meet end to end; with over > 0 they cross near the shared node,
 * inside both curves. */
static void zigzag(size_t n, double over, BzjCurve** out) {
    double nodes[2 * (MAX_CHAIN + 1)];
    for (size_t i = 0; i <= n; i++) {
        nodes[2 * i] = 1.5 * (double)i + rnd(-0.2, 0.2);
        nodes[2 * i + 1] = (i % 2 ? 1.0 : 0.0) + rnd(-0.2, 0.2);
    }
    for (size_t i = 0; i < n; i++) {
        double d[2] = {nodes[2 * i + 2] - nodes[2 * i], nodes[2 * i + 3] - nodes[2 * i + 1]};
        double a[2] = {nodes[2 * i] - over * d[0], nodes[2 * i + 1] - over * d[1]};
        double D[2] = {(1.0 + 2.0 * over) * d[0], (1.0 + 2.0 * over) * d[1]};
        double s1 = rnd(-0.1, 0.1), s2 = rnd(-0.1, 0.1);
        double pts[8] = {a[0],
                         a[1],
                         a[0] + D[0] / 3.0 - s1 * D[1],
                         a[1] + D[1] / 3.0 + s1 * D[0],
                         a[0] + 2.0 * D[0] / 3.0 - s2 * D[1],
                         a[1] + 2.0 * D[1] / 3.0 + s2 * D[0],
                         a[0] + D[0],
                         a[1] + D[1]};
        out[i] = make(3, pts);
    }
}

/* The crossing of c and d nearest their shared end: smallest (1 - u) + v
 * (the rule documented for bzj_fillet_chain). */
static void nearest_crossing(const BzjCurve* c, const BzjCurve* d, double* u, double* v) {
    double pairs[16];
    size_t count = 0;
    EXPECT_STATUS(bzj_intersect(c, d, pairs, 8, &count), BZJ_OK);
    CHECK(count >= 1 && count <= 8, "%zu hits", count);
    *u = pairs[0];
    *v = pairs[1];
    for (size_t k = 1; k < count && k < 8; k++) {
        if ((1.0 - pairs[2 * k]) + pairs[2 * k + 1] < (1.0 - *u) + *v) {
            *u = pairs[2 * k];
            *v = pairs[2 * k + 1];
        }
    }
}

/* The parameter t between lo and hi where the arc length of c from `from`
 * is `length` (bisection on bzj_curve_length; the length is monotone in t). */
static double param_at_length(const BzjCurve* c, double from, double length, double lo,
                              double hi) {
    for (int it = 0; it < 200 && lo != hi; it++) {
        double mid = 0.5 * (lo + hi), l = 0.0;
        if (mid == lo || mid == hi) break;
        EXPECT_STATUS(bzj_curve_length(c, from, mid, &l), BZJ_OK);
        if (fabs(l) < length) {
            if (from <= lo) lo = mid; else hi = mid;
        } else {
            if (from <= lo) hi = mid; else lo = mid;
        }
    }
    return 0.5 * (lo + hi);
}

/* Largest |a_j / sa^j - b_j / sb^j| over the 2D derivative rows j = 0..k,
 * relative to the larger side of that order. */
static double scaled_jump(const double* a, double sa, const double* b, double sb, size_t k) {
    double worst = 0.0, fa = 1.0, fb = 1.0;
    for (size_t j = 0; j <= k; j++) {
        double x[2] = {a[2 * j] / fa, a[2 * j + 1] / fa};
        double y[2] = {b[2 * j] / fb, b[2 * j + 1] / fb};
        double size = fmax(hypot(x[0], x[1]), hypot(y[0], y[1]));
        double jump = hypot(x[0] - y[0], x[1] - y[1]);
        if (size > 0.0 && jump / size > worst) worst = jump / size;
        fa *= sa;
        fb *= sb;
    }
    return worst;
}

/* Round every corner of the open chain `curves` (n curves) and check what
 * the header promises, with cuts computed here: corner i is rounded as
 * bzj_fillet rounds it, so with u0 / v0 the cuts on curves[i] / curves[i+1]
 * (setbacks measured from the crossing by arc length), the kept part of
 * curve i is [v0 of corner i-1 (0 for i = 0), u0 of corner i (1 for the
 * last)] of parameter length h_i, and the pieces form a C^k B-spline with
 * knot intervals h_i (for the kept curve) and alpha (for the blend), the
 * next curve's interval scaled by alpha / beta. Per corner that is
 *   trimmed_i^(j)(1) / h_i^j = blend^(j)(0) / alpha^j,   j = 0..kp,
 *   blend^(j)(1) / beta^j = trimmed_{i+1}^(j)(0) / h_{i+1}^j,   j = 0..kq,
 * (derivatives of each piece in its own parameter, from bzj_curve_eval). */
static void check_open_chain(BzjCurve** owned, size_t n, const BzjFilletOptions* o,
                             const char* label) {
    const BzjCurve* curves[MAX_CHAIN];
    for (size_t i = 0; i < n; i++) curves[i] = owned[i];
    size_t needed = 0;
    EXPECT_STATUS(bzj_fillet_chain(curves, n, o, 0, NULL, 0, &needed), BZJ_OK);
    CHECK(needed == 2 * n - 1, "%s: %zu pieces needed", label, needed);
    BzjCurve* pieces[2 * MAX_CHAIN];
    size_t count = 0;
    EXPECT_STATUS(bzj_fillet_chain(curves, n, o, 0, pieces, 2 * n - 1, &count), BZJ_OK);
    CHECK(count == 2 * n - 1, "%s: count %zu", label, count);
    if (count != 2 * n - 1) return;
    /* Cuts, independently of the library's own inversion. */
    double start[MAX_CHAIN], end[MAX_CHAIN];
    start[0] = 0.0;
    end[n - 1] = 1.0;
    for (size_t i = 0; i + 1 < n; i++) {
        double us = 0.0, vs = 0.0;
        nearest_crossing(curves[i], curves[i + 1], &us, &vs);
        end[i] = param_at_length(curves[i], us, o->p_setback, 0.0, us);
        start[i + 1] = param_at_length(curves[i + 1], vs, o->q_setback, vs, 1.0);
    }
    size_t k = o->p_order > o->q_order ? o->p_order : o->q_order;
    size_t rows = k + 1;
    double worst_gap = 0.0, worst_jump = 0.0, worst_on = 0.0;
    for (size_t i = 0; i < n; i++) {
        double h = end[i] - start[i];
        CHECK(h > 0.0, "%s: curve %zu keeps [%g, %g]", label, i, start[i], end[i]);
        /* The kept piece lies on curve i over [start, end]. */
        for (int s = 0; s <= 8; s++) {
            double a[2], b[2];
            EXPECT_STATUS(bzj_curve_eval(pieces[2 * i], s / 8.0, 0, a, 2), BZJ_OK);
            EXPECT_STATUS(bzj_curve_eval(curves[i], start[i] + h * (s / 8.0), 0, b, 2), BZJ_OK);
            if (dist(a, b) > worst_on) worst_on = dist(a, b);
        }
        size_t degree = 0;
        EXPECT_STATUS(bzj_curve_degree(pieces[2 * i], &degree), BZJ_OK);
        CHECK(degree == 3, "%s: trimmed curve %zu has degree %zu", label, i, degree);
        if (i + 1 == n) break;
        const BzjCurve* left = pieces[2 * i];
        const BzjCurve* blend = pieces[2 * i + 1];
        const BzjCurve* right = pieces[2 * i + 2];
        EXPECT_STATUS(bzj_curve_degree(blend, &degree), BZJ_OK);
        CHECK(degree == o->p_order + o->q_order + 1, "%s: blend %zu has degree %zu", label, i,
              degree);
        double a[8], b[8], c[8], d[8];
        EXPECT_STATUS(bzj_curve_eval(left, 1.0, k, a, 2 * rows), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval(blend, 0.0, k, b, 2 * rows), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval(blend, 1.0, k, c, 2 * rows), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval(right, 0.0, k, d, 2 * rows), BZJ_OK);
        /* Consecutive pieces meet. */
        if (dist(a, b) > worst_gap) worst_gap = dist(a, b);
        if (dist(c, d) > worst_gap) worst_gap = dist(c, d);
        double jl = scaled_jump(a, h, b, o->p_scale, o->p_order);
        double jr = scaled_jump(c, o->q_scale, d, end[i + 1] - start[i + 1], o->q_order);
        CHECK(jl <= 1e-9 && jr <= 1e-9, "%s: corner %zu derivative jumps %.3g (P side), %.3g (Q side)",
              label, i, jl, jr);
        if (jl > worst_jump) worst_jump = jl;
        if (jr > worst_jump) worst_jump = jr;
        /* Not more than promised: with these curved data the next
           derivative does jump (guards the check itself). */
        if (o->p_order < 3) {
            double a2[8], b2[8];
            EXPECT_STATUS(bzj_curve_eval(left, 1.0, o->p_order + 1, a2, 8), BZJ_OK);
            EXPECT_STATUS(bzj_curve_eval(blend, 0.0, o->p_order + 1, b2, 8), BZJ_OK);
            double more = scaled_jump(a2, h, b2, o->p_scale, o->p_order + 1);
            CHECK(more > 1e-6, "%s: corner %zu is smoother than asked (%g)", label, i, more);
        }
    }
    printf("%s: %zu corners, pieces at most %.2g apart, %.2g off their curves, derivative "
           "jump at most %.2g relative\n",
           label, n - 1, worst_gap, worst_on, worst_jump);
    CHECK(worst_gap < 1e-13, "%s: pieces %g apart", label, worst_gap);
    CHECK(worst_on < 1e-12, "%s: a kept piece is %g off its curve", label, worst_on);
    for (size_t i = 0; i < count; i++) bzj_curve_free(pieces[i]);
}

static void test_open_chains(void) {
    /* Four crossing cubics (crossings inside the curves), C^2 with unequal
       scales: the sequential path. */
    BzjCurve* owned[MAX_CHAIN];
    zigzag(4, 0.1, owned);
    BzjFilletOptions o = fillet_options(0.3, 0.25, 2, 2);
    o.p_scale = 1.25;
    o.q_scale = 0.8;
    check_open_chain(owned, 4, &o, "crossing chain");
    for (size_t i = 0; i < 4; i++) bzj_curve_free(owned[i]);
    /* 70 cubics meeting end to end: 69 corners, above the 64 beyond which
       bzj_fillet_chain works in parallel; C^1 with scales 1, and C^3 with
       unequal setbacks and scales. */
    zigzag(70, 0.0, owned);
    o = fillet_options(0.25, 0.25, 1, 1);
    check_open_chain(owned, 70, &o, "long chain, C^1");
    o = fillet_options(0.2, 0.3, 3, 3);
    o.p_scale = 0.9;
    o.q_scale = 1.1;
    check_open_chain(owned, 70, &o, "long chain, C^3");
    for (size_t i = 0; i < 70; i++) bzj_curve_free(owned[i]);
}

/* Space curves meet only within the distance tolerance: a skew pair is
 * BZJ_ERR_NO_INTERSECTION. */
static void test_skew_3d(void) {
    const double x[3] = {0.3, -0.2, 1.1};
    /* The common normal of the tangents (1, 0, 0) and (0, 1, 0.5) at X. */
    const double nrm[3] = {0.0, -0.5 / sqrt(1.25), 1.0 / sqrt(1.25)};
    const double pl[6] = {x[0] - 1.0, x[1], x[2], x[0] + 1.0, x[1], x[2]};
    const double base[9] = {x[0] - 0.3, x[1] - 1.0, x[2] - 0.5, x[0] + 0.3, x[1],
                            x[2],       x[0] - 0.3, x[1] + 1.0, x[2] + 0.5};
    BzjCurve *p = NULL, *q = NULL, *skew = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 1, pl, 6, &p), BZJ_OK);
    double lifted[9];
    for (int i = 0; i < 9; i++) lifted[i] = base[i] + 1e-6 * nrm[i % 3];
    EXPECT_STATUS(bzj_curve_new(3, 2, base, 9, &q), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(3, 2, lifted, 9, &skew), BZJ_OK);
    BzjFilletOptions o = fillet_options(0.3, 0.3, 1, 1);
    BzjCurve *pt = NULL, *r = NULL, *qt = NULL;
    /* Meeting (Q through X at v = 1/2): rounded. */
    EXPECT_STATUS(bzj_fillet(p, q, &o, &pt, &r, &qt), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(r);
    bzj_curve_free(qt);
    /* Lifted by 1e-6, far above the default tolerance 1e-9 x 1.6. */
    EXPECT_STATUS(bzj_fillet(p, skew, &o, &pt, &r, &qt), BZJ_ERR_NO_INTERSECTION);
    expect_message("do not cross");
    CHECK(pt == NULL && r == NULL && qt == NULL, "outputs not NULL after an error");
    BzjDeviationFilletOptions dev;
    dev.max_deviation = 0.05;
    dev.setback_ratio = 1.0;
    dev.p_order = 1;
    dev.q_order = 1;
    dev.p_scale = 1.0;
    dev.q_scale = 1.0;
    EXPECT_STATUS(bzj_fillet_deviation(p, skew, &dev, &pt, &r, &qt, NULL),
                  BZJ_ERR_NO_INTERSECTION);
    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(skew);
}

int main(void) {
    test_intersect();
    test_fillet();
    test_fillet_auto_scale();
    test_fillet_vertex_auto_scale();
    test_fillet_balanced_scale();
    test_chain_balanced_scale();
    test_fillet_deviation_auto_scale();
    test_chain();
    test_chain_auto_scale();
    test_open_chains();
    test_skew_3d();
    if (failures != 0) {
        fprintf(stderr, "fillet.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("fillet.c: all checks passed\n");
    return 0;
}
