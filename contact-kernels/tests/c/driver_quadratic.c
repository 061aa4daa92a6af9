/*
 * The driver of contact-kernels/tests/c_kernels.rs for the 3-node
 * formulation quadratic-slave-normal (12 coordinates): evaluates its C
 * kernels on configurations read from stdin and prints the outputs as the
 * hexadecimal bits of each double, for a bit-for-bit comparison with the
 * Rust kernels.
 *
 * Input, one configuration per line: xi_s, xi_m0 (the slip's last
 * converged projection) then q[0..12], each as 16 hex digits (the bits of
 * the double).
 * Output, per configuration, 13 lines: the projection, types 1..6 and the
 * slip's types 1..6, each "status" followed, when the status is GAPSIM_OK,
 * by the bits of gap (the slip), xi_m and (types) grad[12] and (types
 * 2..6) hess[144].
 */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gapsim_quadratic_slave_normal.h"

#define N GAPSIM_QUADRATIC_SLAVE_NORMAL_COORDS

typedef int (*type_fn)(const double q[N], double xi_s, double *gap, double *xi_m,
                       double grad[N], double *hess);
typedef int (*slip_fn)(const double q[N], double xi_s, double xi_m0, double slip[1],
                       double *xi_m, double grad[N], double *hess);

static double from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static void print_bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    printf(" %016" PRIx64, u);
}

/* One type's line: the status and, on GAPSIM_OK, the bits of the value
 * (the gap or the slip), xi_m, grad[N] and (types 2..6) hess[N * N]. */
static void print_outputs(int status, double value, double xi_m, const double *grad,
                          const double *hess, int t)
{
    int i;
    printf("%d", status);
    if (status == GAPSIM_OK) {
        print_bits(value);
        print_bits(xi_m);
        for (i = 0; i < N; ++i) {
            print_bits(grad[i]);
        }
        if (t > 0) {
            for (i = 0; i < N * N; ++i) {
                print_bits(hess[i]);
            }
        }
    }
    printf("\n");
}

int main(void)
{
    static const type_fn types[6] = {
        gapsim_quadratic_slave_normal_type1, gapsim_quadratic_slave_normal_type2,
        gapsim_quadratic_slave_normal_type3, gapsim_quadratic_slave_normal_type4,
        gapsim_quadratic_slave_normal_type5, gapsim_quadratic_slave_normal_type6,
    };
    static const slip_fn slips[6] = {
        gapsim_quadratic_slave_normal_slip_type1, gapsim_quadratic_slave_normal_slip_type2,
        gapsim_quadratic_slave_normal_slip_type3, gapsim_quadratic_slave_normal_slip_type4,
        gapsim_quadratic_slave_normal_slip_type5, gapsim_quadratic_slave_normal_slip_type6,
    };
    char line[1024];
    while (fgets(line, sizeof line, stdin) != NULL) {
        double v[N + 2], gap = 0.0, xi_m = 0.0, grad[N], hess[N * N];
        char *at = line;
        int i, t, status;
        for (i = 0; i < N + 2; ++i) {
            char *end;
            v[i] = from_bits((uint64_t)strtoull(at, &end, 16));
            if (end == at) {
                fprintf(stderr, "malformed input line: %s", line);
                return 1;
            }
            at = end;
        }
        status = gapsim_quadratic_slave_normal_project(v + 2, v[0], &gap, &xi_m);
        printf("%d", status);
        if (status == GAPSIM_OK) {
            print_bits(gap);
            print_bits(xi_m);
        }
        printf("\n");
        for (t = 0; t < 6; ++t) {
            /* Type 1 gets NULL for hess (documented as accepted). */
            status = types[t](v + 2, v[0], &gap, &xi_m, grad, t == 0 ? NULL : hess);
            print_outputs(status, gap, xi_m, grad, hess, t);
        }
        for (t = 0; t < 6; ++t) {
            double slip[1] = {0.0};
            status = slips[t](v + 2, v[0], v[1], slip, &xi_m, grad, t == 0 ? NULL : hess);
            print_outputs(status, slip[0], xi_m, grad, hess, t);
        }
    }
    return 0;
}
