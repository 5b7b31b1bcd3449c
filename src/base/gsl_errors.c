/* GSL's error handler, off once per process (gsl_errors.h). */
#include "gsl_errors.h"

#include <pthread.h>

#include <gsl/gsl_errno.h>

static pthread_once_t once = PTHREAD_ONCE_INIT;

static void turn_off(void) { gsl_set_error_handler_off(); }

void vl_gsl_errors_off(void) { pthread_once(&once, turn_off); }
