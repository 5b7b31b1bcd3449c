/* viscolube: measured dynamic-mechanical (DMA) data -> a fitted compound.
 *
 * Reads a DMA export as users have it, builds the master curve at a
 * reference temperature by time-temperature superposition (tts.h), fits
 * WLF constants to the shifts and the creep-form Prony series to the master
 * curve (prony_fit.h). The database stores the result with the raw points
 * (database.h, vl_db_compound_add_measured); the shipped compounds go
 * through the same code.
 *
 * File format (the CSV rules of csv.h: '#' comments, blank lines, LF or
 * CRLF, optional UTF-8 byte-order mark, ',' ';' or tab delimiters and
 * decimal commas detected, spreadsheets refused, strict decimal numbers,
 * no NaN/Inf, every offending line reported at once; docs/FORMATS.md
 * section 4 lists every accepted spelling):
 *
 *   - A header row naming the columns, in any order. Names are matched
 *     without regard to case, blanks, '_', '-' and '.' (single letters
 *     exactly; 'δ' reads as delta, 'ω' as omega):
 *       frequency  f, w, freq, frequency, omega, angular frequency
 *       E' / G'    E', E_stor, E_storage, E1 / G', G_stor, G_storage, G1;
 *                  storage, storage modulus (tensile unless moduli = shear)
 *       E'' / G''  E'', E_loss, E2 / G'', G_loss, G2; loss, loss modulus
 *       |E*| / |G*| |E*|, E*, E_abs / |G*|, G*, G_abs; complex modulus
 *       tan delta  tan delta, tan_del, tand, tan(delta), tan δ, loss factor
 *       J', J''    J', J_stor, J_storage, J1 / J'', J_loss, J2 (compliances)
 *       T          T, temp, temperature (optional)
 *       set        set, isotherm (optional: which isotherm a row belongs to)
 *     Required: frequency and one of {E', E''}, {E', tan delta},
 *     {|E*|, tan delta}, {E'', tan delta}, {J', J''}. A redundant column
 *     (tan delta or |E*| beside E' and E'') must agree within 2 %. Other
 *     columns are ignored and named in the notes, unless their name is a
 *     likely misspelling of a known one (then refused with the suggestion).
 *     Tensile and shear names together are refused. Shear moduli are
 *     converted: E = 2 (1 + nu) G with opts->nu.
 *   - Units: after the name in brackets ("f [Hz]", "G' (MPa)"), after a
 *     '_' or blank ("freq_hz", "G_storage_pa", "temperature_C"), in an
 *     optional units row right after the header, or from the options; they
 *     must agree where more than one is given, and a column without any
 *     unit is refused (Hz and rad/s differ by 2 pi, C and K by 273.15).
 *     Frequency Hz or rad/s (1/s under an omega name); moduli Pa, kPa, MPa,
 *     GPa, N/mm^2, N/m^2, dyn/cm^2 (compliances 1/Pa ... 1/GPa or Pa^-1
 *     ...); temperature C, °C, degC, celsius, K or kelvin; tan delta and set
 *     '-', '1' or empty. Case and blanks do not matter. All moduli share a
 *     unit.
 *   - Data rows: frequency, moduli, compliances and tan delta > 0.
 *   - Plausibility: E' and |E*| (tensile, Pa) within [1e4, 1e12], E''
 *     within [10, 1e12], temperatures within [-150, 400] C, and not all
 *     within [200, 400] C under a Celsius unit from the file (kelvin
 *     numbers under a C header) unless opts->temp_unit confirms it.
 *
 * Isotherms: without a temperature column the file is one master curve at
 * opts->tref_c (which is then required). With one, rows are grouped into
 * isotherms: by the set column when present, else consecutive rows within
 * VL_DMA_ISOTHERM_TOL_K of the first row of their group; groups whose mean
 * temperatures lie within that tolerance are merged. A single isotherm
 * needs tref_c equal to its temperature (within the tolerance): it cannot
 * be shifted without WLF constants. Several isotherms are shifted (on
 * log E', and log E'' too where E' is flat: see vl_tts_chain_info; pairs
 * too far apart to share a quarter of a window are bridged) to the
 * isotherm nearest tref_c (default: the measured temperature nearest
 * 20 C), WLF is fitted (3 or more isotherms) and the shifts are re-referred
 * to tref_c exactly through the WLF equation; with 2 isotherms tref_c must
 * be one of their temperatures.
 *
 * Notes (vl_measured.notes, one sentence per line, for the caller to
 * print): the delimiter and decimal comma when not ',' and '.', the
 * ignored columns, the shear conversion (or a generic name read as
 * tensile), bridged pairs; lines starting "warning: " for a WLF residual
 * above VL_DMA_WARN_WLF_RMS, a fit error above VL_DMA_WARN_FIT_RMS in E'
 * or E'', and isotherms too far apart to join; and (dma_quality.c) a
 * note with the measured ranges (E', frequencies, temperatures), then
 * warnings for neighbouring isotherms that do not join (VL_DMA_WARN_JOIN_*,
 * naming both temperatures), a rise of tan delta at the top of the
 * isotherms' windows (VL_DMA_WARN_TAN_RISE, naming each isotherm and the
 * frequency) and Einf or E0 beyond VL_DMA_WARN_EXTRAPOLATION times the
 * measured E' (extrapolated).
 *
 * Refused, with FILE:LINE: column 'NAME' (field K) where a row is at fault
 * (every such row at once): everything csv.h refuses; misspelt, duplicate
 * or missing columns; missing, wrong or mixed units; implausible moduli or
 * temperatures; E' decreasing with frequency within an isotherm by more
 * than VL_DMA_DECREASE_TOL of its largest value at lower frequency (a
 * Prony series cannot); redundant columns that disagree; temperatures
 * below absolute zero; a set spanning more than 2 VL_DMA_ISOTHERM_TOL_K;
 * an isotherm with one point; isotherms that cannot be superposed; a
 * master curve under one decade; fewer points than Prony terms + 1. */
#ifndef VISCOLUBE_DMA_H
#define VISCOLUBE_DMA_H

#include <stddef.h>

#include "viscolube/prony_fit.h"
#include "viscolube/rheology.h"
#include "viscolube/status.h"

#define VL_DMA_ISOTHERM_TOL_K 1.0
/* Measurement scatter lets E' dip between neighbouring points (up to 6.6 %
 * in the pyvisco master curve); a real decrease is larger. */
#define VL_DMA_DECREASE_TOL 0.10
#define VL_DMA_MAX_POINTS 20000
#define VL_DMA_NOTES_MAX 2048
/* Warning thresholds (a note starting "warning: " in vl_measured.notes):
 * the WLF fit misses the shifts by more than this rms in log10 a_T
 * (decades; the shifts of thermorheologically simple data scatter by a few
 * hundredths), or the Prony fit misses E' or E'' by more than this rms
 * relative error (the data's own scatter is typically 1-2 %). */
#define VL_DMA_WARN_WLF_RMS 0.2
#define VL_DMA_WARN_FIT_RMS 0.05
/* Neighbouring isotherms do not join when, shifted, their log10 E' differ
 * by more than this rms over their overlap (decades: 0.02 is 4.7 %; the
 * scatter of a DMA's E' is about 1 %, 0.004 decades, and a thermorheologically
 * simple rubber's isotherms join within it). */
#define VL_DMA_WARN_JOIN_RMS 0.02
/* ... or when the shift step between them departs from the WLF law fitted
 * to all isotherms by more than this (decades): the horizontal shift
 * absorbed a vertical offset (two runs, a specimen that changed), so the
 * overlap matches while the step is off the smooth trend of its
 * neighbours. */
#define VL_DMA_WARN_JOIN_STEP 0.15
/* tan delta at the top of an isotherm's window rises above the trend of
 * the decade below by more than this (decades: 0.04 is 10 %) and by more
 * than 4 times that trend's own scatter: the signature of an instrument
 * resonance near the top of its frequency range, not of the material. */
#define VL_DMA_WARN_TAN_RISE 0.04
/* Einf above this factor times the largest measured E' (or E0 below the
 * smallest over it): the series' modulus there is extrapolated, set by
 * the fit's tail rather than by data. */
#define VL_DMA_WARN_EXTRAPOLATION 2.0

typedef enum {
  VL_DMA_STORAGE_LOSS = 0,  /* E', E'' (tan delta may be present too) */
  VL_DMA_STORAGE_TAN_DELTA, /* E', tan delta */
  VL_DMA_COMPLIANCE         /* J', J'' */
} vl_dma_kind;

/* Whether the file's moduli are tensile (E) or shear (G). */
typedef enum {
  VL_DMA_MODULI_AUTO = 0, /* from the column names: G', G'', |G*| are shear, E', E'', |E*|
                             tensile; names that say neither ("storage modulus") tensile */
  VL_DMA_MODULI_TENSILE,  /* tensile; a shear name in the header is refused */
  VL_DMA_MODULI_SHEAR     /* shear, whatever the names (an E name is refused) */
} vl_dma_moduli;

typedef struct {
  const char *freq_unit;    /* "Hz" or "rad/s"; NULL: from the file */
  const char *modulus_unit; /* "Pa", "kPa", "MPa", "GPa" (compliances in its
                               reciprocal); NULL: from the file */
  const char *temp_unit;    /* "C" or "K"; NULL: from the file */
  double tref_c;            /* reference temperature; NAN: not given */
  double terms_per_decade;  /* Prony grid density; 0: the default */
  vl_prony_weights weights; /* Prony fit row weights (prony_fit.h) */
  double nu;                /* Poisson ratio stored with the series, and the one that converts
                               shear moduli: E = 2 (1 + nu) G */
  vl_dma_moduli moduli;     /* tensile or shear (see vl_dma_moduli) */
} vl_dma_options;

/* No units, tref NAN, default grid, relative weights, nu = 0.5 (rubber,
 * DMA in tension), moduli from the names. */
vl_dma_options vl_dma_options_default(void);

/* The result of an import: the data as read (SI, file order), the
 * isotherms with their shifts, the master curve and the fit. */
typedef struct {
  char *source; /* file name used in messages (owned) */
  vl_dma_kind kind;
  int has_temperature;           /* the file had a temperature column */
  size_t n;                      /* data points */
  size_t *line;                  /* source line of each point */
  double *omega_rad_s;           /* angular frequency as measured */
  double *temperature_c;         /* measured (tref_c when the file has none) */
  double *storage_pa, *loss_pa;  /* E', E'' (derived when J or tan delta given) */
  double *j1_per_pa, *j2_per_pa; /* compliance input only, else NULL */
  size_t *isotherm;              /* isotherm index of each point */
  double *reduced_omega_rad_s;   /* a_T omega: the master curve at tref_c */
  size_t n_isotherms;
  double *iso_temperature_c; /* mean temperature, increasing */
  double *iso_log10_a_t;     /* shift of each isotherm relative to tref_c */
  size_t *iso_points;        /* points per isotherm */
  double tref_c;
  double wlf_c1, wlf_c2_k; /* at tref_c; NAN with fewer than 3 isotherms */
  double wlf_rms;          /* rms residual of the WLF fit in log10 a_T */
  vl_prony prony;          /* the fitted series at tref_c */
  vl_prony_fit_report fit;
  int shear;             /* the file held shear moduli, converted: E = 2 (1 + nu) G */
  char delimiter;        /* the file's delimiter (',', ';' or '\t') */
  int decimal_comma;     /* its numbers had decimal commas */
  size_t n_ignored;      /* header columns not used */
  size_t n_extrapolated; /* neighbouring isotherms shifted across a gap or a thin overlap */
  size_t n_warnings;     /* the lines of notes that start "warning: " */
  /* What was measured, and how well it hangs together (dma_quality.c):
   * the ranges of the data as read (before shifting), the join misfit of
   * each neighbouring pair of isotherms and the rise of tan delta at the top
   * of each isotherm's window. */
  double storage_min_pa, storage_max_pa;       /* E' measured (tensile) */
  double omega_min_rad_s, omega_max_rad_s;     /* measured frequencies (not reduced) */
  double temperature_min_c, temperature_max_c; /* measured isotherms (tref_c without T) */
  double *iso_join_rms;         /* n_isotherms - 1 entries (NULL with one): rms of the log10 E'
                                   difference between isotherms g and g + 1 after shifting, over
                                   their overlap (each point of one against the other's curve,
                                   linear in log w); NAN where the shifted windows do not overlap */
  double *iso_join_step;        /* n_isotherms - 1 entries (NULL with one): the shift step from
                                   isotherm g to g + 1 minus the step of the fitted WLF law
                                   (decades); NAN without WLF (fewer than 3 isotherms) or when the
                                   WLF law misses the shifts (warned of as a whole) */
  double *iso_tan_delta_rise;   /* n_isotherms entries: decades by which log10 tan delta at
                                   the isotherm's highest frequency lies above the straight
                                   line through its points of the decade below; NAN with
                                   fewer than 3 such points */
  char notes[VL_DMA_NOTES_MAX]; /* what the user should know, one sentence per line ('\n'
                                   after each): conversions, ignored columns, the dialect,
                                   warnings on the superposition and the fit */
} vl_measured;

/* Reads, shifts and fits the DMA file at path (see above). On VL_OK *out
 * owns its arrays (release with vl_measured_free); on failure *out is
 * empty (safe to free) and err holds one sentence naming the file (and
 * line and column where a row is at fault). opts may be NULL (defaults).
 * VL_EIO (unreadable file), VL_EINPUT, VL_ENOMEM, VL_ENOCONV. */
vl_status vl_measured_read_file(const char *path, const vl_dma_options *opts, vl_measured *out,
                                vl_error *err);

/* Releases what a vl_measured owns and empties it (NULL or empty is fine). */
void vl_measured_free(vl_measured *m);

#endif
