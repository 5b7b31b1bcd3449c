/* viscolube: time-temperature superposition of measured isotherms.
 *
 * A thermorheologically simple rubber measured at temperature T behaves at
 * the reference temperature Tref as at the reduced frequency
 *   w_r = a_T(T) w,   log10 a_T(Tref) = 0,
 * with a_T > 1 below Tref (colder = stiffer = "higher frequency"). Only
 * horizontal shifts are applied (no vertical b_T = rho T / rho0 T0 factor,
 * a few % over a typical range and usually below the scatter of the data).
 *
 * Shifts are found pairwise between neighbouring isotherms from the overlap
 * of their curves in the (log w, log E') and (log w, log E'') planes, and
 * chained from the reference isotherm outwards. The WLF equation (docs/MODEL.md
 * section 2) is then fitted to the chained shifts. */
#ifndef VISCOLUBE_TTS_H
#define VISCOLUBE_TTS_H

#include <stddef.h>

#include "viscolube/status.h"

/* One isotherm: n points sorted by increasing log10 w (rad/s); the two
 * curves log10 E' and log10 E'' (Pa) at those points. */
typedef struct {
  double temperature_c;
  size_t n;
  const double *log10_omega;
  const double *log10_storage;
  const double *log10_loss;
} vl_tts_isotherm;

/* The horizontal shift d (decades) that lays isotherm b onto isotherm a:
 * b's point at log w sits on a's curve at log w + d. Minimises the mean
 * squared difference of log E' (plus loss_weight times that of log E'')
 * between the two curves' interpolants (cubic Hermite with three-point
 * slopes) over the overlap interval of the two frequency ranges (48
 * midpoints, so the objective does not jump as points enter or leave the
 * overlap, and has no spurious minima at whole point spacings). The
 * overlap must hold at least 3 points of the two curves together and a
 * quarter of the narrower window; among such shifts the global minimum is
 * found by a scan (0.05 decade, then 0.005 decade around its best) and
 * refined by golden section.
 *
 * *shift gets d; *rms (may be NULL) the rms log10 mismatch at d.
 * VL_EINPUT if an isotherm has fewer than 2 distinct frequencies or the
 * curves have no shift with enough overlap (the message names both
 * temperatures). */
vl_status vl_tts_pair_shift(const vl_tts_isotherm *a, const vl_tts_isotherm *b, double loss_weight,
                            double *shift, double *rms, vl_error *err);

/* Shifts of n isotherms sorted by increasing temperature relative to
 * isotherm ref: log10_a_t[ref] = 0 and
 *   log10_a_t[k+1] = log10_a_t[k] + d(iso[k], iso[k+1]).
 * Each pair is shifted on log E' and log E'' together (E' alone is flat on
 * the rubbery and glassy plateaus, where E'' still varies), each weighted
 * by the inverse square of its own misfit (its rms mismatch at its own best
 * shift, at least its scatter about a quadratic and 0.002), unless the two
 * quantities' own shifts disagree by more than 3 standard errors (rms
 * misfit / (trend slope sqrt(points compared)), + 0.02 decade), or an own
 * shift held by the overlap constraint is ruled out by a free E' whose
 * trend changes by more than twice its misfit between the two; or unless,
 * at the joint shift, log E' alone mismatches by more than 1.5 times (+ 0.001) the
 * larger of its mismatch at its own best shift and the mismatch its
 * scatter explains (rms residuals of quadratic fits of log E' against
 * log w, added in quadrature for the two isotherms): then E'' does not obey
 * superposition - below the glass transition secondary relaxations
 * dominate it (on the pyvisco data a shift on E'' puts glassy isotherms
 * ~10 decades off, and weighted equally E'' pulled glassy steps of 0.8 to
 * 2.3 decades to 0.1) - and log E', monotonic and still superposable there,
 * decides alone. See tts.c, "weighing E' against E''".
 * pair_rms (n - 1 values, may be NULL) gets each pair's rms mismatch.
 * Errors as vl_tts_pair_shift. */
vl_status vl_tts_chain(size_t n, const vl_tts_isotherm *iso, size_t ref, double *log10_a_t,
                       double *pair_rms, vl_error *err);

/* How one neighbouring pair was shifted (vl_tts_chain_info). */
typedef struct {
  double shift;           /* d(iso[k], iso[k+1]), decades */
  double rms;             /* rms log10 mismatch at it */
  double overlap_decades; /* of the two windows at it (negative: a gap) */
  int loss_used;          /* E'' took part (else E' alone) */
  double loss_weight;     /* its weight against E' (0: E' alone) */
  int bridged;            /* the overlap was too thin to compare: joined by trends */
  int at_limit;           /* bridged, and the best shift is the largest gap tried */
  int no_join;            /* bridging was needed but the curves do not join smoothly: the shift
                             is the overlap-limited one, a bound */
} vl_tts_pair_info;

/* As vl_tts_chain, with each pair's info (n - 1 entries, may be NULL).
 * A pair whose best shift sits at the smallest overlap allowed (a quarter
 * of the narrower window) is shifted again by bridging: the points of each
 * curve within 1.5 decades of the junction are fitted together, the
 * warmer shifted by d, by one cubic in log w per quantity (log E' and
 * log E'', by the same E''-or-not policy), and d minimises the residual,
 * from that overlap out to a gap of 1 decade between the windows. The
 * shift then rests on the curves' trends, not on common points: the caller
 * should say so (bridged), and more loudly when the best d is the largest
 * gap tried (at_limit: the isotherms are too far apart in temperature).
 * When the joint fit is much worse than each curve's own (an F statistic
 * above 10 for the cubic's extra parameters: the curves do not form one
 * smooth curve, e.g. glassy E'' that does not superpose), the pair keeps
 * the overlap-limited shift and no_join says so. */
vl_status vl_tts_chain_info(size_t n, const vl_tts_isotherm *iso, size_t ref, double *log10_a_t,
                            vl_tts_pair_info *info, vl_error *err);

/* Least-squares fit of the WLF equation
 *   log10 a_T = -C1 (T - Tref) / (C2 + T - Tref)
 * to n >= 3 shifts at distinct temperatures (Celsius) measured relative to
 * tref_c (the shift at tref_c is 0 by definition; it need not be one of the
 * t_c). For fixed C2 the model is linear in C1 (solved exactly); C2 is
 * found by a scan in log C2 and golden-section refinement over
 * (Tref - Tmin, 1e5 K], so that C2 + T - Tref > 0 at every data point.
 * *c1, *c2_k get the constants and *rms (may be NULL) the rms residual in
 * log10 a_T. VL_EINPUT: fewer than 3 points, non-finite input, shifts that
 * do not decrease with temperature overall (C1 <= 0: not WLF). */
vl_status vl_wlf_fit(size_t n, const double *t_c, const double *log10_a_t, double tref_c,
                     double *c1, double *c2_k, double *rms, vl_error *err);

#endif
