/* Fuzz target: scene files (`viscolube run SCENE`), read by vl_scene_load
 * as the command line reads them. Properties: a refused scene gets
 * VL_EINPUT and one line starting with the file name, without control
 * characters (the message goes to a terminal); an accepted scene satisfies
 * every rule README.md states for the keys (required keys present, ranges,
 * effects consistent with the materials). */
#include "vl_fuzz.h"

#include <math.h>
#include <string.h>

#include "viscolube/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const char *path = vl_fuzz_file(data, size);
  static vl_scene sc; /* 30 kB: off the stack */
  vl_error err = {{0}};
  vl_status st = vl_scene_load(path, &sc, &err);
  if (st != VL_OK) {
    FUZZ_CHECK(st == VL_EINPUT, "status %d: %s", (int)st, err.msg);
    FUZZ_CHECK(!strncmp(err.msg, path, strlen(path)), "message does not name the file: %s",
               err.msg);
    for (const char *c = err.msg; *c; c++)
      FUZZ_CHECK((unsigned char)*c >= 0x20 && *c != 0x7f, "control byte 0x%02x in message: %s",
                 (unsigned)(unsigned char)*c, err.msg);
    return 0;
  }
  FUZZ_CHECK(sc.compound[0] != '\0', "no compound");
  FUZZ_CHECK(isfinite(sc.radius_m) && sc.radius_m > 0.0, "radius %g", sc.radius_m);
  if (sc.geometry == VL_GEOMETRY_CYLINDER) /* a cylinder's load per length, a ball's total */
    FUZZ_CHECK(isfinite(sc.load_n_per_m) && sc.load_n_per_m > 0.0, "load %g", sc.load_n_per_m);
  else
    FUZZ_CHECK(isfinite(sc.load_n) && sc.load_n > 0.0 && isfinite(sc.radius_y_m) &&
                   sc.radius_y_m > 0.0 && !sc.effects.fluid && !sc.effects.roughness,
               "point contact: load %g, radius across %g", sc.load_n, sc.radius_y_m);
  FUZZ_CHECK(isfinite(sc.sigma_s_pa) && sc.sigma_s_pa >= 0.0, "sigma_s %g", sc.sigma_s_pa);
  FUZZ_CHECK(isfinite(sc.from) && sc.from > 0.0 && isfinite(sc.to) && sc.to > 0.0, "sweep [%g, %g]",
             sc.from, sc.to);
  FUZZ_CHECK(sc.points >= 1 && sc.points <= 100000, "points %zu", sc.points);
  FUZZ_CHECK(sc.points == 1 || sc.to > sc.from, "to %g <= from %g", sc.to, sc.from);
  FUZZ_CHECK(sc.n_fields_at <= VL_FIELDS_AT_MAX, "n_fields_at %zu", sc.n_fields_at);
  for (size_t i = 0; i < sc.n_fields_at; i++)
    FUZZ_CHECK(isfinite(sc.fields_at[i]) && sc.fields_at[i] > 0.0, "fields_at %g", sc.fields_at[i]);
  FUZZ_CHECK(sc.grid >= 16 && sc.grid <= 8192, "grid %zu", sc.grid);
  FUZZ_CHECK(sc.domain_min_a0 < 0.0 && sc.domain_max_a0 > 0.0 && isfinite(sc.domain_min_a0) &&
                 isfinite(sc.domain_max_a0),
             "domain [%g, %g]", sc.domain_min_a0, sc.domain_max_a0);
  FUZZ_CHECK(sc.tolerance > 0.0 && sc.tolerance < 1.0, "tolerance %g", sc.tolerance);
  FUZZ_CHECK(sc.persson_table == 0 || (sc.persson_table >= 64 && sc.persson_table <= 100000),
             "persson_table %zu", sc.persson_table);
  FUZZ_CHECK(sc.n_fluids <= VL_FLUIDS_MAX, "n_fluids %zu", sc.n_fluids);
  for (size_t k = 0; k < sc.n_fluids; k++)
    FUZZ_CHECK(sc.fluids[k][0] != '\0', "empty fluid name %zu", k);
  FUZZ_CHECK(!sc.effects.roughness || sc.surface[0], "roughness on without a surface");
  FUZZ_CHECK(!sc.effects.fluid || sc.fluid[0], "fluid on without a fluid");
  FUZZ_CHECK(sc.quantity != VL_SWEEP_V0_ETA || sc.effects.fluid, "v0_eta without fluid");
  FUZZ_CHECK(sc.quantity != VL_SWEEP_DEBORAH || sc.effects.viscoelastic,
             "deborah without viscoelasticity");
  FUZZ_CHECK(!sc.effects.solid_shear || sc.sigma_s_pa > 0.0, "solid shear without sigma_s");
  FUZZ_CHECK(!sc.effects.viscous_flattening || (sc.effects.roughness && sc.effects.fluid),
             "viscous flattening without roughness and fluid");
  FUZZ_CHECK(!sc.effects.temperature || isfinite(sc.effects.temperature_c),
             "temperature on without temperature_c");
  FUZZ_CHECK(sc.elastic != VL_ELASTIC_GIVEN ||
                 (isfinite(sc.elastic_modulus_pa) && sc.elastic_modulus_pa > 0.0),
             "elastic modulus %g", sc.elastic_modulus_pa);
  return 0;
}
