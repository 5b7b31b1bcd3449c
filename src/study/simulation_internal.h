/* viscolube (private): simulations below their public part
 * (viscolube/simulation.h): a compound at a temperature (for the queries,
 * query.c, and tests) and what a simulation holds that only the library
 * and tests read. */
#ifndef VISCOLUBE_SIMULATION_INTERNAL_H
#define VISCOLUBE_SIMULATION_INTERNAL_H

#include "viscolube/database.h"
#include "viscolube/rheology.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"
#include "viscolube/status.h"

/* Compound c at temperature t_c (docs/MODEL.md section 2, time-temperature
 * superposition): every retardation time tau_i -> a_T tau_i with
 *   log10 a_T = -C1 (T - Tref) / (C2 + T - Tref),
 * so a_T < 1 above Tref (warmer: faster, the loss peak at higher
 * frequency). Einf, nu and the A_i are unchanged (no vertical shift). At
 * t_c == c->tref_c returns c->prony exactly and a_T = 1, WLF constants or
 * not. VL_EINPUT (message names the compound): no WLF constants (NAN);
 * t_c at or below the WLF singularity Tref - C2; a shift that takes a time
 * out of the finite range. */
vl_status vl_compound_at_temperature(const vl_db_compound *c, double t_c, vl_prony *out,
                                     double *a_T, vl_error *err);

/* The sweep speeds (m/s, increasing), vl_simulation_points of them. */
const double *vl_simulation_speeds(const vl_simulation *sim);
/* The scene the simulation was created from (its copy). */
const vl_scene *vl_simulation_scene(const vl_simulation *sim);
/* The compound's Prony series at the scene's temperature. */
const vl_prony *vl_simulation_rubber(const vl_simulation *sim);

/* The same sweep at the n speeds v0_m_s (positive, increasing) instead of
 * the scene's: the calibration of a pair solves at the measured speeds. */
vl_status vl_simulation_run_speeds(vl_simulation *sim, size_t n, const double *v0_m_s,
                                   vl_point *out, vl_sweep_stats *stats, vl_error *err);

/* The stored pair whose sigma_s law the contact uses (NULL: none; the
 * scene's sigma_s_pa applies), and the law in use: the pair's at the
 * scene's temperature and viscosity (vl_shear_law_at), else the constant
 * sigma_s_pa (0 with solid_shear off). A pair is used when solid_shear is
 * on, the scene did not give sigma_s_pa, and compound, surface and fluid
 * have one. */
const vl_db_pair *vl_simulation_pair(const vl_simulation *sim);

const vl_shear_law *vl_simulation_shear_law(const vl_simulation *sim);

#endif
