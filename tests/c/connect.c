/* bzj_connect, bzj_connect_auto_scale and bzj_connect_balanced_scale
 * through the C ABI: continuity
 * checked by evaluating both curves with bzj_curve_eval, and every error
 * path (null pointers, bad parameters, bad constraints, an ill-posed
 * problem refused by its residual check, a degree above 31); orders above
 * the curves' degrees are accepted (the contract allows them).
 * Returns 0 on success, 1 with a message on the first failure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bezjoin.h"

static int failures = 0;

#define CHECK(cond, ...)                                  \
    do {                                                  \
        if (!(cond)) {                                    \
            fprintf(stderr, "connect.c:%d: ", __LINE__);  \
            fprintf(stderr, __VA_ARGS__);                 \
            fprintf(stderr, "\n");                        \
            failures++;                                   \
        }                                                 \
    } while (0)

#define EXPECT_STATUS(call, expected)                                          \
    do {                                                                       \
        BzjStatus s_ = (call);                                                 \
        CHECK(s_ == (expected), "%s gave %s (%s), expected %s", #call,         \
              bzj_status_name(s_), bzj_last_error(), bzj_status_name(expected)); \
    } while (0)

/* |a - b| <= tol * max(1, |b|) */
static int close_to(double a, double b, double tol) {
    double scale = fabs(b) > 1.0 ? fabs(b) : 1.0;
    return fabs(a - b) <= tol * scale;
}

/* R^(k)(tr) == s^k C^(k)(tc) for k = 0..order, all coordinates. */
static void check_match(const BzjCurve* r, double tr, const BzjCurve* c, double tc,
                        size_t order, double s, size_t dim, const char* what) {
    double rv[4 * 3], cv[4 * 3];
    size_t len = (order + 1) * dim;
    EXPECT_STATUS(bzj_curve_eval(r, tr, order, rv, len), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(c, tc, order, cv, len), BZJ_OK);
    double power = 1.0;
    for (size_t k = 0; k <= order; k++) {
        for (size_t i = 0; i < dim; i++) {
            double want = power * cv[k * dim + i];
            CHECK(close_to(rv[k * dim + i], want, 1e-9), "%s: order %zu coord %zu: %g vs %g",
                  what, k, i, rv[k * dim + i], want);
        }
        power *= s;
    }
}

int main(void) {
    const double p_points[] = {0, 0, 0, 1, 2, 1, 2, 2, 0, 3, 0, 1};
    const double q_points[] = {6, 0, 0, 7, -2, 1, 8, -2, 0, 9, 0, 2};
    const double flat_points[] = {0, 0, 1, 1};
    BzjCurve *p = NULL, *q = NULL, *flat = NULL, *r = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 3, p_points, 12, &p), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(3, 3, q_points, 12, &q), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(2, 1, flat_points, 4, &flat), BZJ_OK);

    /* C3 at both ends, scales 1.5 and 0.75, one K = 1 constraint. */
    const double values[] = {4.5, 0.0, 1.0, 3.0, -1.0, 0.5};
    BzjPointConstraint constraint = {0.4, 1, values};
    BzjConnectOptions options = {3, 3, 1.5, 0.75, &constraint, 1};
    EXPECT_STATUS(bzj_connect(p, 0.8, q, 0.1, &options, &r), BZJ_OK);
    size_t degree = 0;
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 3 + 3 + 1 + 2, "degree %zu, expected 9", degree);
    check_match(r, 0.0, p, 0.8, 3, 1.5, 3, "P end");
    check_match(r, 1.0, q, 0.1, 3, 0.75, 3, "Q end");
    double at_t[2 * 3];
    EXPECT_STATUS(bzj_curve_eval(r, 0.4, 1, at_t, 6), BZJ_OK);
    for (int i = 0; i < 6; i++) {
        CHECK(close_to(at_t[i], values[i], 1e-9), "constraint value %d: %g vs %g", i, at_t[i],
              values[i]);
    }
    bzj_curve_free(r);
    r = NULL;

    /* The paper's case: no constraints, scales 1, NULL constraint array. */
    BzjConnectOptions paper = {2, 1, 1.0, 1.0, NULL, 0};
    EXPECT_STATUS(bzj_connect(p, 1.0, q, 0.0, &paper, &r), BZJ_OK);
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 4, "degree %zu, expected 4", degree);
    check_match(r, 0.0, p, 1.0, 2, 1.0, 3, "paper P end");
    check_match(r, 1.0, q, 0.0, 1, 1.0, 3, "paper Q end");
    bzj_curve_free(r);
    r = NULL;

    /* Automatic scale, with and without scale_out. */
    double scale = -1.0;
    EXPECT_STATUS(bzj_connect_auto_scale(p, 0.8, q, 0.1, &options, &r, &scale), BZJ_OK);
    CHECK(scale > 0.0 && isfinite(scale), "auto scale %g", scale);
    check_match(r, 0.0, p, 0.8, 3, scale, 3, "auto P end");
    check_match(r, 1.0, q, 0.1, 3, scale, 3, "auto Q end");
    bzj_curve_free(r);
    r = NULL;
    EXPECT_STATUS(bzj_connect_auto_scale(p, 0.8, q, 0.1, &options, &r, NULL), BZJ_OK);
    bzj_curve_free(r);
    r = NULL;

    /* Balanced scale: each end matched with its own scale, both ends of R
       at one speed, and the same R when P is given on [0, 50] instead of
       [0, 1] (a NURBS with the same poles: P' divided by 50). */
    {
        double alpha = -1.0, beta = -1.0;
        EXPECT_STATUS(bzj_connect_balanced_scale(p, 0.8, q, 0.1, &options, &r, &alpha, &beta),
                      BZJ_OK);
        CHECK(alpha > 0.0 && beta > 0.0 && isfinite(alpha * beta), "scales %g %g", alpha, beta);
        check_match(r, 0.0, p, 0.8, 3, alpha, 3, "balanced P end");
        check_match(r, 1.0, q, 0.1, 3, beta, 3, "balanced Q end");
        double ends[2][2 * 3];
        EXPECT_STATUS(bzj_curve_eval(r, 0.0, 1, ends[0], 6), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval(r, 1.0, 1, ends[1], 6), BZJ_OK);
        double speed0 = sqrt(ends[0][3] * ends[0][3] + ends[0][4] * ends[0][4] +
                             ends[0][5] * ends[0][5]);
        double speed1 = sqrt(ends[1][3] * ends[1][3] + ends[1][4] * ends[1][4] +
                             ends[1][5] * ends[1][5]);
        CHECK(close_to(speed0, speed1, 1e-9), "balanced speeds %g and %g", speed0, speed1);
        size_t count = 0;
        EXPECT_STATUS(bzj_curve_degree(r, &count), BZJ_OK);
        double first[10 * 3], second[10 * 3];
        EXPECT_STATUS(bzj_curve_points(r, first, (count + 1) * 3), BZJ_OK);
        bzj_curve_free(r);
        r = NULL;
        const double knots[] = {0, 0, 0, 0, 50, 50, 50, 50};
        BzjCurve* slow = NULL;
        EXPECT_STATUS(bzj_nurbs_new(3, 3, p_points, 12, NULL, 0, knots, 8, &slow), BZJ_OK);
        double alpha50 = -1.0;
        EXPECT_STATUS(bzj_connect_balanced_scale(slow, 40.0, q, 0.1, &options, &r, &alpha50, NULL),
                      BZJ_OK);
        CHECK(close_to(alpha50, 50.0 * alpha, 1e-9), "alpha %g on [0, 50], %g on [0, 1]",
              alpha50, alpha);
        EXPECT_STATUS(bzj_curve_points(r, second, (count + 1) * 3), BZJ_OK);
        for (size_t i = 0; i < (count + 1) * 3; i++) {
            CHECK(close_to(second[i], first[i], 1e-9), "point coordinate %zu: %g vs %g", i,
                  second[i], first[i]);
        }
        bzj_curve_free(r);
        r = NULL;
        /* The one-s automatic scale is not independent of P's speed. */
        EXPECT_STATUS(bzj_connect_auto_scale(slow, 40.0, q, 0.1, &options, &r, NULL), BZJ_OK);
        EXPECT_STATUS(bzj_curve_points(r, second, (count + 1) * 3), BZJ_OK);
        double moved = 0.0;
        for (size_t i = 0; i < (count + 1) * 3; i++) {
            moved = fmax(moved, fabs(second[i] - first[i]));
        }
        CHECK(moved > 1e-3, "the automatic scale moved R by only %g", moved);
        bzj_curve_free(r);
        r = NULL;
        bzj_curve_free(slow);
        EXPECT_STATUS(bzj_connect_balanced_scale(p, 0.5, q, 0.5, &options, NULL, NULL, NULL),
                      BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_connect_balanced_scale(p, 0.5, q, 1.5, &options, &r, NULL, NULL),
                      BZJ_ERR_INVALID_ARGUMENT);
        CHECK(strstr(bzj_last_error(), "v0") != NULL, "message: %s", bzj_last_error());
        CHECK(r == NULL, "out not cleared");
    }

    /* Error paths: each leaves *out NULL. */
    BzjCurve* sentinel = (BzjCurve*)&failures; /* non-NULL garbage to be cleared */
    r = sentinel;
    EXPECT_STATUS(bzj_connect(NULL, 0.5, q, 0.5, &options, &r), BZJ_ERR_NULL_POINTER);
    CHECK(r == NULL, "out not cleared");
    EXPECT_STATUS(bzj_connect(p, 0.5, NULL, 0.5, &options, &r), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, NULL, &r), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &options, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_connect_auto_scale(p, 0.5, q, 0.5, &options, NULL, NULL),
                  BZJ_ERR_NULL_POINTER);
    r = sentinel;
    EXPECT_STATUS(bzj_connect(p, 1.5, q, 0.5, &options, &r), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(r == NULL, "out not cleared");
    CHECK(strstr(bzj_last_error(), "u0") != NULL, "message does not name u0: %s",
          bzj_last_error());
    EXPECT_STATUS(bzj_connect(p, 0.5, q, -0.1, &options, &r), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "v0") != NULL, "message: %s", bzj_last_error());
    EXPECT_STATUS(bzj_connect(p, NAN, q, 0.5, &options, &r), BZJ_ERR_NON_FINITE);
    EXPECT_STATUS(bzj_connect_auto_scale(p, 2.0, q, 0.5, &options, &r, NULL),
                  BZJ_ERR_INVALID_ARGUMENT);
    EXPECT_STATUS(bzj_connect(p, 0.5, flat, 0.5, &paper, &r), BZJ_ERR_DIMENSION_MISMATCH);

    /* Orders above the degree are accepted (the contract: p_order, q_order
       may exceed the degree, Bezier curves included): a cubic's 4th
       derivative is 0, and R matches it. */
    BzjConnectOptions bad = options;
    bad.p_order = 4;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_OK);
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 4 + 3 + 1 + 2, "degree %zu, expected 10", degree);
    check_match(r, 0.0, p, 0.5, 3, 1.5, 3, "order 4 P end");
    {
        double rv[5 * 3];
        EXPECT_STATUS(bzj_curve_eval(r, 0.0, 4, rv, 15), BZJ_OK);
        for (int i = 12; i < 15; i++) {
            CHECK(close_to(rv[i], 0.0, 1e-8), "R''''(0)[%d] = %g, P'''' = 0", i - 12, rv[i]);
        }
    }
    bzj_curve_free(r);
    r = NULL;
    bad = options;
    bad.q_order = 9;
    EXPECT_STATUS(bzj_connect_auto_scale(p, 0.5, q, 0.5, &bad, &r, NULL), BZJ_OK);
    EXPECT_STATUS(bzj_curve_degree(r, &degree), BZJ_OK);
    CHECK(degree == 3 + 9 + 1 + 2, "degree %zu, expected 15", degree);
    bzj_curve_free(r);
    r = NULL;
    bad = options;
    bad.p_scale = 0.0;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_INVALID_ARGUMENT);
    bad.p_scale = INFINITY;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_NON_FINITE);
    /* The automatic scale ignores the given scales. */
    bad = options;
    bad.q_scale = -1.0;
    EXPECT_STATUS(bzj_connect_auto_scale(p, 0.5, q, 0.5, &bad, &r, NULL), BZJ_OK);
    bzj_curve_free(r);
    r = NULL;
    bad = options;
    bad.constraints = NULL;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_NULL_POINTER);

    BzjPointConstraint wrong = constraint;
    bad = options;
    bad.constraints = &wrong;
    wrong.t = 1.0;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "constraints[0].t") != NULL, "message: %s",
          bzj_last_error());
    wrong.t = NAN;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_NON_FINITE);
    wrong = constraint;
    wrong.values = NULL;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_NULL_POINTER);
    const double nan_values[] = {1.0, NAN, 0.0, 0.0, 0.0, 0.0};
    wrong = constraint;
    wrong.values = nan_values;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_NON_FINITE);
    wrong = constraint;
    wrong.max_order = (size_t)-1; /* absurd order: refused before reading values */
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_ILL_CONDITIONED);
    BzjPointConstraint twice[2] = {constraint, constraint};
    bad.constraints = twice;
    bad.constraint_count = 2;
    EXPECT_STATUS(bzj_connect(p, 0.5, q, 0.5, &bad, &r), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(strstr(bzj_last_error(), "constraints[1].t") != NULL, "message: %s",
          bzj_last_error());
    CHECK(r == NULL, "out not cleared after errors");

    /* An ill-posed problem far below the degree cap: two constraint points
     * 1e-4 apart whose positions differ by 2 with equal tangents. The
     * solve is done (degree 11) and refused by its own residual check, with
     * a finite estimate above the promised 1e-8 in the message. */
    {
        const double p2_points[] = {0, 0, 1, 2, 2, 2, 3, 0};
        const double q2_points[] = {6, 0, 7, -2, 8, -2, 9, 0};
        const double first[] = {4.5, 1.0, 1.0, 0.0};
        const double second[] = {4.5, -1.0, 1.0, 0.0};
        BzjCurve *p2 = NULL, *q2 = NULL;
        EXPECT_STATUS(bzj_curve_new(2, 3, p2_points, 8, &p2), BZJ_OK);
        EXPECT_STATUS(bzj_curve_new(2, 3, q2_points, 8, &q2), BZJ_OK);
        BzjPointConstraint crowded[2] = {{0.5, 1, first}, {0.5001, 1, second}};
        BzjConnectOptions ill = {3, 3, 1.0, 1.0, crowded, 2};
        r = sentinel;
        EXPECT_STATUS(bzj_connect(p2, 1.0, q2, 0.0, &ill, &r), BZJ_ERR_ILL_CONDITIONED);
        CHECK(r == NULL, "out not cleared");
        const char* message = bzj_last_error();
        CHECK(strncmp(message, "connect (degree 11): ", 21) == 0, "message: %s", message);
        const char* key = "estimated relative error ";
        const char* at = strstr(message, key);
        CHECK(at != NULL, "no estimate in: %s", message);
        if (at != NULL) {
            char* end = NULL;
            double estimate = strtod(at + strlen(key), &end);
            CHECK(end != at + strlen(key), "estimate not a number: %s", message);
            CHECK(isfinite(estimate) && estimate > 1e-8, "estimate %g in: %s", estimate,
                  message);
            CHECK(strstr(end, "exceeds the promised 1e-8") != NULL, "message: %s", message);
        }
        /* The same points 1e-2 apart are answered. */
        crowded[1].t = 0.51;
        EXPECT_STATUS(bzj_connect(p2, 1.0, q2, 0.0, &ill, &r), BZJ_OK);
        check_match(r, 0.0, p2, 1.0, 3, 1.0, 2, "relaxed P end");
        check_match(r, 1.0, q2, 0.0, 3, 1.0, 2, "relaxed Q end");
        bzj_curve_free(r);
        r = NULL;

        /* Degree 3 + 3 + 1 + 25 = 32: refused before solving; the message
         * names the degree, the estimate is inf (nothing was solved). */
        double many[25 * 2] = {0};
        BzjPointConstraint high = {0.5, 24, many};
        BzjConnectOptions over = {3, 3, 1.0, 1.0, &high, 1};
        r = sentinel;
        EXPECT_STATUS(bzj_connect(p2, 1.0, q2, 0.0, &over, &r), BZJ_ERR_ILL_CONDITIONED);
        CHECK(r == NULL, "out not cleared");
        message = bzj_last_error();
        CHECK(strstr(message, "result degree 32 is above the supported maximum 31") != NULL,
              "message: %s", message);
        CHECK(strstr(message, "estimated relative error inf") != NULL, "message: %s", message);
        high.max_order = 23; /* degree 31 exactly is solved */
        EXPECT_STATUS(bzj_connect(p2, 1.0, q2, 0.0, &over, &r), BZJ_OK);
        bzj_curve_free(r);
        r = NULL;
        bzj_curve_free(p2);
        bzj_curve_free(q2);
    }

    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(flat);
    if (failures != 0) {
        fprintf(stderr, "connect.c: %d failure(s)\n", failures);
        return 1;
    }
    printf("connect.c: ok\n");
    return 0;
}
