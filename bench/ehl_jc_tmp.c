#include <stdio.h>
#include "point_ehl.h"
int main(void) {
  vl_point_ehl_config c;
  vl_point_ehl_config_defaults(&c);
  c.radius_m = 0.009525, c.load_n = 3.0, c.e_pa = 2e6, c.nu = 0.5, c.eta_pa_s = 10, c.v0_m_s = 0.04;
  c.h_fine = 0.15, c.h_coarse = 0.4;
  printf("worst %g\n", vl_point_ehl_jacobian_check(&c, 0.05));
  return 0;
}
