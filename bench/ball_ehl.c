/* Quick driver (temporary). */
#include "point_ehl.h"
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char **argv) {
  vl_point_ehl_config c;
  vl_point_ehl_config_defaults(&c);
  c.radius_m = 0.009525, c.load_n = 3.0, c.rubber.e_inf_pa = 2e6, c.rubber.nu = 0.5,
  c.eta_pa_s = 0.1;
  c.v0_m_s = argc > 1 ? atof(argv[1]) : 0.04;
  if (argc > 2) c.h_fine = atof(argv[2]);
  if (argc > 3) c.h_coarse = atof(argv[3]);
  if (argc > 4) c.eta_pa_s = atof(argv[4]);
  if (argc > 5) c.growth = atof(argv[5]);
  vl_point_ehl_result r;
  vl_error err = {0};
  vl_status st = vl_point_ehl_solve(&c, NULL, &r, NULL, &err);
  double hm, hc;
  vl_point_ehl_hamrock_dowson(&c, &hm, &hc);
  printf("st %d conv %d it %ld cont %ld cells %zux%zu res %.2e hc %.4g (HD %.4g) hmin %.4g (HD "
         "%.4g) at %.3f,%.3f a; axis min %.4g; load %.1e muRf %.4g muSf %.4g t %.2f+%.2f s %s\n",
         st, r.converged, r.iterations, r.continuation_steps, r.nx, r.ny, r.residual, r.h_c_m, hc,
         r.h_min_m, hm, r.x_min_m / r.a_m, r.y_min_m / r.a_m, r.h_min_axis_m, r.load_error, r.mu_Rf,
         r.mu_Sf, r.t_influence_s, r.t_solve_s, err.msg);
  return 0;
}
