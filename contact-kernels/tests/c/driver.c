/*
 * The driver of contact-kernels/tests/c_kernels.rs: evaluates every C
 * kernel on configurations read from stdin and prints the outputs as the
 * hexadecimal bits of each double, for a bit-for-bit comparison with the
 * Rust kernels.
 *
 * Input, one configuration per line: xi_s, xi_m0 (the slip's last
 * converged projection) then q[0..8], each as 16 hex digits (the bits of
 * the double).
 * Output, per configuration, 26 lines: for slave-normal, then closest-point,
 * the projection, types 1..6 and the slip's types 1..6, each "status"
 * followed, when the status is GAPSIM_OK, by the bits of gap (the slip),
 * xi_m and (types) grad[8] and (types 2..6) hess[64].
 */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gapsim_closest_point.h"
#include "gapsim_slave_normal.h"

typedef int (*project_fn)(const double q[8], double xi_s, double *gap, double *xi_m);
typedef int (*type_fn)(const double q[8], double xi_s, double *gap, double *xi_m,
                       double grad[8], double *hess);
typedef int (*slip_fn)(const double q[8], double xi_s, double xi_m0, double slip[1],
                       double *xi_m, double grad[8], double *hess);

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
 * (the gap or the slip), xi_m, grad[8] and (types 2..6) hess[64]. */
static void print_outputs(int status, double value, double xi_m, const double grad[8],
                          const double hess[64], int t)
{
    int i;
    printf("%d", status);
    if (status == GAPSIM_OK) {
        print_bits(value);
        print_bits(xi_m);
        for (i = 0; i < 8; ++i) {
            print_bits(grad[i]);
        }
        if (t > 0) {
            for (i = 0; i < 64; ++i) {
                print_bits(hess[i]);
            }
        }
    }
    printf("\n");
}

static void run(project_fn project, const type_fn types[6], const slip_fn slips[6],
                const double q[8], double xi_s, double xi_m0)
{
    double gap = 0.0, xi_m = 0.0, grad[8], hess[64];
    int status, t;
    status = project(q, xi_s, &gap, &xi_m);
    printf("%d", status);
    if (status == GAPSIM_OK) {
        print_bits(gap);
        print_bits(xi_m);
    }
    printf("\n");
    for (t = 0; t < 6; ++t) {
        /* Type 1 gets NULL for hess (documented as accepted). */
        status = types[t](q, xi_s, &gap, &xi_m, grad, t == 0 ? NULL : hess);
        print_outputs(status, gap, xi_m, grad, hess, t);
    }
    for (t = 0; t < 6; ++t) {
        double slip[1] = {0.0};
        status = slips[t](q, xi_s, xi_m0, slip, &xi_m, grad, t == 0 ? NULL : hess);
        print_outputs(status, slip[0], xi_m, grad, hess, t);
    }
}

int main(void)
{
    static const type_fn slave_normal[6] = {
        gapsim_slave_normal_type1, gapsim_slave_normal_type2, gapsim_slave_normal_type3,
        gapsim_slave_normal_type4, gapsim_slave_normal_type5, gapsim_slave_normal_type6,
    };
    static const type_fn closest_point[6] = {
        gapsim_closest_point_type1, gapsim_closest_point_type2, gapsim_closest_point_type3,
        gapsim_closest_point_type4, gapsim_closest_point_type5, gapsim_closest_point_type6,
    };
    static const slip_fn slave_normal_slip[6] = {
        gapsim_slave_normal_slip_type1, gapsim_slave_normal_slip_type2,
        gapsim_slave_normal_slip_type3, gapsim_slave_normal_slip_type4,
        gapsim_slave_normal_slip_type5, gapsim_slave_normal_slip_type6,
    };
    static const slip_fn closest_point_slip[6] = {
        gapsim_closest_point_slip_type1, gapsim_closest_point_slip_type2,
        gapsim_closest_point_slip_type3, gapsim_closest_point_slip_type4,
        gapsim_closest_point_slip_type5, gapsim_closest_point_slip_type6,
    };
    char line[512];
    while (fgets(line, sizeof line, stdin) != NULL) {
        double v[10];
        char *at = line;
        int i;
        for (i = 0; i < 10; ++i) {
            char *end;
            v[i] = from_bits((uint64_t)strtoull(at, &end, 16));
            if (end == at) {
                fprintf(stderr, "malformed input line: %s", line);
                return 1;
            }
            at = end;
        }
        run(gapsim_slave_normal_project, slave_normal, slave_normal_slip, v + 2, v[0], v[1]);
        run(gapsim_closest_point_project, closest_point, closest_point_slip, v + 2, v[0], v[1]);
    }
    return 0;
}
