/* `cmake --install` into a scratch prefix, and the library used from there
 * as another project would: the files in their places (program, shared
 * library with its SONAME link, headers, CMake package, pkg-config file,
 * man page), the installed program's --version, and a small C program
 * (open a database on a temporary path, print the compound names) built
 * once with find_package(viscolube) and once with pkg-config, then run.
 * ctest passes the build's settings in the environment (tests/CMakeLists.txt). */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char dir[1024], prefix[1100], log_path[1100];

/* getenv(name), failing the test when ctest did not set it. */
static const char *env(const char *name) {
  const char *v = getenv(name);
  if (!v) fail_msg("%s is not set (run the tests through ctest)", name);
  return v;
}

/* Runs a shell command (printf-style), its output into log_path; fails the
 * test with the output when it exits non-zero. */
static void sh(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void sh(const char *fmt, ...) {
  char cmd[8192], full[8192 + 1200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(cmd, sizeof cmd, fmt, ap);
  va_end(ap);
  snprintf(full, sizeof full, "( %s ) >'%s' 2>&1", cmd, log_path);
  int rc = system(full);
  if (rc != 0) {
    char *text = vl_test_read_file(log_path);
    fail_msg("`%s` failed (status %d):\n%s", cmd, rc, text ? text : "");
  }
}

static void expect_file(const char *rel) {
  char path[1400];
  struct stat sb;
  snprintf(path, sizeof path, "%s/%s", prefix, rel);
  if (stat(path, &sb) != 0) fail_msg("not installed: %s", path);
}

static const char consumer_c[] =
    "/* lists the compounds of a fresh database */\n"
    "#include <stdio.h>\n"
    "#include <stdlib.h>\n"
    "#include <viscolube.h>\n"
    "int main(int argc, char **argv) {\n"
    "  vl_db *db = NULL;\n"
    "  vl_error err = {{0}};\n"
    "  vl_db_compound *items = NULL;\n"
    "  size_t n = 0;\n"
    "  if (argc != 2) return 2;\n"
    "  if (vl_db_open(argv[1], &db, &err) != VL_OK ||\n"
    "      vl_db_compound_list(db, &items, &n, &err) != VL_OK) {\n"
    "    fprintf(stderr, \"%s\\n\", err.msg);\n"
    "    vl_db_close(db);\n"
    "    return 1;\n"
    "  }\n"
    "  for (size_t i = 0; i < n; i++) printf(\"%s\\n\", items[i].name);\n"
    "  free(items);\n"
    "  vl_db_close(db);\n"
    "  return 0;\n"
    "}\n";

static const char consumer_cmake[] =
    "cmake_minimum_required(VERSION 3.25)\n"
    "project(consumer C)\n"
    "find_package(viscolube 0.1 REQUIRED)\n"
    "add_executable(consumer main.c)\n"
    "target_link_libraries(consumer PRIVATE viscolube::viscolube)\n";

/* Runs a consumer on a new database and checks the shipped compounds. */
static void run_consumer(const char *exe, const char *label) {
  char db[1400], out[1400];
  snprintf(db, sizeof db, "%s/%s.db", dir, label);
  snprintf(out, sizeof out, "%s/%s.out", dir, label);
  sh("'%s' '%s' >'%s'", exe, db, out);
  char *text = vl_test_read_file(out);
  printf("%s consumer: %s", label, text);
  if (!text || !strstr(text, "sbr-filled\n") || !strstr(text, "sbr-unfilled\n") ||
      !strstr(text, "model-rubber\n"))
    fail_msg("%s consumer printed: %s", label, text ? text : "(nothing)");
  free(text);
  /* with the shared library, the one installed (not the build tree's) */
  if (!strcmp(env("VL_SHARED"), "ON")) {
    snprintf(out, sizeof out, "%s/%s.ldd", dir, label);
    sh("ldd '%s' >'%s'", exe, out);
    text = vl_test_read_file(out);
    char want[1400];
    snprintf(want, sizeof want, "%s/%s/libviscolube.so.", prefix, env("VL_INSTALL_LIBDIR"));
    if (!text || !strstr(text, want))
      fail_msg("%s consumer: not linked to %s: %s", label, want, text ? text : "");
    free(text);
  }
}

static void test_install(void **state) {
  (void)state;
  snprintf(dir, sizeof dir, "%s", vl_test_tmpdir());
  snprintf(prefix, sizeof prefix, "%s/prefix", dir);
  snprintf(log_path, sizeof log_path, "%s/log", dir);
  const char *cmake = env("VL_CMAKE"), *libdir = env("VL_INSTALL_LIBDIR");
  const char *flags = env("VL_CONSUMER_FLAGS");
  sh("'%s' --install '%s' --prefix '%s'", cmake, env("VL_BUILD_DIR"), prefix);
  char rel[512];
  expect_file("bin/viscolube");
  expect_file("include/viscolube.h");
  expect_file("include/viscolube/status.h");
  expect_file("include/viscolube/database.h");
  expect_file("share/man/man1/viscolube.1");
  snprintf(rel, sizeof rel, "%s/cmake/viscolube/viscolube-config.cmake", libdir);
  expect_file(rel);
  snprintf(rel, sizeof rel, "%s/pkgconfig/viscolube.pc", libdir);
  expect_file(rel);
  if (!strcmp(env("VL_SHARED"), "ON")) {
    const char *v = env("VL_VERSION");
    unsigned major = 0, minor = 0;
    sscanf(v, "%u.%u", &major, &minor);
    snprintf(rel, sizeof rel, "%s/libviscolube.so.%u.%u", libdir, major, minor); /* SONAME */
    expect_file(rel);
    snprintf(rel, sizeof rel, "%s/libviscolube.so.%s", libdir, v);
    expect_file(rel);
  } else {
    snprintf(rel, sizeof rel, "%s/libviscolube.a", libdir);
    expect_file(rel);
  }

  /* the installed program: its version */
  char path[1400], want[256];
  snprintf(path, sizeof path, "%s/version", dir);
  sh("'%s/bin/viscolube' --version >'%s'", prefix, path);
  char *text = vl_test_read_file(path);
  snprintf(want, sizeof want, "viscolube %s (source ", env("VL_VERSION"));
  if (!text || strncmp(text, want, strlen(want)) != 0) fail_msg("--version: %s", text);
  printf("installed: %s", text);
  free(text);
  /* the man page is the --help text */
  snprintf(path, sizeof path, "%s/share/man/man1/viscolube.1", prefix);
  text = vl_test_read_file(path);
  assert_non_null(strstr(text, ".TH VISCOLUBE 1"));
  assert_non_null(strstr(text, "usage: viscolube run SCENE"));
  free(text);

  /* a project with find_package(viscolube) */
  char src[1200], build[1200];
  snprintf(src, sizeof src, "%s/consumer", dir);
  snprintf(build, sizeof build, "%s/consumer-build", dir);
  sh("mkdir -p '%s'", src);
  snprintf(path, sizeof path, "%s/main.c", src);
  vl_test_write_file(path, consumer_c);
  snprintf(path, sizeof path, "%s/CMakeLists.txt", src);
  vl_test_write_file(path, consumer_cmake);
  sh("'%s' -S '%s' -B '%s' -DCMAKE_PREFIX_PATH='%s' -DCMAKE_C_COMPILER='%s' "
     "-DCMAKE_C_FLAGS='%s' -DCMAKE_EXE_LINKER_FLAGS='%s' && '%s' --build '%s'",
     cmake, src, build, prefix, env("VL_CC"), flags, flags, cmake, build);
  snprintf(path, sizeof path, "%s/consumer", build);
  run_consumer(path, "find_package");

  /* and one with pkg-config */
  snprintf(path, sizeof path, "%s/consumer-pc", dir);
  sh("PKG_CONFIG_PATH='%s/%s/pkgconfig' && export PKG_CONFIG_PATH && "
     "'%s' %s -o '%s' '%s/main.c' $(pkg-config --cflags --libs %s viscolube) "
     "-Wl,-rpath,'%s/%s'",
     prefix, libdir, env("VL_CC"), flags, path, src,
     strcmp(env("VL_SHARED"), "ON") ? "--static" : "", prefix, libdir);
  run_consumer(path, "pkg-config");
  sh("rm -rf '%s'", dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_install),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
