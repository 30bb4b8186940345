/* bzj_connect_geometric, bzj_fillet_radius, bzj_fillet_radius_detailed and
 * bzj_fillet_radius_chain through the C ABI (contract
 * section "Geometric continuity"): given shape values satisfy the beta-constraints
 * R'(0) = b1 P', R''(0) = b1^2 P'' + b2 P' (and at Q); fair shapes on a
 * long-edge corner give a G2 blend whose unit tangent and curvature vector
 * match both edges, with one curvature maximum; the radius fillet cuts where
 * the arc of that radius touches the edges; shapes and report are
 * written; every error names its argument and clears `out`. Compiled as C11
 * and C++17 by tests/tests/c_programs.rs, run under valgrind memcheck by
 * scripts/ci-embedding.sh. Exits 0 when every check passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bezjoin.h"

static int failures = 0;

#define CHECK(cond, ...)                                    \
    do {                                                    \
        if (!(cond)) {                                      \
            fprintf(stderr, "geometric.c:%d: ", __LINE__);  \
            fprintf(stderr, __VA_ARGS__);                   \
            fprintf(stderr, "\n");                          \
            failures++;                                     \
        }                                                   \
    } while (0)

#define EXPECT_STATUS(call, expected)                                            \
    do {                                                                         \
        BzjStatus s_ = (call);                                                   \
        CHECK(s_ == (expected), "%s gave %s (%s), expected %s", #call,           \
              bzj_status_name(s_), bzj_last_error(), bzj_status_name(expected)); \
    } while (0)

static void expect_message(const char* word) {
    CHECK(strstr(bzj_last_error(), word) != NULL, "message \"%s\" lacks \"%s\"",
          bzj_last_error(), word);
}

/* unit tangent and curvature vector (r'' |r'|^2 - (r'.r'') r') / |r'|^4 of a
   2D jet (rows 0..2) */
static void frame(const double* jet, double* t, double* k) {
    const double* a = jet + 2;
    const double* b = jet + 4;
    double s2 = a[0] * a[0] + a[1] * a[1], m = a[0] * b[0] + a[1] * b[1];
    double s = sqrt(s2);
    for (int c = 0; c < 2; c++) {
        t[c] = a[c] / s;
        k[c] = (b[c] * s2 - m * a[c]) / (s2 * s2);
    }
}

static double dist(const double* a, const double* b) {
    return hypot(a[0] - b[0], a[1] - b[1]);
}

int main(void) {
    const double p_points[] = {0, 0, 1, 2, 3, 2, 4, 0};
    const double q_points[] = {6, 1, 7, 3, 9, 2, 10, 0};
    BzjCurve *p = NULL, *q = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 3, p_points, 8, &p), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(2, 3, q_points, 8, &q), BZJ_OK);

    /* given shapes: the beta-constraints, exactly */
    const double ps[2] = {0.8, 0.3}, qs[2] = {1.2, -0.2};
    BzjGeometricOptions o = {2, 2, ps, qs};
    BzjCurve* r = NULL;
    double ps_out[2] = {0, 0}, qs_out[2] = {0, 0};
    BzjFairnessReport report;
    memset(&report, 0, sizeof report);
    EXPECT_STATUS(bzj_connect_geometric(p, 0.7, q, 0.2, &o, &r, ps_out, qs_out, &report), BZJ_OK);
    CHECK(ps_out[0] == 0.8 && ps_out[1] == 0.3 && qs_out[0] == 1.2 && qs_out[1] == -0.2,
          "given shapes echoed");
    size_t degree = 0;
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 5, "degree %zu", degree);
    double pj[6], qj[6], r0[6], r1[6];
    EXPECT_STATUS(bzj_curve_eval(p, 0.7, 2, pj, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(q, 0.2, 2, qj, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(r, 0.0, 2, r0, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(r, 1.0, 2, r1, 6), BZJ_OK);
    for (int c = 0; c < 2; c++) {
        double want1 = ps[0] * pj[2 + c], want2 = ps[0] * ps[0] * pj[4 + c] + ps[1] * pj[2 + c];
        CHECK(fabs(r0[c] - pj[c]) <= 1e-12, "R(0) = P(u0)");
        CHECK(fabs(r0[2 + c] - want1) <= 1e-9 * (1 + fabs(want1)), "R'(0)");
        CHECK(fabs(r0[4 + c] - want2) <= 1e-9 * (1 + fabs(want2)), "R''(0): %g vs %g",
              r0[4 + c], want2);
        want1 = qs[0] * qj[2 + c];
        want2 = qs[0] * qs[0] * qj[4 + c] + qs[1] * qj[2 + c];
        CHECK(fabs(r1[2 + c] - want1) <= 1e-9 * (1 + fabs(want1)), "R'(1)");
        CHECK(fabs(r1[4 + c] - want2) <= 1e-9 * (1 + fabs(want2)), "R''(1)");
    }
    CHECK(report.energy > 0.0 && isfinite(report.energy), "energy %g", report.energy);
    bzj_curve_free(r);

    /* fair shapes: a corner of edges 40 and 20 long, setback 2 */
    const double long_edge[] = {-40, 0, 0, 0}, short_edge[] = {0, 0, 0, 20};
    BzjCurve *a = NULL, *b = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 1, long_edge, 4, &a), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(2, 1, short_edge, 4, &b), BZJ_OK);
    BzjGeometricOptions fair = {2, 2, NULL, NULL};
    EXPECT_STATUS(bzj_connect_geometric(a, 0.95, b, 0.1, &fair, &r, ps_out, qs_out, &report),
                  BZJ_OK);
    CHECK(ps_out[0] > 0.0 && qs_out[0] > 0.0, "fair beta_1 %g %g", ps_out[0], qs_out[0]);
    CHECK(report.curvature_extrema == 1, "%zu curvature extrema", report.curvature_extrema);
    CHECK(report.curvature_max > 0.25 && report.curvature_max < 2.0, "curvature max %g",
          report.curvature_max);
    double length = 0.0;
    EXPECT_STATUS(bzj_curve_length(r, 0.0, 1.0, &length), BZJ_OK);
    CHECK(length > 2.8 && length < 4.0, "fair blend length %g (arc of radius 2: 3.14)", length);
    /* G2 judged by unit tangent and curvature vector on both sides */
    double aj[6], bj[6], t1[2], k1[2], t2[2], k2[2];
    EXPECT_STATUS(bzj_curve_eval(a, 0.95, 2, aj, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(r, 0.0, 2, r0, 6), BZJ_OK);
    frame(aj, t1, k1);
    frame(r0, t2, k2);
    CHECK(dist(t1, t2) <= 1e-12 && dist(k1, k2) <= 1e-9, "G2 at the long edge");
    EXPECT_STATUS(bzj_curve_eval(b, 0.1, 2, bj, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(r, 1.0, 2, r1, 6), BZJ_OK);
    frame(bj, t1, k1);
    frame(r1, t2, k2);
    CHECK(dist(t1, t2) <= 1e-12 && dist(k1, k2) <= 1e-9, "G2 at the short edge");
    bzj_curve_free(r);

    /* errors name the argument and clear out */
    r = (BzjCurve*)&failures;
    EXPECT_STATUS(bzj_connect_geometric(p, 0.7, q, 0.2, NULL, &r, NULL, NULL, NULL),
                  BZJ_ERR_NULL_POINTER);
    CHECK(r == NULL, "out cleared");
    BzjGeometricOptions high = {7, 1, NULL, NULL};
    EXPECT_STATUS(bzj_connect_geometric(p, 0.7, q, 0.2, &high, &r, NULL, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("options.p_order");
    const double negative[2] = {-1.0, 0.0};
    BzjGeometricOptions bad = {2, 2, negative, NULL};
    EXPECT_STATUS(bzj_connect_geometric(p, 0.7, q, 0.2, &bad, &r, NULL, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("options.p_shape[0]");
    EXPECT_STATUS(bzj_connect_geometric(p, 1.5, q, 0.2, &o, &r, NULL, NULL, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("u0");
    CHECK(r == NULL, "out cleared");
    /* a zero tangent at the join (P's last two poles equal): no shape values
       give a blend with defined curvature there, searched or given */
    const double cusp_points[] = {0, 0, 1, 1, 2, 0, 2, 0};
    BzjCurve* cusp = NULL;
    EXPECT_STATUS(bzj_curve_new(2, 3, cusp_points, 8, &cusp), BZJ_OK);
    BzjGeometricOptions fair_cusp = {2, 2, NULL, NULL};
    r = (BzjCurve*)&failures;
    EXPECT_STATUS(bzj_connect_geometric(cusp, 1.0, q, 0.2, &fair_cusp, &r, NULL, NULL, &report),
                  BZJ_ERR_ILL_CONDITIONED);
    expect_message("tangent of p at u0 = 1 is zero");
    CHECK(r == NULL, "out cleared");
    EXPECT_STATUS(bzj_connect_geometric(q, 0.2, cusp, 0.0, &o, &r, NULL, NULL, NULL), BZJ_OK);
    bzj_curve_free(r);
    r = NULL;
    EXPECT_STATUS(bzj_connect_geometric(cusp, 1.0, q, 0.2, &o, &r, NULL, NULL, NULL),
                  BZJ_ERR_ILL_CONDITIONED);
    expect_message("tangent of p");
    bzj_curve_free(cusp);

    /* bzj_fillet_radius at the vertex of the two edges: cut where the arc of
       radius 2 touches them (2 from the corner), G2 blend between */
    BzjCurve *pt = NULL, *blend = NULL, *qt = NULL;
    EXPECT_STATUS(bzj_fillet_radius(a, b, 2.0, 2, &pt, &blend, &qt, &report), BZJ_OK);
    double first = 0, last = 0, x[6], y[6];
    EXPECT_STATUS(bzj_curve_eval(pt, 1.0, 2, x, 6), BZJ_OK);
    CHECK(fabs(x[0] + 2.0) <= 1e-10 && fabs(x[1]) <= 1e-12, "P cut at (%g, %g)", x[0], x[1]);
    EXPECT_STATUS(bzj_curve_eval(qt, 0.0, 2, y, 6), BZJ_OK);
    CHECK(fabs(y[0]) <= 1e-12 && fabs(y[1] - 2.0) <= 1e-10, "Q cut at (%g, %g)", y[0], y[1]);
    EXPECT_STATUS(bzj_curve_eval(blend, 0.0, 2, r0, 6), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(blend, 1.0, 2, r1, 6), BZJ_OK);
    frame(x, t1, k1);
    frame(r0, t2, k2);
    CHECK(dist(t1, t2) <= 1e-12 && dist(k1, k2) <= 1e-9, "radius fillet: G2 at P");
    frame(y, t1, k1);
    frame(r1, t2, k2);
    CHECK(dist(t1, t2) <= 1e-12 && dist(k1, k2) <= 1e-9, "radius fillet: G2 at Q");
    CHECK(report.curvature_extrema == 1 && report.curvature_max > 0.5, "radius fillet report");
    EXPECT_STATUS(bzj_curve_domain(pt, &first, &last), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(blend);
    bzj_curve_free(qt);
    pt = blend = qt = (BzjCurve*)&failures;
    EXPECT_STATUS(bzj_fillet_radius(a, b, 30.0, 2, &pt, &blend, &qt, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("radius");
    CHECK(pt == NULL && blend == NULL && qt == NULL, "outs cleared");
    EXPECT_STATUS(bzj_fillet_radius(a, b, 1.0, 0, &pt, &blend, &qt, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("order");
    EXPECT_STATUS(bzj_fillet_radius(a, b, NAN, 2, &pt, &blend, &qt, NULL), BZJ_ERR_NON_FINITE);
    EXPECT_STATUS(bzj_fillet_radius(a, b, 1.0, 2, &pt, NULL, &qt, NULL), BZJ_ERR_NULL_POINTER);

    /* bzj_fillet_radius_detailed: the same fillet, with the arc's centre
       (-2, 2) (at distance 2 from both edges), the touching points, and the
       blend's distance from the arc's circle (positive: a G2 blend is not
       the arc, and below the radius). */
    BzjRadiusFilletReport detailed;
    memset(&detailed, 0, sizeof detailed);
    double centre[2] = {0, 0};
    EXPECT_STATUS(bzj_fillet_radius_detailed(a, b, 2.0, 2, &pt, &blend, &qt, &detailed, centre),
                  BZJ_OK);
    CHECK(fabs(centre[0] + 2.0) <= 1e-10 && fabs(centre[1] - 2.0) <= 1e-10, "centre (%g, %g)",
          centre[0], centre[1]);
    CHECK(fabs(40.0 * (1.0 - detailed.u0) - 2.0) <= 1e-10 && fabs(20.0 * detailed.v0 - 2.0) <= 1e-10,
          "touching points u0 = %g, v0 = %g", detailed.u0, detailed.v0);
    CHECK(detailed.fairness.energy == report.energy &&
              detailed.fairness.curvature_max == report.curvature_max &&
              detailed.fairness.curvature_extrema == report.curvature_extrema,
          "detailed fairness differs from bzj_fillet_radius's");
    CHECK(detailed.arc_deviation > 0.0 && detailed.arc_deviation < 2.0, "arc deviation %g",
          detailed.arc_deviation);
    /* independently: the largest sampled distance from the circle */
    double worst = 0.0;
    for (int i = 0; i <= 64; i++) {
        double z[2];
        EXPECT_STATUS(bzj_curve_eval(blend, i / 64.0, 0, z, 2), BZJ_OK);
        double off = fabs(hypot(z[0] - centre[0], z[1] - centre[1]) - 2.0);
        if (off > worst) worst = off;
    }
    CHECK(worst <= detailed.arc_deviation * (1.0 + 1e-12) && worst >= 0.9 * detailed.arc_deviation,
          "sampled deviation %g vs reported %g", worst, detailed.arc_deviation);
    bzj_curve_free(pt);
    bzj_curve_free(blend);
    bzj_curve_free(qt);
    EXPECT_STATUS(bzj_fillet_radius_detailed(a, b, 2.0, 3, &pt, &blend, &qt, NULL, NULL), BZJ_OK);
    bzj_curve_free(pt);
    bzj_curve_free(blend);
    bzj_curve_free(qt);
    pt = blend = qt = (BzjCurve*)&failures;
    EXPECT_STATUS(bzj_fillet_radius_detailed(a, b, -1.0, 2, &pt, &blend, &qt, &detailed, centre),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("radius");
    CHECK(pt == NULL && blend == NULL && qt == NULL, "outs cleared");
    EXPECT_STATUS(bzj_fillet_radius_detailed(a, NULL, 2.0, 2, &pt, &blend, &qt, NULL, NULL),
                  BZJ_ERR_NULL_POINTER);

    /* bzj_fillet_radius_chain on a closed square of side 4, radius 1: every
       corner is cut 1 from its vertex (u0 = 0.75, v0 = 0.25 on these lines),
       each blend meets its neighbours with G2 (tangent and curvature vector),
       and the pieces go round once. */
    const double sq[4][4] = {{0, 0, 4, 0}, {4, 0, 4, 4}, {4, 4, 0, 4}, {0, 4, 0, 0}};
    BzjCurve* side[4];
    for (int i = 0; i < 4; i++) EXPECT_STATUS(bzj_curve_new(2, 1, sq[i], 4, &side[i]), BZJ_OK);
    const BzjCurve* wire[4] = {side[0], side[1], side[2], side[3]};
    size_t count = 0;
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 2, 1, NULL, 0, &count, NULL), BZJ_OK);
    CHECK(count == 8, "closed square: %zu pieces", count);
    BzjCurve* pieces[8];
    BzjRadiusFilletReport corners[4];
    memset(corners, 0, sizeof corners);
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 2, 1, pieces, 8, &count, corners), BZJ_OK);
    for (int i = 0; i < 4; i++) {
        CHECK(fabs(corners[i].u0 - 0.75) <= 1e-12 && fabs(corners[i].v0 - 0.25) <= 1e-12,
              "corner %d cut at %g, %g", i, corners[i].u0, corners[i].v0);
        CHECK(corners[i].fairness.curvature_extrema == 1, "corner %d extrema %zu", i,
              corners[i].fairness.curvature_extrema);
    }
    for (int i = 0; i < 8; i++) {
        double end[6], start[6], te[2], ke[2], ts[2], ks[2];
        EXPECT_STATUS(bzj_curve_eval(pieces[i], 1.0, 2, end, 6), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval(pieces[(i + 1) % 8], 0.0, 2, start, 6), BZJ_OK);
        frame(end, te, ke);
        frame(start, ts, ks);
        CHECK(dist(end, start) <= 1e-13, "pieces %d, %d apart", i, (i + 1) % 8);
        CHECK(dist(te, ts) <= 1e-12 && dist(ke, ks) <= 1e-9, "pieces %d, %d not G2", i,
              (i + 1) % 8);
    }
    for (int i = 0; i < 8; i++) bzj_curve_free(pieces[i]);
    /* open: 7 pieces, 3 reports */
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 3, 0, pieces, 8, &count, corners), BZJ_OK);
    CHECK(count == 7, "open square: %zu pieces", count);
    for (int i = 0; i < 7; i++) bzj_curve_free(pieces[i]);
    /* errors */
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 3.0, 2, 1, pieces, 8, &count, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("curves[0]");
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 9.0, 2, 1, pieces, 8, &count, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("corner 0 radius");
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 2, 1, pieces, 7, &count, NULL),
                  BZJ_ERR_BUFFER_TOO_SMALL);
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 2, 2, pieces, 8, &count, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("closed");
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 1, 1.0, 2, 0, pieces, 8, &count, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("at least 2");
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 0, 1, pieces, 8, &count, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    expect_message("order");
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, NAN, 2, 1, pieces, 8, &count, NULL),
                  BZJ_ERR_NON_FINITE);
    EXPECT_STATUS(bzj_fillet_radius_chain(NULL, 4, 1.0, 2, 1, pieces, 8, &count, NULL),
                  BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_fillet_radius_chain(wire, 4, 1.0, 2, 1, pieces, 8, NULL, NULL),
                  BZJ_ERR_NULL_POINTER);
    for (int i = 0; i < 4; i++) bzj_curve_free(side[i]);

    bzj_curve_free(a);
    bzj_curve_free(b);
    bzj_curve_free(p);
    bzj_curve_free(q);
    if (failures) {
        fprintf(stderr, "geometric.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("geometric.c: all checks passed\n");
    return 0;
}
