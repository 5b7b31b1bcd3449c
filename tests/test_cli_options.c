/* The command line's option parser (src/cli/cli_options.c) end to end: a
 * mistyped option gets the nearest known one in every command ("unknown
 * option '--sped' (did you mean --speed?)"), exit status 2, one line on
 * stderr, nothing on stdout and the database untouched; an option that
 * is nothing like a known one keeps the command's old message. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "vl_test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The scratch database, created (from the shipped materials) so that
 * vl_test_expect_fail can see it is left alone. */
static int setup(void **state) {
  vl_test_setup_db(state);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "fluid list");
  free(out);
  free(err);
  return rc;
}

/* `ARGS` fails with status 2 and one line naming typo and its suggestion. */
static void expect_suggestion(const char *args, const char *typo, const char *near) {
  char unknown[128], hint[128];
  snprintf(unknown, sizeof unknown, "unknown option '%s'", typo);
  snprintf(hint, sizeof hint, "(did you mean %s?)", near);
  vl_test_expect_fail(2, unknown, hint, "%s", args);
}

static void test_friction_and_compare(void **state) {
  (void)state;
  static const struct {
    const char *args, *typo, *near;
  } cases[] = {
      {"friction --compound sbr-unfilled %s --sped 1", "--sped", "--speed"},
      {"friction --compund sbr-unfilled %s --speed 1", "--compund", "--compound"},
      /* a neighbour swap is one edit */
      {"friction --compound sbr-unfilled %s --speed 1 --laod 100", "--laod", "--load"},
      {"compare --compunds sbr-unfilled,sbr-filled %s", "--compunds", "--compounds"},
      {"compare --compounds sbr-unfilled %s --form 1e-9", "--form", "--from"},
      /* friction's option, given to compare */
      {"compare --compound sbr-unfilled %s", "--compound", "--compounds"},
  };
  const char *mats = "--surface paper-3um --fluid water";
  char args[512];
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(args, sizeof args, cases[i].args, mats);
    expect_suggestion(args, cases[i].typo, cases[i].near);
  }
  /* nothing near: the command's own message, unchanged */
  snprintf(args, sizeof args, "friction --compound sbr-unfilled %s --speed 1 --bogus", mats);
  vl_test_expect_fail(2, "unknown or incomplete option '--bogus' (see --help)", NULL, "%s", args);
}

static void test_run_and_study(void **state) {
  (void)state;
  const char *scene = vl_test_source_path("cases/fig05.ini");
  vl_test_expect_fail(2, "unknown option '--jsn' (did you mean --json?)", NULL, "run %s --jsn",
                      scene);
  vl_test_expect_fail(2, "unknown option '--uot' (did you mean --out?)", NULL, "run %s --uot %s/o",
                      scene, vl_test_dir);
  const char *study = vl_test_source_path("studies/example.ini");
  vl_test_expect_fail(2, "unknown option '--jbos' (did you mean --jobs?)", NULL,
                      "study %s --out %s/s --jbos 2", study, vl_test_dir);
  vl_test_expect_fail(2, "unknown option '--quite' (did you mean --quiet?)", NULL,
                      "study %s --out %s/s --quite", study, vl_test_dir);
  vl_test_expect_fail(2, "unknown option '--frobnicate' (see viscolube study --help)", NULL,
                      "study %s --out %s/s --frobnicate", study, vl_test_dir);
}

static void test_material_nouns(void **state) {
  (void)state;
  const char *prony = vl_test_scratch("prony.csv", "A,tau_s\n9,1e-3\n");
  vl_test_expect_fail(2, "unknown option '--e-ifn' (did you mean --e-inf?)", NULL,
                      "compound add x --prony %s --e-ifn 1e9 --nu 0.5", prony);
  vl_test_expect_fail(2, "unknown option '--prnoy' (did you mean --prony?)", NULL,
                      "compound add x --prnoy %s --e-inf 1e9 --nu 0.5", prony);
  /* strict form: the part before '=' is the option */
  vl_test_expect_fail(2, "unknown option '--descripton' (did you mean --description?)", NULL,
                      "compound add x --prony %s --e-inf 1e9 --nu 0.5 --descripton=old", prony);
  vl_test_expect_fail(2, "unknown option '--jsn' (did you mean --json?)", NULL,
                      "compound list --jsn");
  vl_test_expect_fail(2, "unknown option '--hurts' (did you mean --hurst?)", NULL,
                      "surface add s --self-affine --hurts 0.8 --q0 1e3 --q1 1e6 --hrms 1e-6");
  vl_test_expect_fail(2, "unknown option '--modle' (did you mean --model?)", NULL,
                      "surface flow-factors paper-3um --modle smooth");
  vl_test_expect_fail(2, "unknown option '--viscosty' (did you mean --viscosity?)", NULL,
                      "fluid add f --viscosty 1e-3");
  /* nothing near */
  vl_test_expect_fail(2, "unknown option '--frobnicate' (see viscolube compound add --help)", NULL,
                      "compound add x --prony %s --e-inf 1e9 --nu 0.5 --frobnicate", prony);
}

static void test_other_commands(void **state) {
  (void)state;
  vl_test_expect_fail(2, "viscolube flattening: unknown option '--sped' (did you mean --speeds?)",
                      NULL,
                      "flattening --compound sbr-unfilled --surface paper-3um --fluid water "
                      "--sped 1");
  /* the global options before the noun */
  vl_test_expect_fail(2, "viscolube: unknown option '--qiuet' (did you mean --quiet?)", NULL,
                      "--qiuet fluid list");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_friction_and_compare, setup),
      cmocka_unit_test_setup(test_run_and_study, setup),
      cmocka_unit_test_setup(test_material_nouns, setup),
      cmocka_unit_test_setup(test_other_commands, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
