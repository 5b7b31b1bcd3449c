/* viscolube: the exponential integral of the viscoelastic kernel,
 *   g(z) = -e^{-z} Ei(z)  (z > 0),   g(z) = e^{|z|} E1(|z|)  (z < 0),
 * which the memory term needs once or twice per Prony term and offset
 * (kernel.c). GSL's scaled Ei and E1 cost 60-90 ns a call, most of a kernel
 * refill of a many-term rubber; on the range the kernel mostly asks for,
 * 1/2 <= |z| < 64, g comes from a piecewise Chebyshev interpolant of GSL's own
 * values, built once per process (about 900 GSL calls), at a few ns a call.
 * Elsewhere GSL is called directly. */
#ifndef VISCOLUBE_KERNEL_EXPINT_H
#define VISCOLUBE_KERNEL_EXPINT_H

/* g(z) for z != 0 (log-singular at 0); NaN if GSL fails, which it cannot for
 * finite nonzero z. Thread-safe. Turns GSL's abort handler off. Agrees with
 * vl_expint_g_gsl to about 1e-15 relative (tests/test_kernel.c). */
double vl_expint_g(double z);

/* g(z) straight from GSL (the reference the interpolant is built from). */
double vl_expint_g_gsl(double z);

#endif
