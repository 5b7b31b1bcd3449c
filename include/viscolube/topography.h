/* viscolube: measured topography (profilometer line scans, AFM height maps)
 * -> the isotropic 2-D power spectrum C(q) of roughness.h.
 *
 * Users have heights, not spectra. This module reads the two files they
 * usually have and estimates C(q) in m^4 with this project's convention,
 *   h_rms^2 = \int d^2q C(q) = 2 pi \int q C(q) dq,
 * as tabulated points ready for vl_psd_init_tabulated.
 *
 * ---- Files (text; LF, CRLF or CR; an optional UTF-8 byte-order mark) ------
 *
 * Line scan: two columns, position then height, under a header row that
 * names the unit of each: "x [um], z [nm]", "position (m);height (m)",
 * "x_m,z_m" (a unit in [] or (), else after the last '_'). Units: m, mm,
 * um, µm, nm and their spellings (meter, metre, micron, micrometer,
 * nanometre, ...; case ignored). Lines whose first non-blank character is
 * '#' and blank lines are ignored. The delimiter is taken from the first
 * data row: tab if it has one, else ';', else blanks if they separate two
 * fields, else ','; with a delimiter other than ',' a ',' inside numbers is
 * a decimal comma ("0,25;1,5"; the first row that shows a separator
 * decides), and then '.' is refused (it would be a thousands separator). Positions must increase on
 * a uniform grid (every position within VL_TOPOGRAPHY_GRID_TOL spacings of x_0 + i dx); at least
 * VL_TOPOGRAPHY_MIN_POINTS points.
 *
 * Height map (as Gwyddion and SurfaceTopography export "matrix" files):
 * '#' header lines "# Width: 10.00 µm", "# Height: 10.00 µm" (the physical
 * size along the rows and down the columns) and "# Value units: m" (the
 * heights' unit); keys in any case, ':' or '=' after them, other '#' lines
 * ignored (and in a line scan '#' lines are only comments). Width and
 * value units are required; without Height the pixels
 * are taken square (said in the provenance). Then a matrix of heights, one
 * row per line, separated by tabs, blanks, ';' or ',' (detected as for line
 * scans, decimal comma likewise), every row of the same length, at least
 * VL_TOPOGRAPHY_MIN_POINTS rows and columns. Row i of the file is y = i dy,
 * column j is x = j dx, with dx = width / columns, dy = height / rows.
 *
 * A file is a map when its first row that is not a '#' line is numeric, a
 * line scan when that row is a header. Every failure is VL_EINPUT with one
 * sentence "FILE:LINE: field K: what is wrong (got 'TEXT')" (file-level
 * errors without line or field), VL_EIO for an unreadable file, VL_ENOMEM.
 *
 * ---- The spectrum (vl_topography_psd) -------------------------------------
 *
 * 1. Detrend: the least-squares plane (map) or line (line scan) is removed;
 *    hrms_topography_m is the rms of what remains (vl_topography_hrms).
 * 2. Window: a periodic Tukey (cosine-tapered) window, separable w_x w_y on
 *    maps: w = (1 - cos(2 pi e / taper)) / 2 within a fraction taper/2 of
 *    either end (e = distance to the end / length), 1 between; taper 1 is
 *    the periodic Hann window. It removes the jump between the two ends of
 *    a non-periodic measurement, which would leak power ~ q^-2 over the
 *    whole spectrum. The power is divided by mean(w^2) (0.766 for the
 *    default taper 0.2 on a map, 9/64 for Hann), which restores the mean
 *    square of a stationary signal. Why not Hann: on a map it weighs the
 *    centre, an effective 26 % of the area (Tukey 0.2: 80 %), and a real
 *    map is not stationary at its own scale. The AFM map of the tests
 *    (SurfaceTopography's matrix-3, 10 um, rms 35.2 nm) is rougher near its
 *    edges: Hann keeps 27.3 nm of its rms, Tukey 0.2 33.9 nm. On synthetic
 *    surfaces both recover C(q) (tests/test_topography.c); Hann leaks less
 *    from wavelengths longer than the map when nothing rolls off within it.
 *    taper 0 (no window) is for periodic data; only the mean is then
 *    removed in step 1's place (a plane would make a sawtooth of them).
 * 3. FFT (FFTW, real to complex). With H_k = \sum_n w_n h_n e^{-2 pi i k n/N}
 *    and Parseval, <h^2> = \sum_k |H_k|^2 / N^2 over all N frequencies. A
 *    density C sampled on the lattice q = 2 pi k / L must satisfy
 *    \sum_k C(q_k) dq = <h^2> with dq = 2 pi / L per dimension, hence
 *      map:  C(q)  = |H|^2 (dx dy)^2 / ((2 pi)^2 Lx Ly) / mean(w^2)   [m^4]
 *      line: C1(q) = |H|^2 dx^2 / (2 pi L) / mean(w^2)                [m^3]
 *    with h_rms^2 = \int d^2q C and h_rms^2 = \int_{-inf}^{inf} C1 dq.
 * 4. Band: wavevectors q in [q_min, q_max] are kept, with
 *    q_min = long_cut * 2 pi / L (L the shorter side; below 2 pi / L nothing
 *    is measured) and q_max = short_cut * pi / dx (pi / dx is the Nyquist
 *    wavevector; the default 1/2 keeps wavelengths of 4 pixels and more:
 *    the last octave carries the instrument's transfer function - tip,
 *    filters - and the aliases of what the sampling missed).
 * 5. Log bins: bins_per_decade per decade, centred on q_min 10^(j/b); each
 *    non-empty bin gives one point: the mean C of its wavevectors (the
 *    radial average over an annulus on maps) at the geometric mean of their
 *    |q|. Empty bins (the sparse lattice at the lowest q) are skipped. On a
 *    power law the mean over a bin sits ~2 % above the value at the
 *    geometric mean (10 bins per decade).
 * 6. Line scans only, 1-D -> 2-D. For isotropic roughness the profile's
 *    spectrum is the projection of the surface's,
 *      C1(q) = \int dq_y C(sqrt(q^2 + q_y^2)) = 2 \int_q^inf C(Q) Q dQ / sqrt(Q^2 - q^2),
 *    an Abel transform, whose inverse is
 *      C(Q) = -(1/pi) \int_Q^inf C1'(q) dq / sqrt(q^2 - Q^2).
 *    It is evaluated on the binned C1 made non-increasing (the least-squares
 *    non-increasing fit, by pooling adjacent bins where one profile's noise
 *    makes C1 rise: C1 of an isotropic surface whose C does not increase
 *    cannot, and then C >= 0 everywhere), interpolated as a power law
 *    between points and continued beyond the last one with the slope of a
 *    log-log fit to the last half decade, substituting q = Q cosh t
 *    (dq / sqrt(q^2 - Q^2) = dt removes the singularity) and integrating in
 *    t by Gauss-Legendre panels. For a power law C1 = A q^-(1+2H) this
 *    gives C = C1 / q * Gamma(H+1) / (sqrt(pi) Gamma(H+1/2)), between
 *    C1/(pi q) (H = 0) and 2 C1/(pi q) (H = 1): the common shortcut
 *    C1/(pi q) is right only for H = 0, and a local-slope version of the
 *    formula fails where C1 flattens (the roll-off), hence the integral.
 *    Points with C <= 0 (none after the pooling, in practice) are dropped
 *    and counted in n_dropped. One profile is one sample of the surface:
 *    its lowest points (one frequency each) scatter by tens of percent.
 * 7. (extend_low, with long_cut 1) The first point's C is continued, flat,
 *    down to q_e = sqrt(dq_x dq_y / pi), the radius of a disc of one lattice
 *    cell (a line scan counts as an L x L square). The cells of the
 *    wavevectors with |q| >= 2 pi/L tile the plane outside the cell of
 *    q = 0; a tabulated spectrum that starts at 2 pi/L would lose about
 *    half the power of the lowest ring, much of h_rms^2 when nothing rolls
 *    off within the measurement. The point has count 0 and q < q_min.
 *
 * hrms_band_m is the rms of the kept wavevectors' power (before binning);
 * hrms_psd_m is vl_psd_hrms of the tabulated points (power law between
 * points, zero outside [q_1, q_n]); hrms_psd_m / hrms_topography_m says how
 * much of the measured roughness the tabulated spectrum keeps (a caller
 * should report it: below 1 when power lies beyond the band, or the
 * window weighs smoother parts of the measurement).
 *
 * Not thread-safe: FFTW's planner is not. */
#ifndef VISCOLUBE_TOPOGRAPHY_H
#define VISCOLUBE_TOPOGRAPHY_H

#include <stddef.h>

#include "viscolube/status.h"

#define VL_TOPOGRAPHY_MIN_POINTS 16
#define VL_TOPOGRAPHY_GRID_TOL 0.05
#define VL_TOPOGRAPHY_MAX_BYTES ((size_t)512 << 20)
#define VL_TOPOGRAPHY_TAPER 0.2

typedef enum { VL_TOPOGRAPHY_LINE = 0, VL_TOPOGRAPHY_MAP = 1 } vl_topography_kind;

/* "line scan", "height map". */
const char *vl_topography_kind_name(vl_topography_kind kind);

/* Heights as read, in SI units. */
typedef struct {
  char *source; /* the file name used in messages (owned) */
  vl_topography_kind kind;
  size_t nx, ny;     /* line: nx points, ny = 1; map: nx columns, ny rows */
  double dx_m, dy_m; /* sampling steps (line: dy_m = 0) */
  double *h_m;       /* nx * ny heights, row-major: h_m[i * nx + j] at x = j dx, y = i dy (owned) */
  int square_assumed; /* map without '# Height:': dy_m set equal to dx_m */
} vl_topography;

/* As vl_topography_read_text for the file at path; VL_EIO if unreadable. */
vl_status vl_topography_read_file(const char *path, vl_topography *out, vl_error *err);

/* Releases what a vl_topography owns and empties it (NULL or empty is fine). */
void vl_topography_free(vl_topography *t);

typedef struct {
  double taper;           /* window (step 2): tapered fraction of each axis in [0, 1]; 1 is Hann,
                             0 no window (for periodic data only) */
  double bins_per_decade; /* log bins per decade of q; in (0, 100] */
  double long_cut;        /* q_min = long_cut * 2 pi / L; >= 1 */
  double short_cut;       /* q_max = short_cut * pi / dx; in (0, 1] */
  int extend_low;         /* nonzero: step 7 */
} vl_topography_psd_options;

/* Taper VL_TOPOGRAPHY_TAPER, 10 bins per decade, long_cut 1, short_cut 0.5,
 * extend_low 1. */
vl_topography_psd_options vl_topography_psd_options_default(void);

typedef struct {
  size_t n;         /* tabulated points (>= 2) */
  double *q_per_m;  /* strictly increasing, > 0 (owned) */
  double *c_m4;     /* isotropic 2-D C(q) > 0 (owned) */
  size_t *count;    /* wavevectors (line: frequencies) averaged into each point; 0 for
                       step 7's point (owned) */
  size_t n1;        /* line scans: binned 1-D points, else 0 */
  double *q1_per_m; /* line scans: bin wavevectors (owned), else NULL */
  double *c1_m3;    /* line scans: binned 1-D C1(q) as measured (before step 6's pooling),
                       two-sided density (owned), else NULL */
  size_t n_dropped; /* line scans: points with C <= 0 after step 6 */
  double q_min_per_m, q_max_per_m; /* the band kept (step 4) */
  double tail_slope;               /* line scans: -dlnC1/dlnq beyond the last bin */
  double window_power;             /* mean(w^2) of the window (step 2) */
  int extended;                    /* step 7 added the first point */
  double hrms_topography_m;        /* rms of the detrended heights */
  double hrms_band_m;              /* rms of the power in [q_min, q_max] */
  double hrms_psd_m;               /* vl_psd_hrms of the tabulated points */
  char provenance[640];            /* one paragraph: kind, size, pixel, steps, band, rms */
} vl_topography_spectrum;

/* Estimates the isotropic 2-D PSD of t (steps 1-7 above); opt may be NULL
 * (defaults). On VL_OK *out owns its arrays (vl_topography_spectrum_free) and
 * (n, q_per_m, c_m4) pass vl_psd_init_tabulated; on failure *out is empty.
 * VL_EINPUT (bad options, heights that are a plane, fewer than 2 points in
 * the band), VL_ENOMEM. */
vl_status vl_topography_psd(const vl_topography *t, const vl_topography_psd_options *opt,
                            vl_topography_spectrum *out, vl_error *err);

/* Releases what a vl_topography_spectrum owns and empties it (NULL is fine). */
void vl_topography_spectrum_free(vl_topography_spectrum *p);

#endif
