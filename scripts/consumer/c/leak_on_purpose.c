/*
 * Self-test of the memcheck step in scripts/ci-embedding.sh: this program
 * leaks one bezjoin curve handle on purpose and exits 0. Run under the same
 * valgrind flags as the C programs of tests/c/, it must make valgrind fail
 * (the leak check is not blind) with bzj_curve_new on the allocation stack.
 * Built like smoke.c:  cc leak_on_purpose.c $(pkg-config --cflags --libs bezjoin)
 */
#include <bezjoin.h>

#include <stdio.h>

int main(void) {
    const double points[4] = {0.0, 0.0, 1.0, 1.0};
    BzjCurve *leaked = NULL;
    if (bzj_curve_new(2, 1, points, 4, &leaked) != BZJ_OK || leaked == NULL) {
        fprintf(stderr, "bzj_curve_new failed: %s\n", bzj_last_error());
        return 1;
    }
    printf("leaking one curve handle on purpose: %p\n", (void *)leaked);
    return 0; /* no bzj_curve_free(leaked) */
}
