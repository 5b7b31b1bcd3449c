/* Fuzz target: the number parser behind every numeric command-line option
 * (--e-inf, --nu, --tref, --wlf-c1/2, --hurst, --q0, --q1, --hrms,
 * --viscosity: cli_materials.c's number_opt calls vl_csv_parse_double) and
 * every CSV cell. Differential check against an independent reading of
 * csv.h's grammar plus the C library's strtod:
 *   - accepted exactly when the blank-trimmed text is
 *     [+-](digits[.digits]|.digits)[(e|E)[+-]digits], at most 128
 *     characters, and strtod gives a finite value without ERANGE;
 *   - an accepted value is bit-for-bit strtod's;
 *   - a refusal comes with a reason. */
#include "vl_fuzz.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube/csv.h"

/* The grammar, written as a table of states rather than import_text.c's loops. */
static int grammar(const char *s, size_t n) {
  enum { START, SIGN, INT, DOT0, FRAC, EXP, EXPSIGN, EXPDIG, BAD } q = START;
  for (size_t i = 0; i < n && q != BAD; i++) {
    char c = s[i];
    int d = c >= '0' && c <= '9';
    switch (q) {
    case START: q = (c == '+' || c == '-') ? SIGN : d ? INT : c == '.' ? DOT0 : BAD; break;
    case SIGN: q = d ? INT : c == '.' ? DOT0 : BAD; break;
    case INT: q = d ? INT : c == '.' ? FRAC : (c == 'e' || c == 'E') ? EXP : BAD; break;
    case DOT0: q = d ? FRAC : BAD; break;
    case FRAC: q = d ? FRAC : (c == 'e' || c == 'E') ? EXP : BAD; break;
    case EXP: q = (c == '+' || c == '-') ? EXPSIGN : d ? EXPDIG : BAD; break;
    case EXPSIGN: q = d ? EXPDIG : BAD; break;
    case EXPDIG: q = d ? EXPDIG : BAD; break;
    case BAD: break;
    }
  }
  return q == INT || q == FRAC || q == EXPDIG;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (memchr(data, '\0', size)) return 0; /* a C string cannot hold one */
  char *s = vl_fuzz_strdup(data, size);
  double v = -12345.0;
  const char *why = NULL;
  vl_status st = vl_csv_parse_double(s, &v, &why);

  const char *b = s, *e = s + size;
  while (b < e && (*b == ' ' || *b == '\t'))
    b++;
  while (e > b && (e[-1] == ' ' || e[-1] == '\t'))
    e--;
  size_t n = (size_t)(e - b);
  int expect = 0;
  double ref = 0.0;
  if (n <= 128 && grammar(b, n)) {
    char *t = vl_fuzz_strdup((const uint8_t *)b, n);
    errno = 0;
    ref = strtod(t, NULL);
    expect = errno != ERANGE && isfinite(ref);
    free(t);
  }
  if (expect) {
    FUZZ_CHECK(st == VL_OK, "refused '%s' (%s)", s, why ? why : "no reason");
    FUZZ_CHECK(memcmp(&v, &ref, sizeof v) == 0, "'%s' read as %.17g, strtod %.17g", s, v, ref);
  } else {
    FUZZ_CHECK(st == VL_EINPUT, "accepted '%s' as %.17g", s, v);
    FUZZ_CHECK(why && *why, "no reason given for refusing '%s'", s);
    FUZZ_CHECK(v == -12345.0, "a refused value was written");
  }
  free(s);
  return 0;
}
