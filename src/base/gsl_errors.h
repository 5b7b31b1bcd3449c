/* The library's one policy for GSL's errors. Private to the library.
 *
 * GSL's default error handler prints a message and aborts the process. The
 * library never prints and never exits (status.h): every GSL call it makes
 * has its return code checked (or, for the special functions, its result
 * tested for finiteness) and turned into a vl_status. So the handler is
 * turned off, process-wide and once, by vl_gsl_errors_off(), which every
 * library entry point that reaches GSL calls first: vl_kernel_viscoelastic,
 * vl_toeplitz_refill (kernel.c), vl_persson_build, vl_persson_deserialize
 * (persson.c: a table exists only through them), vl_flattening_create
 * (flattening.c) and vl_nnls_solve (nnls.c). The handler is not restored
 * afterwards: an application that installs its own after the library's
 * first use gets it back, and it must not abort either. */
#ifndef VL_GSL_ERRORS_H
#define VL_GSL_ERRORS_H

/* Turns GSL's aborting error handler off, once per process (thread-safe;
 * later calls cost one check). */
void vl_gsl_errors_off(void);

#endif
