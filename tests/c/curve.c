/* Every curve function of the C contract, with each error path.
 * Compiled as C11 and as C++17 by tests/tests/c_programs.rs and linked with
 * libbezjoin.a. Exits 0 when every check passes. */
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

/* The message must be non-empty and mention `word`. */
static void expect_message(const char* word) {
    const char* m = bzj_last_error();
    CHECK(m != NULL && strstr(m, word) != NULL, "message '%s' does not name '%s'", m ? m : "(null)", word);
}

static double dist2(const double* a, const double* b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
}

/* Cubic B(t) by the closed form, for comparison. */
static void cubic_closed_form(const double* p, double t, double* out) {
    double s = 1.0 - t;
    double b[4];
    b[0] = s * s * s;
    b[1] = 3.0 * s * s * t;
    b[2] = 3.0 * s * t * t;
    b[3] = t * t * t;
    out[0] = out[1] = 0.0;
    for (int i = 0; i < 4; i++) {
        out[0] += b[i] * p[2 * i];
        out[1] += b[i] * p[2 * i + 1];
    }
}

int main(void) {
    const double pts[8] = {0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 4.0, 0.0};
    BzjCurve* c = NULL;
    BzjCurve* sentinel = (BzjCurve*)&failures; /* non-NULL garbage: must be cleared on error */
    size_t n = 0;

    /* version */
    CHECK(bzj_version() != NULL && strlen(bzj_version()) >= 5, "version '%s'", bzj_version());
    CHECK(strcmp(bzj_status_name(BZJ_ERR_SINGULAR), "BZJ_ERR_SINGULAR") == 0, "status name");
    CHECK(strcmp(bzj_status_name(12345), "BZJ_UNKNOWN_STATUS") == 0, "unknown status name");

    /* new: success and each error */
    EXPECT_STATUS(bzj_curve_new(2, 3, pts, 8, &c), BZJ_OK);
    CHECK(c != NULL, "curve created");
    CHECK(strcmp(bzj_last_error(), "") == 0, "last error empty after success");
    BzjCurve* bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(2, 3, NULL, 8, &bad), BZJ_ERR_NULL_POINTER);
    CHECK(bad == NULL, "out cleared on null points");
    expect_message("points");
    EXPECT_STATUS(bzj_curve_new(2, 3, pts, 8, NULL), BZJ_ERR_NULL_POINTER);
    expect_message("out");
    bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(2, 3, pts, 7, &bad), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(bad == NULL, "out cleared on bad length");
    expect_message("points");
    EXPECT_STATUS(bzj_curve_new(0, 3, pts, 0, &bad), BZJ_ERR_INVALID_ARGUMENT);
    expect_message("dim");
    {
        double nan_pts[4] = {0.0, 1.0, NAN, 2.0};
        EXPECT_STATUS(bzj_curve_new(2, 1, nan_pts, 4, &bad), BZJ_ERR_NON_FINITE);
        expect_message("points[2]");
        CHECK(bad == NULL, "out cleared on NaN");
    }
    /* Degree above the maximum (MAX_DEGREE = 4096 in crates/bezjoin/src/bezier.rs),
       with a points array of exactly the right length: refused for the
       degree alone. The maximum itself is accepted. */
    {
        enum { MAX_DEGREE = 4096 };
        static double zeros[MAX_DEGREE + 2]; /* zero-initialised */
        bad = sentinel;
        EXPECT_STATUS(bzj_curve_new(1, MAX_DEGREE + 1, zeros, MAX_DEGREE + 2, &bad),
                      BZJ_ERR_INVALID_ARGUMENT);
        CHECK(bad == NULL, "out cleared on a degree above the maximum");
        expect_message("degree");
        expect_message("4097");
        BzjCurve* top = NULL;
        EXPECT_STATUS(bzj_curve_new(1, MAX_DEGREE, zeros, MAX_DEGREE + 1, &top), BZJ_OK);
        CHECK(top != NULL, "the maximum degree is accepted");
        bzj_curve_free(top);
    }
    /* (degree + 1) * dim overflows size_t: refused from the numbers alone,
       before points is read (it holds only 8 doubles). */
    bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(2, SIZE_MAX, pts, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(bad == NULL, "out cleared when degree + 1 overflows");
    expect_message("degree");
    expect_message("overflows");
    bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(SIZE_MAX, 3, pts, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(bad == NULL, "out cleared when (degree + 1) * dim overflows");
    expect_message("dim");
    expect_message("overflows");
    bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(SIZE_MAX / 2 + 1, 1, pts, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(bad == NULL, "out cleared when 2 * dim overflows");
    bad = sentinel;
    EXPECT_STATUS(bzj_curve_new(SIZE_MAX, SIZE_MAX, pts, 8, &bad), BZJ_ERR_INVALID_ARGUMENT);
    CHECK(bad == NULL, "out cleared when both are SIZE_MAX");

    /* degree, dim, points */
    EXPECT_STATUS(bzj_curve_degree(c, &n), BZJ_OK);
    CHECK(n == 3, "degree %zu", n);
    EXPECT_STATUS(bzj_curve_dim(c, &n), BZJ_OK);
    CHECK(n == 2, "dim %zu", n);
    EXPECT_STATUS(bzj_curve_degree(NULL, &n), BZJ_ERR_NULL_POINTER);
    expect_message("c");
    EXPECT_STATUS(bzj_curve_degree(c, NULL), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_dim(NULL, &n), BZJ_ERR_NULL_POINTER);
    EXPECT_STATUS(bzj_curve_dim(c, NULL), BZJ_ERR_NULL_POINTER);
    {
        double back[8];
        double small[7] = {-1, -1, -1, -1, -1, -1, -1};
        EXPECT_STATUS(bzj_curve_points(c, back, 8), BZJ_OK);
        CHECK(memcmp(back, pts, sizeof pts) == 0, "points round trip exactly");
        EXPECT_STATUS(bzj_curve_points(c, small, 7), BZJ_ERR_BUFFER_TOO_SMALL);
        CHECK(small[0] == -1.0 && small[6] == -1.0, "nothing written to a short buffer");
        expect_message("out");
        EXPECT_STATUS(bzj_curve_points(c, NULL, 8), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_points(NULL, back, 8), BZJ_ERR_NULL_POINTER);
    }

    /* eval against the closed form; derivative 1 at 0 is 3 (P1 - P0) */
    {
        double v[8], ref[2];
        for (int i = 0; i <= 10; i++) {
            double t = i / 10.0;
            EXPECT_STATUS(bzj_curve_eval(c, t, 0, v, 2), BZJ_OK);
            cubic_closed_form(pts, t, ref);
            CHECK(dist2(v, ref) < 1e-14, "eval at %g", t);
        }
        EXPECT_STATUS(bzj_curve_eval(c, 0.0, 3, v, 8), BZJ_OK);
        CHECK(fabs(v[2] - 3.0) < 1e-14 && fabs(v[3] - 6.0) < 1e-14, "first derivative at 0");
        CHECK(fabs(v[6] - 6.0 * (4.0 - 3 * 3.0 + 3 * 1.0 - 0.0)) < 1e-12, "third derivative x");
        EXPECT_STATUS(bzj_curve_eval(c, 0.5, 3, v, 7), BZJ_ERR_BUFFER_TOO_SMALL);
        expect_message("out");
        {
            /* Nothing is written to a buffer that is too short. */
            double shortbuf[7];
            for (int i = 0; i < 7; i++) shortbuf[i] = -7.25;
            EXPECT_STATUS(bzj_curve_eval(c, 0.5, 3, shortbuf, 7), BZJ_ERR_BUFFER_TOO_SMALL);
            EXPECT_STATUS(bzj_curve_eval(c, 0.5, 0, shortbuf, 1), BZJ_ERR_BUFFER_TOO_SMALL);
            int untouched = 1;
            for (int i = 0; i < 7; i++) untouched = untouched && shortbuf[i] == -7.25;
            CHECK(untouched, "eval wrote into a too-short buffer");
        }
        EXPECT_STATUS(bzj_curve_eval(c, NAN, 0, v, 2), BZJ_ERR_NON_FINITE);
        expect_message("t");
        EXPECT_STATUS(bzj_curve_eval(c, 0.5, 0, NULL, 2), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_eval(NULL, 0.5, 0, v, 2), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_eval(c, 0.5, (size_t)-1, v, 8), BZJ_ERR_INVALID_ARGUMENT);
    }

    /* eval_many: block i is exactly what eval writes at ts[i], parameter-major */
    {
        const double ts[5] = {-0.25, 0.0, 0.3, 1.0, 1.75};
        double many[5 * 3 * 2], one[3 * 2];
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 5, 2, many, 30), BZJ_OK);
        for (int i = 0; i < 5; i++) {
            EXPECT_STATUS(bzj_curve_eval(c, ts[i], 2, one, 6), BZJ_OK);
            for (int k = 0; k < 6; k++) CHECK(many[i * 6 + k] == one[k], "eval_many block %d entry %d", i, k);
        }
        double values[5 * 2];
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 5, 0, values, 10), BZJ_OK);
        for (int i = 0; i < 5; i++) {
            EXPECT_STATUS(bzj_curve_eval(c, ts[i], 0, one, 2), BZJ_OK);
            CHECK(values[2 * i] == one[0] && values[2 * i + 1] == one[1], "eval_many value %d", i);
        }
        /* every parameter is checked before anything is written */
        const double bad[3] = {0.1, 0.2, INFINITY};
        for (int k = 0; k < 30; k++) many[k] = -7.25;
        EXPECT_STATUS(bzj_curve_eval_many(c, bad, 3, 2, many, 30), BZJ_ERR_NON_FINITE);
        expect_message("ts[2]");
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 5, 2, many, 29), BZJ_ERR_BUFFER_TOO_SMALL);
        expect_message("out");
        int untouched = 1;
        for (int k = 0; k < 30; k++) untouched = untouched && many[k] == -7.25;
        CHECK(untouched, "eval_many wrote after a failure");
        EXPECT_STATUS(bzj_curve_eval_many(c, NULL, 0, 3, NULL, 0), BZJ_OK);
        EXPECT_STATUS(bzj_curve_eval_many(c, NULL, 2, 0, values, 10), BZJ_ERR_NULL_POINTER);
        expect_message("ts");
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 2, 0, NULL, 10), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_eval_many(NULL, ts, 2, 0, values, 10), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, (size_t)1 << 62, 3, values, 10), BZJ_ERR_INVALID_ARGUMENT);
        EXPECT_STATUS(bzj_curve_eval_many(c, ts, 2, (size_t)-1, values, 10), BZJ_ERR_INVALID_ARGUMENT);
    }

    /* eval outside [0, 1] continues the polynomial: at t = a and t = b it
       equals the extrapolated segment s -> c(a + (b - a) s) at s = 0 and
       s = 1 (computed by blossoming, a different route), and the k-th
       derivatives satisfy seg^(k)(s) = (b - a)^k c^(k)(a + (b - a) s).
       Orders above the degree are zero. */
    {
        const double a = -0.5, b = 1.5;
        BzjCurve* seg = NULL;
        EXPECT_STATUS(bzj_curve_segment(c, a, b, &seg), BZJ_OK);
        for (int end = 0; end <= 1; end++) {
            double t = end ? b : a;
            double direct[12], via[12];
            EXPECT_STATUS(bzj_curve_eval(c, t, 5, direct, 12), BZJ_OK);
            EXPECT_STATUS(bzj_curve_eval(seg, (double)end, 5, via, 12), BZJ_OK);
            double factor = 1.0;
            for (int k = 0; k <= 5; k++) {
                double want[2] = {factor * direct[2 * k], factor * direct[2 * k + 1]};
                double size = sqrt(want[0] * want[0] + want[1] * want[1]);
                CHECK(dist2(&via[2 * k], want) <= 1e-12 * (size > 1.0 ? size : 1.0),
                      "t = %g, order %d: segment gives (%.17g, %.17g), eval (%.17g, %.17g)", t, k,
                      via[2 * k], via[2 * k + 1], want[0], want[1]);
                if (k > 3) {
                    CHECK(direct[2 * k] == 0.0 && direct[2 * k + 1] == 0.0,
                          "order %d above the degree is not zero at t = %g", k, t);
                }
                factor *= b - a;
            }
        }
        bzj_curve_free(seg);
    }

    /* elevate: same values */
    {
        BzjCurve* e = NULL;
        double a[2], b[2];
        EXPECT_STATUS(bzj_curve_elevate(c, 9, &e), BZJ_OK);
        EXPECT_STATUS(bzj_curve_degree(e, &n), BZJ_OK);
        CHECK(n == 9, "elevated degree %zu", n);
        for (int i = 0; i <= 20; i++) {
            double t = i / 20.0;
            bzj_curve_eval(c, t, 0, a, 2);
            bzj_curve_eval(e, t, 0, b, 2);
            CHECK(dist2(a, b) < 1e-13, "elevated curve differs at %g", t);
        }
        bzj_curve_free(e);
        e = sentinel;
        EXPECT_STATUS(bzj_curve_elevate(c, 2, &e), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(e == NULL, "out cleared");
        expect_message("new_degree");
        EXPECT_STATUS(bzj_curve_elevate(NULL, 5, &e), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_elevate(c, 5, NULL), BZJ_ERR_NULL_POINTER);
    }

    /* split: the pieces reproduce the curve */
    {
        BzjCurve *l = NULL, *r = NULL;
        double a[2], b[2];
        EXPECT_STATUS(bzj_curve_split(c, 0.3, &l, &r), BZJ_OK);
        for (int i = 0; i <= 10; i++) {
            double s = i / 10.0;
            bzj_curve_eval(l, s, 0, a, 2);
            bzj_curve_eval(c, 0.3 * s, 0, b, 2);
            CHECK(dist2(a, b) < 1e-14, "left piece at %g", s);
            bzj_curve_eval(r, s, 0, a, 2);
            bzj_curve_eval(c, 0.3 + 0.7 * s, 0, b, 2);
            CHECK(dist2(a, b) < 1e-14, "right piece at %g", s);
        }
        bzj_curve_free(l);
        bzj_curve_free(r);
        l = sentinel;
        r = sentinel;
        EXPECT_STATUS(bzj_curve_split(c, 1.5, &l, &r), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(l == NULL && r == NULL, "outs cleared");
        expect_message("t = 1.5 is outside [0, 1]");
        EXPECT_STATUS(bzj_curve_split(c, INFINITY, &l, &r), BZJ_ERR_NON_FINITE);
        EXPECT_STATUS(bzj_curve_split(c, 0.5, NULL, &r), BZJ_ERR_NULL_POINTER);
        CHECK(r == NULL, "right cleared when left is NULL");
        EXPECT_STATUS(bzj_curve_split(c, 0.5, &l, NULL), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_split(NULL, 0.5, &l, &r), BZJ_ERR_NULL_POINTER);
    }

    /* segment with extrapolation */
    {
        BzjCurve* s = NULL;
        double a[2], b[2];
        EXPECT_STATUS(bzj_curve_segment(c, -0.5, 1.75, &s), BZJ_OK);
        for (int i = 0; i <= 10; i++) {
            double u = i / 10.0;
            bzj_curve_eval(s, u, 0, a, 2);
            bzj_curve_eval(c, -0.5 + 2.25 * u, 0, b, 2);
            CHECK(dist2(a, b) < 1e-12, "segment at %g", u);
        }
        bzj_curve_free(s);
        s = sentinel;
        EXPECT_STATUS(bzj_curve_segment(c, NAN, 1.0, &s), BZJ_ERR_NON_FINITE);
        CHECK(s == NULL, "out cleared");
        expect_message("a");
        EXPECT_STATUS(bzj_curve_segment(c, 0.0, INFINITY, &s), BZJ_ERR_NON_FINITE);
        EXPECT_STATUS(bzj_curve_segment(NULL, 0.0, 1.0, &s), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_segment(c, 0.0, 1.0, NULL), BZJ_ERR_NULL_POINTER);
    }

    /* reverse */
    {
        BzjCurve* r = NULL;
        double a[2], b[2];
        EXPECT_STATUS(bzj_curve_reverse(c, &r), BZJ_OK);
        for (int i = 0; i <= 10; i++) {
            double u = i / 10.0;
            bzj_curve_eval(r, u, 0, a, 2);
            bzj_curve_eval(c, 1.0 - u, 0, b, 2);
            CHECK(dist2(a, b) < 1e-14, "reverse at %g", u);
        }
        bzj_curve_free(r);
        EXPECT_STATUS(bzj_curve_reverse(NULL, &r), BZJ_ERR_NULL_POINTER);
        EXPECT_STATUS(bzj_curve_reverse(c, NULL), BZJ_ERR_NULL_POINTER);
    }

    /* length: a straight line of length 5 traversed non-uniformly */
    {
        const double line[6] = {1.0, 2.0, 1.3, 2.4, 4.0, 6.0};
        BzjCurve* l = NULL;
        double len = 0.0;
        EXPECT_STATUS(bzj_curve_new(2, 2, line, 6, &l), BZJ_OK);
        EXPECT_STATUS(bzj_curve_length(l, 0.0, 1.0, &len), BZJ_OK);
        CHECK(fabs(len - 5.0) < 1e-12, "line length %.17g", len);
        EXPECT_STATUS(bzj_curve_length(l, 1.0, 0.0, &len), BZJ_OK);
        CHECK(fabs(len + 5.0) < 1e-12, "reversed length %.17g", len);
        EXPECT_STATUS(bzj_curve_length(l, 0.0, NAN, &len), BZJ_ERR_NON_FINITE);
        expect_message("b = NaN");
        /* On every error `out` is left as it was. */
        len = 42.5;
        EXPECT_STATUS(bzj_curve_length(l, NAN, 1.0, &len), BZJ_ERR_NON_FINITE);
        CHECK(strcmp(bzj_last_error(), "a = NaN is not finite") == 0, "message '%s'", bzj_last_error());
        CHECK(len == 42.5, "out written on NaN a: %.17g", len);
        EXPECT_STATUS(bzj_curve_length(l, -INFINITY, 1.0, &len), BZJ_ERR_NON_FINITE);
        expect_message("a = -inf");
        CHECK(len == 42.5, "out written on infinite a: %.17g", len);
        /* A range so long that the length overflows the double range
           (|c(t)| ~ t^3 for the cubic, t^2 for this non-uniform line):
           BZJ_ERR_INVALID_ARGUMENT naming a and b, as documented. */
        EXPECT_STATUS(bzj_curve_length(c, -1e200, 1e200, &len), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("a, b");
        expect_message("overflows");
        CHECK(len == 42.5, "out written on an overflowing length: %.17g", len);
        EXPECT_STATUS(bzj_curve_length(l, 1e200, -1e200, &len), BZJ_ERR_INVALID_ARGUMENT);
        expect_message("overflows");
        CHECK(len == 42.5, "out written on an overflowing reversed length: %.17g", len);
        {
            /* Finite control points more than DBL_MAX apart: the default
               accuracy (relative to the control polygon's length) is
               infinite; the caller passed no accuracy, so the message names
               the polygon length (reliability F3), not `accuracy`. */
            const double far[3] = {0.0, DBL_MAX, -DBL_MAX};
            BzjCurve* wide = NULL;
            EXPECT_STATUS(bzj_curve_new(1, 2, far, 3, &wide), BZJ_OK);
            EXPECT_STATUS(bzj_curve_length(wide, 0.0, 1.0, &len), BZJ_ERR_NON_FINITE);
            CHECK(strcmp(bzj_last_error(), "the control polygon length of the curve = inf is not finite") == 0,
                  "message '%s'", bzj_last_error());
            CHECK(len == 42.5, "out written on an overflowing polygon: %.17g", len);
            bzj_curve_free(wide);
        }
        EXPECT_STATUS(bzj_curve_length(l, 0.0, 1.0, NULL), BZJ_ERR_NULL_POINTER);
        expect_message("out");
        EXPECT_STATUS(bzj_curve_length(NULL, 0.0, 1.0, &len), BZJ_ERR_NULL_POINTER);
        expect_message("c");
        CHECK(len == 42.5, "out written on a NULL curve: %.17g", len);
        /* Long but representable: a finite value (rounding-level accuracy). */
        EXPECT_STATUS(bzj_curve_length(c, -1e4, 1e4, &len), BZJ_OK);
        CHECK(isfinite(len) && len > 0.0, "long extrapolated length %.17g", len);
        bzj_curve_free(l);
    }

    /* review findings: impossible sizes are errors (never a panic, never
       BZJ_ERR_INTERNAL), scalar messages carry no index, and releasing a
       handle keeps the thread's last error. */
    {
        BzjCurve* e = (BzjCurve*)&failures; /* garbage on purpose: must be cleared */
        EXPECT_STATUS(bzj_curve_elevate(c, SIZE_MAX, &e), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(e == NULL, "out cleared on impossible new_degree");
        expect_message("new_degree");
        double v[2];
        EXPECT_STATUS(bzj_curve_eval(c, NAN, 0, v, 2), BZJ_ERR_NON_FINITE);
        CHECK(strcmp(bzj_last_error(), "t = NaN is not finite") == 0, "message '%s'", bzj_last_error());
        BzjCurve* tmp = NULL;
        EXPECT_STATUS(bzj_curve_reverse(c, &tmp), BZJ_OK);
        EXPECT_STATUS(bzj_curve_split(c, 2.0, &e, &e), BZJ_ERR_INVALID_ARGUMENT);
        bzj_curve_free(tmp);
        expect_message("t = 2");
        BzjCurve* far = NULL;
        EXPECT_STATUS(bzj_curve_segment(c, 0.0, 1e120, &far), BZJ_ERR_INVALID_ARGUMENT);
        CHECK(far == NULL, "no curve with infinite control points");
        expect_message("overflow");
    }

    /* free accepts NULL */
    bzj_curve_free(NULL);
    bzj_curve_free(c);

    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("curve.c: all checks passed\n");
    return 0;
}
