/*
 * The face driver of contact-kernels/tests/c_kernels.rs: evaluates the C
 * kernels of every formulation of 3D faces on configurations read from
 * stdin and prints the outputs as the hexadecimal bits of each double, for
 * a bit-for-bit comparison with the Rust kernels.
 *
 * Input, one configuration per line: the formulation's index (decimal, in
 * the order of the table below), then xi_s (u, v), xi_m0 (u, v: the slip's
 * last converged projection) and q[0..n], each as 16 hex digits (the bits
 * of the double).
 * Output, per configuration, 13 lines: the projection, types 1..6 and the
 * slip's types 1..6, each "status" followed, when the status is GAPSIM_OK,
 * by the bits of gap (the slip's 3 components), xi_m (u, v) and (types)
 * grad[n] (slip: [3 n]) and (types 2..6) hess[n * n] (slip: [3 n n]).
 */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gapsim_quad4_closest_point.h"
#include "gapsim_quad4_slave_normal.h"
#include "gapsim_quad4_tri3_closest_point.h"
#include "gapsim_quad4_tri3_slave_normal.h"
#include "gapsim_tri3_closest_point.h"
#include "gapsim_tri3_quad4_closest_point.h"
#include "gapsim_tri3_quad4_slave_normal.h"
#include "gapsim_tri3_slave_normal.h"

#define MAX_COORDS 24

typedef int (*project_fn)(const double *q, double u, double v, double *gap, double *xi_m_u,
                          double *xi_m_v);
typedef int (*type_fn)(const double *q, double u, double v, double *gap, double *xi_m_u,
                       double *xi_m_v, double *grad, double *hess);

typedef int (*slip_fn)(const double *q, double u, double v, double m0_u, double m0_v,
                       double *slip, double *xi_m_u, double *xi_m_v, double *grad,
                       double *hess);

struct formulation {
    int coords;
    project_fn project;
    type_fn types[6];
    slip_fn slips[6];
};

#define TYPES(id)                                                                            \
    {                                                                                        \
        gapsim_##id##_type1, gapsim_##id##_type2, gapsim_##id##_type3, gapsim_##id##_type4, \
            gapsim_##id##_type5, gapsim_##id##_type6                                         \
    }

#define SLIPS(id)                                                                      \
    {                                                                                  \
        gapsim_##id##_slip_type1, gapsim_##id##_slip_type2, gapsim_##id##_slip_type3, \
            gapsim_##id##_slip_type4, gapsim_##id##_slip_type5, gapsim_##id##_slip_type6  \
    }

/* The order of tests/common/faces.rs' FACES. */
static const struct formulation formulations[8] = {
    {GAPSIM_TRI3_SLAVE_NORMAL_COORDS, gapsim_tri3_slave_normal_project, TYPES(tri3_slave_normal), SLIPS(tri3_slave_normal)},
    {GAPSIM_TRI3_CLOSEST_POINT_COORDS, gapsim_tri3_closest_point_project,
     TYPES(tri3_closest_point), SLIPS(tri3_closest_point)},
    {GAPSIM_QUAD4_SLAVE_NORMAL_COORDS, gapsim_quad4_slave_normal_project,
     TYPES(quad4_slave_normal), SLIPS(quad4_slave_normal)},
    {GAPSIM_QUAD4_CLOSEST_POINT_COORDS, gapsim_quad4_closest_point_project,
     TYPES(quad4_closest_point), SLIPS(quad4_closest_point)},
    {GAPSIM_TRI3_QUAD4_SLAVE_NORMAL_COORDS, gapsim_tri3_quad4_slave_normal_project,
     TYPES(tri3_quad4_slave_normal), SLIPS(tri3_quad4_slave_normal)},
    {GAPSIM_TRI3_QUAD4_CLOSEST_POINT_COORDS, gapsim_tri3_quad4_closest_point_project,
     TYPES(tri3_quad4_closest_point), SLIPS(tri3_quad4_closest_point)},
    {GAPSIM_QUAD4_TRI3_SLAVE_NORMAL_COORDS, gapsim_quad4_tri3_slave_normal_project,
     TYPES(quad4_tri3_slave_normal), SLIPS(quad4_tri3_slave_normal)},
    {GAPSIM_QUAD4_TRI3_CLOSEST_POINT_COORDS, gapsim_quad4_tri3_closest_point_project,
     TYPES(quad4_tri3_closest_point), SLIPS(quad4_tri3_closest_point)},
};

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

static void run(const struct formulation *f, const double *q, double u, double v,
                double m0_u, double m0_v)
{
    double gap = 0.0, xi_m_u = 0.0, xi_m_v = 0.0;
    static double grad[3 * MAX_COORDS], hess[3 * MAX_COORDS * MAX_COORDS];
    int n = f->coords;
    int status, t, i;
    status = f->project(q, u, v, &gap, &xi_m_u, &xi_m_v);
    printf("%d", status);
    if (status == GAPSIM_OK) {
        print_bits(gap);
        print_bits(xi_m_u);
        print_bits(xi_m_v);
    }
    printf("\n");
    for (t = 0; t < 6; ++t) {
        /* Type 1 gets NULL for hess (documented as accepted). */
        status = f->types[t](q, u, v, &gap, &xi_m_u, &xi_m_v, grad, t == 0 ? NULL : hess);
        printf("%d", status);
        if (status == GAPSIM_OK) {
            print_bits(gap);
            print_bits(xi_m_u);
            print_bits(xi_m_v);
            for (i = 0; i < n; ++i) {
                print_bits(grad[i]);
            }
            if (t > 0) {
                for (i = 0; i < n * n; ++i) {
                    print_bits(hess[i]);
                }
            }
        }
        printf("\n");
    }
    for (t = 0; t < 6; ++t) {
        double slip[3] = {0.0, 0.0, 0.0};
        status = f->slips[t](q, u, v, m0_u, m0_v, slip, &xi_m_u, &xi_m_v, grad,
                             t == 0 ? NULL : hess);
        printf("%d", status);
        if (status == GAPSIM_OK) {
            for (i = 0; i < 3; ++i) {
                print_bits(slip[i]);
            }
            print_bits(xi_m_u);
            print_bits(xi_m_v);
            for (i = 0; i < 3 * n; ++i) {
                print_bits(grad[i]);
            }
            if (t > 0) {
                for (i = 0; i < 3 * n * n; ++i) {
                    print_bits(hess[i]);
                }
            }
        }
        printf("\n");
    }
}

int main(void)
{
    static char line[4096];
    while (fgets(line, sizeof line, stdin) != NULL) {
        double v[4 + MAX_COORDS];
        char *at = line;
        char *end;
        long which = strtol(at, &end, 10);
        int i, n;
        if (end == at || which < 0 || which >= 8) {
            fprintf(stderr, "malformed input line: %s", line);
            return 1;
        }
        at = end;
        n = formulations[which].coords;
        for (i = 0; i < 4 + n; ++i) {
            v[i] = from_bits((uint64_t)strtoull(at, &end, 16));
            if (end == at) {
                fprintf(stderr, "malformed input line: %s", line);
                return 1;
            }
            at = end;
        }
        run(&formulations[which], v + 4, v[0], v[1], v[2], v[3]);
    }
    return 0;
}
