/* bzj_connect_points and bzj_connect_points_auto_scale through the C ABI:
 * the control points are those of bzj_curve_new + bzj_connect
 * (bzj_connect_auto_scale) + bzj_curve_points, bit for bit; the ends match
 * P's and Q's scaled derivatives (bzj_curve_eval on both sides); every error
 * path (null pointers, dim 0, lengths that are no multiple of dim, a short
 * output buffer, parameters outside [0, 1], a bad or non-finite scale, a
 * degree above 31) leaves the output untouched.
 * Returns 0 on success, 1 with a message on the first failure. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bezjoin.h"

static int failures = 0;

#define CHECK(cond, ...)                                         \
    do {                                                         \
        if (!(cond)) {                                           \
            fprintf(stderr, "connect_points.c:%d: ", __LINE__);  \
            fprintf(stderr, __VA_ARGS__);                        \
            fprintf(stderr, "\n");                               \
            failures++;                                          \
        }                                                        \
    } while (0)

#define EXPECT_STATUS(call, expected)                                          \
    do {                                                                       \
        BzjStatus s_ = (call);                                                 \
        CHECK(s_ == (expected), "%s gave %s (%s), expected %s", #call,         \
              bzj_status_name(s_), bzj_last_error(), bzj_status_name(expected)); \
    } while (0)

static const double P[] = {0, 0, 0, 1, 2, 1, 2, 2, 0, 3, 0, 1};
static const double Q[] = {6, 0, 0, 7, -2, 1, 9, 0, 2};
#define OUT_LEN ((3 + 2 + 2) * 3)

/* The points of R through handles: bzj_connect (auto: bzj_connect_auto_scale). */
static void through_handles(int automatic, double scale, double* points, double* scale_out) {
    BzjCurve *p = NULL, *q = NULL, *r = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 3, P, 12, &p), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(3, 2, Q, 9, &q), BZJ_OK);
    BzjConnectOptions options = {3, 2, scale, scale, NULL, 0};
    if (automatic) {
        EXPECT_STATUS(bzj_connect_auto_scale(p, 0.8, q, 0.1, &options, &r, scale_out), BZJ_OK);
    } else {
        EXPECT_STATUS(bzj_connect(p, 0.8, q, 0.1, &options, &r), BZJ_OK);
    }
    EXPECT_STATUS(bzj_curve_points(r, points, OUT_LEN), BZJ_OK);
    bzj_curve_free(p);
    bzj_curve_free(q);
    bzj_curve_free(r);
}

/* R^(k)(tr) == s^k C^(k)(tc), k = 0..order, R given by its points. */
static void check_end(const double* r_points, double tr, const double* c_points, size_t c_degree,
                      double tc, size_t order, double s, const char* what) {
    BzjCurve *r = NULL, *c = NULL;
    EXPECT_STATUS(bzj_curve_new(3, 6, r_points, OUT_LEN, &r), BZJ_OK);
    EXPECT_STATUS(bzj_curve_new(3, c_degree, c_points, (c_degree + 1) * 3, &c), BZJ_OK);
    double rv[4 * 3], cv[4 * 3];
    EXPECT_STATUS(bzj_curve_eval(r, tr, order, rv, (order + 1) * 3), BZJ_OK);
    EXPECT_STATUS(bzj_curve_eval(c, tc, order, cv, (order + 1) * 3), BZJ_OK);
    double power = 1.0;
    for (size_t k = 0; k <= order; k++) {
        for (size_t i = 0; i < 3; i++) {
            double want = power * cv[k * 3 + i];
            double size = fabs(want) > 1.0 ? fabs(want) : 1.0;
            CHECK(fabs(rv[k * 3 + i] - want) <= 1e-9 * size, "%s: order %zu coord %zu: %g vs %g",
                  what, k, i, rv[k * 3 + i], want);
        }
        power *= s;
    }
    bzj_curve_free(r);
    bzj_curve_free(c);
}

static int untouched(const double* out) {
    for (int i = 0; i < OUT_LEN; i++) {
        if (out[i] != 7.0) return 0;
    }
    return 1;
}

/* One failing call of bzj_connect_points: the status, the argument named, the output kept. */
static void expect_error(BzjStatus status, BzjStatus expected, const char* name,
                         const double* out, int line) {
    if (status != expected || strstr(bzj_last_error(), name) == NULL || !untouched(out)) {
        fprintf(stderr, "connect_points.c:%d: gave %s (%s), expected %s naming %s%s\n", line,
                bzj_status_name(status), bzj_last_error(), bzj_status_name(expected), name,
                untouched(out) ? "" : "; the output was written");
        failures++;
    }
}

#define EXPECT_ERROR(call, expected, name) expect_error((call), (expected), (name), out, __LINE__)

int main(void) {
    double out[OUT_LEN], want[OUT_LEN];
    double scale = 0.0, want_scale = -1.0;

    /* Given scales: the same points as through handles, the ends matched. */
    EXPECT_STATUS(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, 1.25, 1.25, out, OUT_LEN),
                  BZJ_OK);
    through_handles(0, 1.25, want, NULL);
    CHECK(memcmp(out, want, sizeof out) == 0, "given scale: points differ from bzj_connect's");
    check_end(out, 0.0, P, 3, 0.8, 3, 1.25, "P end");
    check_end(out, 1.0, Q, 2, 0.1, 2, 1.25, "Q end");

    /* A larger buffer: only (p_order + q_order + 2) * dim doubles are written. */
    double big[OUT_LEN + 3];
    for (int i = 0; i < OUT_LEN + 3; i++) big[i] = 7.0;
    EXPECT_STATUS(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, 1.25, 1.25, big, OUT_LEN + 3),
                  BZJ_OK);
    CHECK(memcmp(big, want, sizeof want) == 0 && big[OUT_LEN] == 7.0 && big[OUT_LEN + 2] == 7.0,
          "larger buffer: wrong points or written past the result");

    /* Automatic scale: the points and the scale of bzj_connect_auto_scale. */
    EXPECT_STATUS(bzj_connect_points_auto_scale(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, out, OUT_LEN,
                                                &scale),
                  BZJ_OK);
    through_handles(1, 1.0, want, &want_scale);
    CHECK(memcmp(out, want, sizeof out) == 0, "auto scale: points differ from the handles'");
    CHECK(memcmp(&scale, &want_scale, sizeof scale) == 0, "auto scale %g vs %g", scale,
          want_scale);
    check_end(out, 0.0, P, 3, 0.8, 3, scale, "P end (auto)");
    check_end(out, 1.0, Q, 2, 0.1, 2, scale, "Q end (auto)");
    /* scale_out may be NULL. */
    EXPECT_STATUS(bzj_connect_points_auto_scale(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, out, OUT_LEN,
                                                NULL),
                  BZJ_OK);
    CHECK(memcmp(out, want, sizeof out) == 0, "auto scale without scale_out: points differ");

    /* Errors: status, the argument named, nothing written. */
    for (int i = 0; i < OUT_LEN; i++) out[i] = 7.0;
    EXPECT_ERROR(bzj_connect_points(3, NULL, 12, 0.8, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_NULL_POINTER, "p_points");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, NULL, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_NULL_POINTER, "q_points");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, 1, 1, NULL, OUT_LEN),
                 BZJ_ERR_NULL_POINTER, "out_points");
    EXPECT_ERROR(bzj_connect_points(0, P, 12, 0.8, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "dim");
    EXPECT_ERROR(bzj_connect_points(3, P, 11, 0.8, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "p_len");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 0, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "q_len");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN - 1),
                 BZJ_ERR_BUFFER_TOO_SMALL, "out_points");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 1.5, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "u0");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, -0.5, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "v0");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, 0.0, 1, out, OUT_LEN),
                 BZJ_ERR_INVALID_ARGUMENT, "scale");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, NAN, 1, out, OUT_LEN),
                 BZJ_ERR_NON_FINITE, "scale");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, NAN, Q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_NON_FINITE, "u0");
    const double bad_q[] = {6, 0, 0, 7, INFINITY, 1, 9, 0, 2};
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, bad_q, 9, 0.1, 3, 2, 1, 1, out, OUT_LEN),
                 BZJ_ERR_NON_FINITE, "q_points[4]");
    EXPECT_ERROR(bzj_connect_points(3, P, 12, 0.8, Q, 9, 0.1, 20, 20, 1, 1, out, OUT_LEN),
                 BZJ_ERR_ILL_CONDITIONED, "degree 41");
    scale = 5.0;
    EXPECT_ERROR(bzj_connect_points_auto_scale(3, NULL, 12, 0.8, Q, 9, 0.1, 3, 2, out, OUT_LEN,
                                               &scale),
                 BZJ_ERR_NULL_POINTER, "p_points");
    EXPECT_ERROR(bzj_connect_points_auto_scale(3, P, 12, 0.8, Q, 9, 0.1, 3, 2, out, 3, &scale),
                 BZJ_ERR_BUFFER_TOO_SMALL, "out_points");
    EXPECT_ERROR(bzj_connect_points_auto_scale(3, P, 12, 0.8, Q, 9, 2.0, 3, 2, out, OUT_LEN,
                                               &scale),
                 BZJ_ERR_INVALID_ARGUMENT, "v0");
    CHECK(scale == 5.0, "scale_out written on an error: %g", scale);

    if (failures) {
        fprintf(stderr, "connect_points.c: %d failure(s)\n", failures);
        return 1;
    }
    printf("connect_points.c: ok\n");
    return 0;
}
