/*
 * Evaluates the slave-normal Type 6 kernel at the worked example of
 * docs/conventions.md from C and prints the gap, xi_m and the gradient.
 *
 * Build and run from the repository root:
 *
 *   cc -std=c99 -O2 -ffp-contract=off -Icontact-kernels/c examples/c/evaluate.c contact-kernels/c/gapsim_slave_normal.c contact-kernels/c/gapsim_runtime.c -lm -o evaluate && ./evaluate
 */
#include <stdio.h>

#include "gapsim_slave_normal.h"

int main(void)
{
    /* q = [xs1, ys1, xs2, ys2, xm1, ym1, xm2, ym2], current coordinates. */
    const double q[GAPSIM_SLAVE_NORMAL_COORDS] = {0.0, 1.0, 2.0, 1.1, 2.1, 0.9, -0.1, 1.0};
    const double xi_s = 0.3;
    double gap, xi_m;
    double grad[GAPSIM_SLAVE_NORMAL_COORDS];
    double hess[GAPSIM_SLAVE_NORMAL_COORDS * GAPSIM_SLAVE_NORMAL_COORDS]; /* row-major */
    int i;

    int status = gapsim_slave_normal_type6(q, xi_s, &gap, &xi_m, grad, hess);
    if (status != GAPSIM_OK) {
        fprintf(stderr, "gapsim_slave_normal_type6: %s\n", gapsim_status_name(status));
        return 1;
    }
    printf("gap  = %.15g\nxi_m = %.15g\ngrad =", gap, xi_m);
    for (i = 0; i < GAPSIM_SLAVE_NORMAL_COORDS; ++i) {
        printf(" %.6g", grad[i]);
    }
    printf("\nhess[0][0] = %.6g\n", hess[0]);

    /* Degenerate input is a status code, never NaN: a zero-length slave. */
    {
        const double bad[GAPSIM_SLAVE_NORMAL_COORDS] = {1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0};
        status = gapsim_slave_normal_type6(bad, xi_s, &gap, &xi_m, grad, hess);
        printf("zero-length slave: %s\n", gapsim_status_name(status));
    }
    return 0;
}
