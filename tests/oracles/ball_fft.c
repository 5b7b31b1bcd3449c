/* The Fourier-space ball oracle (ball_fft.h). */
#include "ball_fft.h"

#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b,
                   const int *ldb, int *info);

/* The displacement at the periodic offsets (i, j) of the FFT grid from a
 * unit pressure on one cell (point weight h^2), in the solver's units:
 * t = (1/(Nx Ny)) sum_q K(q) e^{i q.x}, K = (2/pi^2)(Er0/Er_inf) 2 pi/|q|
 * (1 + sum A/(1 + i q_x b)), the mean (q = 0) dropped (a constant, which the
 * rigid approach absorbs). */
static double *fft_table(const vl_oracle_ball_problem *pb, size_t Nx, size_t Ny) {
  fftw_complex *buf = fftw_malloc(Nx * Ny * sizeof *buf);
  double *t = malloc(Nx * Ny * sizeof *t);
  if (!buf || !t) {
    fftw_free(buf), free(t);
    return NULL;
  }
  double ainf = 1.0;
  for (size_t k = 0; k < pb->n_terms; k++)
    ainf += pb->A[k];
  for (size_t i = 0; i < Nx; i++) {
    long ki = i < (Nx + 1) / 2 ? (long)i : (long)i - (long)Nx;
    double qx = 2.0 * M_PI * (double)ki / ((double)Nx * pb->h);
    for (size_t j = 0; j < Ny; j++) {
      long kj = j < (Ny + 1) / 2 ? (long)j : (long)j - (long)Ny;
      double qy = 2.0 * M_PI * (double)kj / ((double)Ny * pb->h), q = hypot(qx, qy);
      double complex J = 1.0;
      for (size_t k = 0; k < pb->n_terms; k++)
        J += pb->A[k] / (1.0 + I * qx * pb->de[k]);
      double complex K = q > 0.0 ? 2.0 / (M_PI * M_PI) / ainf * 2.0 * M_PI / q * J : 0.0;
      buf[i * Ny + j] = K;
    }
  }
  fftw_plan plan = fftw_plan_dft_2d((int)Nx, (int)Ny, buf, buf, FFTW_BACKWARD, FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  for (size_t i = 0; i < Nx * Ny; i++)
    t[i] = creal(buf[i]) / (double)(Nx * Ny);
  fftw_free(buf);
  return t;
}

/* The influence matrix of the half grid (the cell and its mirror image). */
static void half_matrix(const vl_oracle_ball_problem *pb, const double *t, size_t Nx, size_t Ny,
                        double *M) {
  size_t n = pb->nx * pb->ny, ny = pb->ny;
  for (size_t i = 0; i < n; i++)
    for (size_t j = 0; j < n; j++) {
      long dx = (long)(i / ny) - (long)(j / ny);
      long iy = (long)(i % ny), jy = (long)(j % ny);
      size_t px = (size_t)((dx % (long)Nx + (long)Nx) % (long)Nx);
      size_t d1 = (size_t)(((iy - jy) % (long)Ny + (long)Ny) % (long)Ny);
      size_t d2 = (size_t)((iy + jy + 1) % (long)Ny);
      M[i * n + j] = t[px * Ny + d1] + t[px * Ny + d2];
    }
}

/* One active-set step: the pressure on the set S (n_s cells) and h0 from
 * M_SS p + h0 = -f_S and the load; returns the LAPACK info. */
static int solve_set(size_t n, const double *M, const double *f, double w, const char *in,
                     double *p, double *h0, double *A, double *rhs, int *piv, size_t *idx) {
  size_t ns = 0;
  for (size_t i = 0; i < n; i++)
    if (in[i]) idx[ns++] = i;
  size_t m = ns + 1;
  for (size_t a = 0; a < ns; a++) {
    for (size_t b = 0; b < ns; b++)
      A[b * m + a] = M[idx[a] * n + idx[b]]; /* column-major */
    A[ns * m + a] = 1.0;
    A[a * m + ns] = w;
    rhs[a] = -f[idx[a]];
  }
  A[ns * m + ns] = 0.0;
  rhs[ns] = 1.0;
  int mi = (int)m, one = 1, info = 0;
  dgesv_(&mi, &one, A, &mi, piv, rhs, &mi, &info);
  memset(p, 0, n * sizeof *p);
  for (size_t a = 0; a < ns; a++)
    p[idx[a]] = rhs[a];
  *h0 = rhs[ns];
  return info;
}

int vl_oracle_ball_fft_solve(const vl_oracle_ball_problem *pb, vl_oracle_ball_solution *out) {
  memset(out, 0, sizeof *out);
  if (pb->nx % 2 == 0 || pb->ny < 1 || !(pb->h > 0.0) || pb->pad_x < 2 || pb->pad_y < 2) return -1;
  size_t nx = pb->nx, ny = pb->ny, n = nx * ny;
  size_t Nx = (size_t)ceil(pb->pad_x * (double)nx), Ny = (size_t)ceil(pb->pad_y * 2.0 * (double)ny);
  double *t = fft_table(pb, Nx, Ny);
  double *M = malloc(n * n * sizeof *M), *A = malloc((n + 1) * (n + 1) * sizeof *A);
  double *f = malloc(4 * (n + 1) * sizeof *f);
  char *in = malloc(n), *next = malloc(n);
  int *piv = malloc((n + 1) * sizeof *piv);
  size_t *idx = malloc(n * sizeof *idx);
  int rc = -3;
  if (!t || !M || !A || !f || !in || !next || !piv || !idx) goto done;
  half_matrix(pb, t, Nx, Ny, M);
  double *p = f + (n + 1), *rhs = f + 2 * (n + 1), *u = f + 3 * (n + 1), h0 = 0.0;
  size_t i0 = (nx - 1) / 2;
  for (size_t i = 0; i < n; i++) {
    double x = ((double)(i / ny) - (double)i0) * pb->h, y = ((double)(i % ny) + 0.5) * pb->h;
    f[i] = 0.5 * (pb->gx * x * x + pb->gy * y * y);
    in[i] = f[i] < 0.5; /* Hertz's circle */
  }
  double w = 3.0 * pb->h * pb->h / M_PI; /* both halves: 2 h^2 P p0 a0^2 / W */
  rc = -2;
  for (int it = 1; it <= 200; it++) {
    if (solve_set(n, M, f, w, in, p, &h0, A, rhs, piv, idx) != 0) {
      rc = -3;
      goto done;
    }
    int changed = 0;
    for (size_t i = 0; i < n; i++) {
      u[i] = h0 + f[i];
      for (size_t j = 0; j < n; j++)
        u[i] += M[i * n + j] * p[j];
      next[i] = in[i] ? p[i] > 0.0 : u[i] < 0.0;
      changed += next[i] != in[i];
    }
    out->iterations = it;
    if (!changed) {
      rc = 0;
      break;
    }
    memcpy(in, next, n);
  }
  if (rc == 0) {
    double spx = 0.0, cells = 0.0;
    for (size_t i = 0; i < n; i++) {
      double x = ((double)(i / ny) - (double)i0) * pb->h;
      spx += p[i] * x;
      out->p_max = fmax(out->p_max, p[i]);
      cells += p[i] > 0.0;
    }
    out->mu_R_over_a0 = -w * spx;
    out->area = 2.0 * cells * pb->h * pb->h;
    out->h0 = h0;
    out->converged = 1;
  }
done:
  free(t), free(M), free(A), free(f), free(in), free(next), free(piv), free(idx);
  return rc;
}
