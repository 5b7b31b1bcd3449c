/* `viscolube seal`: what it adds to a run's outputs (cli_run.c runs the
 * scene, both strokes): the table of the strokes on the console, seal.csv,
 * seal.json and the figure, and the instroke's points for the lists of
 * failures, warnings and points above their target. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

vl_point *vl_cli_instroke_points(size_t n, const vl_point *pts) {
  vl_point *in = calloc(n ? n : 1, sizeof *in);
  for (size_t i = 0; in && i < n; i++) {
    const vl_seal_result *s = &pts[i].seal;
    vl_point *q = &in[i];
    q->v0_m_s = pts[i].v0_m_s;
    q->converged = s->in_converged;
    q->iterations = s->in_iterations, q->residual = s->in_residual;
    q->mu = s->in_mu, q->mu_Sc = s->in_mu_Sc, q->mu_Sf = s->in_mu_Sf, q->rolling_na = true;
    q->u_min_m = s->in_u_min_m, q->u_central_m = s->in_u_central_m;
    q->flux_m2_s = s->in_flux_m2_s;
    q->error_estimate = s->in_error_estimate, q->flux_error_estimate = s->in_flux_error_estimate;
    q->accuracy = s->in_accuracy;
    snprintf(q->warnings, sizeof q->warnings, "%s", s->in_warnings);
  }
  return in;
}

/* A stroke's error estimate as the run's table shows it: "-" without one,
 * '!' when not known to its target. */
static void estimate_text(char *buf, size_t size, bool converged, double est, bool unreliable) {
  snprintf(buf, size, "-");
  if (converged && isfinite(est)) snprintf(buf, size, "%.2g%%", 100.0 * est);
  if (unreliable) snprintf(buf + strlen(buf), size - strlen(buf), "!");
}

/* A number of the table, "-" where the stroke did not converge. */
static void cell(char *buf, size_t size, double v) {
  if (isfinite(v))
    snprintf(buf, size, "%.4g", v);
  else
    snprintf(buf, size, "-");
}

void vl_cli_print_seal_table(size_t n, const vl_point *pts) {
  vl_point *in = vl_cli_instroke_points(n, pts);
  if (!in) return;
  printf("%11s %11s %11s %10s %10s %10s %10s %11s %11s %8s %8s %10s %10s %5s\n", "v0_m_s",
         "F_out_N/m", "F_in_N/m", "umin_out", "umin_in", "ucen_out", "ucen_in", "q_out_m2/s",
         "q_in_m2/s", "err_out", "err_in", "V_out_m3", "V_back_m3", "tight");
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i], *q = &in[i];
    const vl_point *st[2] = {p, q};
    char c[2][6][24], eo[16], ei[16];
    for (int s = 0; s < 2; s++) {
      bool ok = st[s]->converged;
      cell(c[s][0], sizeof c[s][0],
           ok ? (s ? p->seal.in_friction_n_per_m : p->seal.friction_n_per_m) : NAN);
      cell(c[s][1], sizeof c[s][1], ok ? st[s]->u_min_m : NAN);
      cell(c[s][2], sizeof c[s][2], ok ? st[s]->u_central_m : NAN);
      cell(c[s][3], sizeof c[s][3], ok ? st[s]->flux_m2_s : NAN);
    }
    estimate_text(eo, sizeof eo, p->converged, p->error_estimate, vl_point_unreliable(p));
    estimate_text(ei, sizeof ei, q->converged, q->error_estimate, vl_point_unreliable(q));
    char vo[24], vb[24];
    cell(vo, sizeof vo, p->seal.volume_out_m3);
    cell(vb, sizeof vb, p->seal.volume_back_m3);
    const char *tight = p->seal.tight < 0 ? "-" : p->seal.tight ? "yes" : "NO";
    printf("%11.4g %11s %11s %10s %10s %10s %10s %11s %11s %8s %8s %10s %10s %5s\n", p->v0_m_s,
           c[0][0], c[1][0], c[0][1], c[1][1], c[0][2], c[1][2], c[0][3], c[1][3], eo, ei, vo, vb,
           tight);
  }
  free(in);
}

vl_status vl_cli_seal_files(vl_manifest *man, const char *out_dir, size_t n, const vl_point *pts,
                            const vl_plot_options *plot, vl_error *err) {
  char path[4200];
  vl_error werr = {{0}};
  snprintf(path, sizeof path, "%s/seal.csv", out_dir);
  vl_cli_manifest_file(man, path, vl_write_seal_csv(path, n, pts, &werr), &werr);
  snprintf(path, sizeof path, "%s/seal.json", out_dir);
  vl_cli_manifest_file(man, path, vl_write_seal_json(path, n, pts, &werr), &werr);
  if (!plot) return VL_OK;
  snprintf(path, sizeof path, "%s/seal", out_dir);
  vl_status st = vl_plot_seal(path, n, pts, plot, NULL, err);
  vl_cli_manifest_figure(man, path, st, err);
  /* a figure that did not fit is in the manifest; anything else is an error */
  return st == VL_EIO ? VL_OK : st;
}
