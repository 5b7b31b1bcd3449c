/* The point contact's private state (point_contact.c) and what the tests
 * and the benchmark read of it. Private to src/solver; the public API is
 * viscolube/point_contact.h. */
#ifndef VISCOLUBE_POINT_CONTACT_INTERNAL_H
#define VISCOLUBE_POINT_CONTACT_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <time.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include "viscolube/point_contact.h"

#include "kernel2d.h"
#include "point_ehl.h"

/* Where a point's time goes (seconds and counts, since creation). */
typedef struct {
  double t_kernel_s;   /* influence table and blocks at each new speed */
  double t_residual_s; /* the gap (block products) and the rows */
  double t_jacobian_s; /* the dense Jacobian */
  double t_setup_s;    /* the linear solver's set-up (the LU of the cells in contact) */
  double t_solve_s;    /* its solves */
  long residuals, jacobians, setups, solves, newton_iterations, kernels;
} vl_point_contact_timing;

struct vl_point_contact {
  vl_point_contact_config cfg;
  int geometry;                           /* VL_GEOMETRY_BALL (Rx = Ry) or VL_GEOMETRY_ELLIPSOID */
  size_t nx, ny, n, nunk;                 /* cells along x and across, cells, unknowns (n + 1) */
  size_t i0;                              /* the column of cells on the axis x = 0 */
  double h;                               /* cell size / a0 */
  double a0, p0, re, er0, er_inf, uscale; /* uscale = a0^2/Re */
  double gx, gy;                          /* f/(a0^2/Re) = (gx X^2 + gy Y^2)/2: Re/Rx, Re/Ry */
  double kfac;                            /* U per (kernel coefficient P): 2/pi^2 Er0/Er_inf */
  double load_unit;                       /* the load row: load_unit sum P = W_solved/W */
  double *X, *Y, *f;                      /* cell centres (a0) and the undeformed gap (a0^2/Re) */
  size_t nk;                              /* Prony terms */
  double *A, *b;                          /* their strengths and memory lengths v0 tau / a0 */
  vl_kernel2d kern;                       /* the influence table (lengths in a0) */
  double *B;          /* blocks of the influence matrix: B(dx) for dx = ix - jx, ny x ny,
                       * column-major: B[(dx + nx - 1) ny^2 + jy ny + iy] */
  double *P, *U;      /* pressure (p0) and gap (a0^2/Re) of the last evaluation */
  double *dp, *du;    /* d(row i)/dP_i and d(row i)/dU_i (du: the reduced solver's hint) */
  size_t jlo, jhi;    /* columns ix with pressure (the block products skip the others) */
  bool min_rows;      /* min(P, U) rows (active set), else Fischer-Burmeister */
  bool warm_set;      /* the next rows take the set {P > 0} of the state */
  bool gap_rows_only; /* the Jacobian writes only the rows the reduced solver reads */
  size_t kernel_builds;
  double v0;      /* speed the influence is built for (NAN: none yet) */
  double v_state; /* speed of the converged state (NAN: the state is a guess) */
  vl_point_contact_timing timing;
  bool graded;          /* a lubricated or rough ball on graded cells: point_contact_wet.c */
  vl_point_ehl_map map; /* its fields after a solve (nx 0: none yet) */
  const vl_point_ehl_map *start; /* the next solve's start (another contact's map), or NULL */
  SUNContext ctx;
  N_Vector y, y_saved, y_start, ones, fwork;
  SUNMatrix J;
  SUNLinearSolver LS;
  void *kmem;
};

/* Wall-clock seconds (CLOCK_MONOTONIC), for the cost counters. */
static inline double vl_point_contact_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* point_contact.c */

/* Checks cfg (VL_EINPUT naming the field), sets the scales and cells and
 * allocates everything but KINSOL's part; no state yet. */
vl_status vl_point_contact_build(const vl_point_contact_config *cfg, vl_point_contact **out,
                                 vl_error *err);

/* Frees what vl_point_contact_build allocated, and c (NULL allowed). */
void vl_point_contact_release(vl_point_contact *c);

/* Makes the influence blocks those of speed v0 (a no-op at the current
 * speed; an elastic ball builds them once). */
void vl_point_contact_set_speed(vl_point_contact *c, double v0);

/* The influence matrix element: U_i per P_j (dimensionless), i, j < n. */
double vl_point_contact_influence(const vl_point_contact *c, size_t i, size_t j);

/* Resets the state to the Hertz guess. */
void vl_point_contact_reset(vl_point_contact *c);

/* P and U from the unknowns y (U = H0 + f + M P). */
void vl_point_contact_eval(vl_point_contact *c, const double *y);

/* The residual f(y) (nunk values): 0, or 1 when an entry is not finite. */
int vl_point_contact_residual(vl_point_contact *c, const double *y, double *f);

/* The dense Jacobian at y into the column-major nunk x nunk Jd. */
void vl_point_contact_jacobian(vl_point_contact *c, const double *y, double *Jd);

/* point_contact_wet.c */

/* A lubricated or rough ball: solved on graded cells by point_ehl.h. */
static inline bool vl_point_contact_is_graded(const vl_point_contact_config *cfg) {
  return cfg->eta_pa_s > 0.0 || cfg->roughness;
}

/* Solves the lubricated ball at v0 into pt (and c->map). */
vl_status vl_point_contact_wet_solve(vl_point_contact *c, double v0, vl_point *pt, vl_error *err);

/* The next lubricated solve of c starts from from's solution (the same
 * contact on other cells; from must outlive that solve; NULL: none). */
void vl_point_contact_wet_start_from(vl_point_contact *c, const vl_point_contact *from);

/* Cells of a lubricated ball's grid for cfg (without solving). */
size_t vl_point_contact_wet_cells(const vl_point_contact_config *cfg);

/* point_contact_solve.c */

/* (vl_point_contact_create, _solve, _free of point_contact.h) */

#endif
