/* Open finding (fuzz target curve_ops): bzj_curve_length does not return
 * (minutes) for an ordinary degree-22 planar curve on an extrapolated range.
 * Build: cc length_hang.c $(pkg-config --cflags --libs bezjoin) -o length_hang
 * Stack: arclength.rs Speed::adaptive recursing towards MAX_DEPTH = 40 on
 * both halves (up to 2^40 Gauss-Legendre panels). */
#include <bezjoin.h>
#include <stdio.h>

int main(void) {
    double p[46] = {75.341796875, -55.3375244140625, 77.6519775390625, 7.659912109375,
                    -63.00048828125, 64.764404296875, 33.880615234375, 20.4742431640625,
                    70.770263671875, -68.194580078125, -31.1187744140625, 76.62353515625,
                    42.96875, 0, 0, 0, 2.2250738585072014e-308, 57.769775390625,
                    62.152099609375, -49.542236328125, 40.9454345703125};
    for (int i = 21; i < 46; ++i) p[i] = -17.6483154296875;
    BzjCurve *c = NULL;
    double length = 0;
    if (bzj_curve_new(2, 22, p, 46, &c) != BZJ_OK) return 2;
    BzjStatus s = bzj_curve_length(c, -0.33865110246433205, 0.95217059586480501, &length);
    printf("%s %.17g %s\n", bzj_status_name(s), length, bzj_last_error());
    bzj_curve_free(c);
    return 0;
}
