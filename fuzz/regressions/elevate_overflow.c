/* Open finding F1 (docs/reliability.md): bzj_curve_elevate with a huge new degree.
 * Build: cc elevate_overflow.c $(pkg-config --cflags --libs bezjoin) -o elevate_overflow
 * ./elevate_overflow 18446744073709551615   -> BZJ_ERR_INTERNAL (index out of bounds)
 * ./elevate_overflow 18446744073709551614   -> BZJ_ERR_INTERNAL (capacity overflow)
 * ./elevate_overflow 0x100000000000          -> the process aborts (allocation failure) */
#include <bezjoin.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
int main(int argc, char** argv) {
    double p[2] = {0, 1};
    BzjCurve *c = NULL, *o = NULL;
    bzj_curve_new(1, 1, p, 2, &c);
    size_t nd = (size_t)strtoull(argv[1], NULL, 0);
    BzjStatus s = bzj_curve_elevate(c, nd, &o);
    printf("new_degree=%zu status=%s msg=%s\n", nd, bzj_status_name(s), bzj_last_error());
    return 0;
}
