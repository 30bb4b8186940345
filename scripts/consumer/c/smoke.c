/*
 * C consumer of an installed bezjoin, built with
 *   cc smoke.c $(pkg-config --cflags --libs bezjoin)
 * Checks real values against hand computation:
 *   cubic P0=(0,0) P1=(1,2) P2=(3,3) P3=(4,0) at t = 1/2:
 *     P(1/2)  = (P0 + 3 P1 + 3 P2 + P3) / 8            = (2, 15/8)
 *     P'(1/2) = 3/4 ((P1-P0) + 2 (P2-P1) + (P3-P2))    = (9/2, 3/4)
 *     P''(1/2)= 3 ((P2 - 2 P1 + P0) + (P3 - 2 P2 + P1)) = 3 ((1,-1) + (-1,-4)) = (0, -15)
 *   segment (0,0)-(3,4) has length 5;
 *   splitting at 1/2 gives a left piece ending at P(1/2);
 *   a NaN coordinate is refused with BZJ_ERR_NON_FINITE and a message.
 * Every handle is freed (run under valgrind in CI).
 */
#include <bezjoin.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

static void check_close(const char *what, double got, double want) {
    if (!(fabs(got - want) <= 1e-14 * (1.0 + fabs(want)))) {
        fprintf(stderr, "FAIL %s: got %.17g, want %.17g\n", what, got, want);
        failures++;
    }
}

static void check_status(const char *what, BzjStatus got, BzjStatus want) {
    if (got != want) {
        fprintf(stderr, "FAIL %s: status %s, want %s (%s)\n", what, bzj_status_name(got),
                bzj_status_name(want), bzj_last_error());
        failures++;
    }
}

int main(void) {
    char expected_version[64];
    snprintf(expected_version, sizeof expected_version, "%d.%d.%d", BZJ_VERSION_MAJOR,
             BZJ_VERSION_MINOR, BZJ_VERSION_PATCH);
    if (strcmp(bzj_version(), expected_version) != 0) {
        fprintf(stderr, "FAIL version: library %s, header %s\n", bzj_version(), expected_version);
        failures++;
    }

    const double cubic[] = {0, 0, 1, 2, 3, 3, 4, 0};
    BzjCurve *c = NULL;
    check_status("curve_new", bzj_curve_new(2, 3, cubic, 8, &c), BZJ_OK);
    if (c == NULL) {
        fprintf(stderr, "FAIL curve_new returned no handle\n");
        return 1;
    }

    double d[6];
    check_status("eval", bzj_curve_eval(c, 0.5, 2, d, 6), BZJ_OK);
    check_close("P(1/2).x", d[0], 2.0);
    check_close("P(1/2).y", d[1], 15.0 / 8.0);
    check_close("P'(1/2).x", d[2], 4.5);
    check_close("P'(1/2).y", d[3], 0.75);
    check_close("P''(1/2).x", d[4], 0.0);
    check_close("P''(1/2).y", d[5], -15.0);

    check_status("eval short buffer", bzj_curve_eval(c, 0.5, 2, d, 5), BZJ_ERR_BUFFER_TOO_SMALL);

    BzjCurve *left = NULL, *right = NULL;
    check_status("split", bzj_curve_split(c, 0.5, &left, &right), BZJ_OK);
    double lp[8];
    check_status("points", bzj_curve_points(left, lp, 8), BZJ_OK);
    check_close("left end.x", lp[6], 2.0);
    check_close("left end.y", lp[7], 15.0 / 8.0);
    bzj_curve_free(left);
    bzj_curve_free(right);

    const double line[] = {0, 0, 3, 4};
    BzjCurve *l = NULL;
    check_status("line", bzj_curve_new(2, 1, line, 4, &l), BZJ_OK);
    double len = 0;
    check_status("length", bzj_curve_length(l, 0.0, 1.0, &len), BZJ_OK);
    check_close("length", len, 5.0);
    bzj_curve_free(l);

    double bad[8];
    memcpy(bad, cubic, sizeof bad);
    bad[5] = NAN;
    BzjCurve *b = (BzjCurve *)&failures; /* must be overwritten with NULL */
    check_status("NaN input", bzj_curve_new(2, 3, bad, 8, &b), BZJ_ERR_NON_FINITE);
    if (b != NULL) {
        fprintf(stderr, "FAIL: handle not cleared on error\n");
        failures++;
    }
    if (strlen(bzj_last_error()) == 0 || strstr(bzj_last_error(), "points") == NULL) {
        fprintf(stderr, "FAIL: last error does not name the argument: '%s'\n", bzj_last_error());
        failures++;
    }
    check_status("null out", bzj_curve_new(2, 3, cubic, 8, NULL), BZJ_ERR_NULL_POINTER);

    bzj_curve_free(c);
    bzj_curve_free(NULL);

    if (failures != 0) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C consumer: bezjoin %s OK\n", bzj_version());
    return 0;
}
