/* Shared by the fuzz targets of tests/fuzz (see tests/fuzz/CMakeLists.txt).
 *
 * Every fuzz_*.c defines LLVMFuzzerTestOneInput. Built with VL_FUZZ=ON
 * (clang) it is a libFuzzer program; otherwise it is linked with
 * replay_main.c and ctest replays its seed corpus, so the corpus is also a
 * regression test in the ordinary and the ASan builds. */
#ifndef VL_FUZZ_H
#define VL_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Where a failed check is reported: stderr under libFuzzer, the replay
 * driver's saved stderr when it silences the code under test. */
extern int vl_fuzz_report_fd;

/* Reports "file:line: message" and aborts (libFuzzer then saves the input). */
_Noreturn void vl_fuzz_fail(const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* A property of the code under test that must hold for every input. */
#define FUZZ_CHECK(cond, ...)                                                                      \
  do {                                                                                             \
    if (!(cond)) vl_fuzz_fail(__FILE__, __LINE__, __VA_ARGS__);                                    \
  } while (0)

/* 1 when msg holds no control byte except newlines that separate the lines
 * of a message listing several problems, each of which again starts with
 * path (or continues with two spaces); 0 otherwise. */
int vl_fuzz_message_clean(const char *msg, const char *path);

/* The contract of a reader refusing the file at path (status st, message
 * msg): VL_EINPUT, a message that starts with the path and holds no control
 * byte but the newlines between the lines of a problem list
 * (vl_fuzz_message_clean). A macro so that a failure names the caller's
 * line; the caller includes <string.h> and the viscolube header defining
 * VL_EINPUT. */
#define FUZZ_CHECK_REFUSED(st, path, msg)                                                          \
  do {                                                                                             \
    FUZZ_CHECK((st) == VL_EINPUT, "status %d for a bad file: %s", (int)(st), (msg));               \
    FUZZ_CHECK_LINES((path), (msg));                                                               \
  } while (0)

/* msg starts with name, every further line starts with name or continues
 * with two spaces, and it holds no control byte but the line breaks. */
#define FUZZ_CHECK_LINES(name, msg)                                                                \
  do {                                                                                             \
    FUZZ_CHECK(!strncmp((msg), (name), strlen(name)), "message does not name the file: %s",        \
               (msg));                                                                             \
    FUZZ_CHECK(vl_fuzz_message_clean((msg), (name)), "control byte in message: %s", (msg));        \
  } while (0)

/* A path naming a file whose content is exactly data[0..size): the readers
 * under test take paths. One in-memory file (memfd) is reused by every call,
 * so the path is only valid until the next call. Aborts if impossible. */
const char *vl_fuzz_file(const uint8_t *data, size_t size);

/* data[0..size) as a malloc'd NUL-terminated string (caller frees). */
char *vl_fuzz_strdup(const uint8_t *data, size_t size);

#endif
