/* Figures with PLplot's cairo drivers (plot.h).
 *
 * PLplot draws; everything a reader judges a figure by is done here: tick
 * positions and labels (PLplot's own log axes label every decade however
 * crowded), the legend (outside the data, with the very markers the plot
 * uses), gaps and hollow markers for points that did not converge.
 *
 * Output goes through a FILE we open ourselves and hand to PLplot (plsfile):
 * with only a file name PLplot retries fopen and then exits the process
 * when the file cannot be created. PLplot closes the FILE in plend1; it is
 * a second stream on the temporary of atomic_file.h, which is fsynced and
 * renamed into place afterwards. */
#include "viscolube/plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <plplot.h>

#include "viscolube/atomic_file.h"

#define PAGE_W_DEFAULT 1000
#define PAGE_H_DEFAULT 750
#define LEGEND_MAX 48
#define TOP 0.905 /* top of every layout's data area; the title is above */
#define TEXT_MAX 192

/* Text sizes as fractions of the page height (PLplot sizes text in mm).
 * Measured on the cairo drivers: a digit is about 0.88 character heights
 * wide (see text_width_ch). */
#define CH_TICK 0.0190
#define CH_TITLE 0.0210
#define CH_SUBTITLE 0.0165 /* the conditions under the title */
#define CH_LEGEND 0.0162
#define DIGIT_W 0.88 /* width of a digit in character heights */

typedef struct {
  unsigned char r, g, b;
} rgb;

static const rgb BLACK = {0, 0, 0};
static const rgb WHITE = {255, 255, 255};
static const rgb GRID = {222, 222, 222};
static const rgb GREY = {120, 120, 120};
/* Okabe & Ito's colour-blind safe set without its yellow (too pale on
 * white) and black (the axes), completed by two of Tol's. */
static const rgb PALETTE[8] = {{0, 114, 178}, {213, 94, 0},   {0, 158, 115}, {204, 121, 167},
                               {230, 159, 0}, {86, 180, 233}, {136, 34, 85}, {68, 170, 153}};

/* c mixed with white: t = 0 is c, 1 is white */
static rgb tint(rgb c, double t) {
  return (rgb){(unsigned char)lround(c.r + t * (255 - c.r)),
               (unsigned char)lround(c.g + t * (255 - c.g)),
               (unsigned char)lround(c.b + t * (255 - c.b))};
}

typedef enum { M_NONE = 0, M_CIRCLE, M_SQUARE, M_DIAMOND, M_TRIANGLE } shape;

typedef struct {
  rgb color;
  int dash;     /* PLplot line style 1..8 (1 = solid) */
  double width; /* pixels */
} style;

typedef struct {
  char text[TEXT_MAX];
  bool line;
  style st;
  shape mark;
  bool hollow; /* white inside, coloured edge */
  rgb mark_color;
} legend_entry;

typedef struct {
  double lo, hi; /* window (log axes: log10 of the values) */
  bool log;
  double step;  /* linear: tick step; log: decades between labels */
  int nsub;     /* linear: minor intervals per step */
  int decimals; /* linear: label decimals */
} axis;

/* One figure being drawn. */
typedef struct {
  double pw, ph;             /* page in mm */
  double vx0, vx1, vy0, vy1; /* data area, normalised device coordinates */
  axis x, y;
  legend_entry legend[LEGEND_MAX];
  size_t n_legend;
  size_t series, failed;
  int scratch; /* alternates the colour slots (a slot change is what makes
                  PLplot send the new colour to the driver) */
} fig;

/* ---- small helpers ----------------------------------------------------- */

static void set_color(fig *f, rgb c) {
  f->scratch = f->scratch == 14 ? 15 : 14;
  plscol0(f->scratch, c.r, c.g, c.b);
  plcol0(f->scratch);
}

static void set_style(fig *f, style st) {
  set_color(f, st.color);
  pllsty(st.dash);
  plwidth(st.width);
}

static void set_ch(const fig *f, double frac) { plschr(frac * f->ph, 1.0); }

/* Copies plain text for PLplot: '#' is its escape character. */
static void plain_text(char *dst, size_t size, const char *src) {
  size_t j = 0;
  for (size_t i = 0; src && src[i] && j + 2 < size; i++) {
    if (src[i] == '#') dst[j++] = '#';
    dst[j++] = src[i];
  }
  dst[j] = '\0';
}

/* Width of UTF-8 text in character heights, escapes not counted. The
 * cairo drivers set fonts at about 1.38 character heights per em; widths in
 * em are DejaVu Sans's, by class (narrow, digits and most letters, wide). */
static double text_width_ch(const char *s) {
  double em = 0, scale = 1;
  for (size_t i = 0; s[i]; i++) {
    unsigned char c = (unsigned char)s[i];
    if ((c & 0xC0) == 0x80) continue; /* continuation byte */
    if (c == '#' && s[i + 1] && s[i + 1] != '#') {
      char e = s[++i];
      if (e == 'u' || e == 'd') scale = scale < 1 ? 1 : 0.7; /* sub/superscript and back */
      if (e == '<')
        while (s[i + 1] && s[i] != '>')
          i++;
      continue;
    }
    if (c == '#') i++;
    double w;
    if (strchr("ijlt.,:;!|' ()[]f/r-", c))
      w = 0.34;
    else if (c >= '0' && c <= '9')
      w = 0.64;
    else if (strchr("mwMW", c))
      w = 0.90;
    else if (c >= 'A' && c <= 'Z')
      w = 0.72;
    else
      w = 0.60;
    em += scale * w;
  }
  return 1.38 * em;
}

static void add_legend(fig *f, const char *text, bool line, style st, shape mark, bool hollow,
                       rgb mark_color) {
  if (f->n_legend >= LEGEND_MAX) return;
  legend_entry *e = &f->legend[f->n_legend++];
  snprintf(e->text, sizeof e->text, "%.*s", (int)sizeof e->text - 1, text);
  e->line = line;
  e->st = st;
  e->mark = mark;
  e->hollow = hollow;
  e->mark_color = mark_color;
}

/* ---- numbers ----------------------------------------------------------- */

static const char *const SUPERSCRIPT[10] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};

size_t vl_plot_format_value(char *buf, size_t size, double v) {
  if (!buf || size == 0) return 0;
  const char *sign = v < 0 ? "−" : ""; /* a true minus sign */
  double a = fabs(v);
  int n;
  if (!isfinite(v)) {
    n = snprintf(buf, size, "%s", isnan(v) ? "NaN" : v > 0 ? "∞" : "−∞");
  } else if (a == 0 || (a >= 1e-3 && a < 1e4)) {
    /* three significant digits without an exponent ("%.3g" gives 1.5e+03),
       trailing zeros dropped */
    int decimals = a == 0 ? 0 : 2 - (int)floor(log10(a));
    char tmp[64];
    snprintf(tmp, sizeof tmp, "%.*f", decimals < 0 ? 0 : decimals, a);
    if (strchr(tmp, '.')) {
      size_t len = strlen(tmp);
      while (len > 0 && tmp[len - 1] == '0')
        tmp[--len] = '\0';
      if (len > 0 && tmp[len - 1] == '.') tmp[--len] = '\0';
    }
    n = snprintf(buf, size, "%s%s", sign, tmp);
  } else {
    int e = (int)floor(log10(a));
    double m = a / pow(10.0, e);
    if (m >= 9.995) { /* rounding carried into the next decade */
      m /= 10;
      e++;
    }
    char mant[32] = "";
    if (fabs(m - 1.0) >= 0.005) snprintf(mant, sizeof mant, "%.3g×", m);
    char ex[64] = "";
    size_t k = 0;
    if (e < 0) k += (size_t)snprintf(ex + k, sizeof ex - k, "⁻");
    char digits[16];
    snprintf(digits, sizeof digits, "%d", abs(e));
    for (size_t i = 0; digits[i] && k + 4 < sizeof ex; i++)
      k += (size_t)snprintf(ex + k, sizeof ex - k, "%s", SUPERSCRIPT[digits[i] - '0']);
    n = snprintf(buf, size, "%s%s10%s", sign, mant, ex);
  }
  if (n < 0) {
    buf[0] = '\0';
    return 0;
  }
  return (size_t)n < size ? (size_t)n : size - 1;
}

/* A "nice" step (1, 2, 2.5 or 5 times a power of ten) of at least raw. */
static double nice_step(double raw, int *nsub) {
  double p = pow(10.0, floor(log10(raw)));
  double m = raw / p;
  double s;
  if (m <= 1.0 + 1e-9)
    s = 1, *nsub = 5;
  else if (m <= 2.0 + 1e-9)
    s = 2, *nsub = 4;
  else if (m <= 2.5 + 1e-9)
    s = 2.5, *nsub = 5;
  else if (m <= 5.0 + 1e-9)
    s = 5, *nsub = 5;
  else
    s = 10, *nsub = 5;
  return s * p;
}

static int step_decimals(double step) {
  for (int d = 0; d < 12; d++) {
    double s = step * pow(10.0, d);
    if (fabs(s - round(s)) < 1e-6 * s) return d;
  }
  return 12;
}

/* Tick label of a linear axis, with a true minus sign. */
static void linear_label(char *buf, size_t size, double v, int decimals) {
  if (fabs(v) < 1e-12) v = 0;
  snprintf(buf, size, "%s%.*f", v < 0 ? "−" : "", decimals, fabs(v));
}

static void log_label(char *buf, size_t size, int decade) {
  if (decade == 0)
    snprintf(buf, size, "1");
  else if (decade == 1)
    snprintf(buf, size, "10");
  else
    snprintf(buf, size, "10#u%s%d#d", decade < 0 ? "−" : "", abs(decade));
}

/* Linear axis over the data range [lo, hi] on len_mm of paper: the
 * smallest nice step whose labels do not crowd (at most ~9 ticks). tight:
 * the window is the data range (a spatial domain), else it is widened to
 * the next minor ticks. */
static axis linear_axis(double lo, double hi, double len_mm, double ch_mm, bool tight,
                        bool vertical) {
  axis a = {0};
  if (!isfinite(lo) || !isfinite(hi)) lo = 0, hi = 1;
  if (!(hi > lo)) {
    double d = fabs(lo) > 0 ? 0.1 * fabs(lo) : 1.0;
    lo -= d;
    hi += d;
  }
  double raw = (hi - lo) / 8.0;
  for (int it = 0; it < 40; it++) {
    a.step = nice_step(raw, &a.nsub);
    a.decimals = step_decimals(a.step);
    /* not tight: widened to the next minor tick, not a whole step */
    double minor = a.step / a.nsub;
    a.lo = tight ? lo : floor(lo / minor + 1e-9) * minor;
    a.hi = tight ? hi : ceil(hi / minor - 1e-9) * minor;
    /* widest label against the room each one gets */
    double need = 0;
    for (int s = -1; s <= 1; s += 2) {
      char buf[64];
      linear_label(buf, sizeof buf, s < 0 ? a.lo : a.hi, a.decimals);
      double w = text_width_ch(buf);
      if (w > need) need = w;
    }
    need = vertical ? 2.2 * ch_mm : (need + 1.5) * ch_mm;
    double room = len_mm * a.step / (a.hi - a.lo);
    if (room >= need) break;
    raw = a.step * 1.0001;
  }
  return a;
}

/* Logarithmic axis over positive data [lo, hi]: whole decades, labels
 * every 1, 2, 3, 4, 5 or 10 decades, whichever is the first not to crowd. */
static axis log_axis(double lo, double hi, double len_mm, double ch_mm, bool vertical) {
  axis a = {0};
  a.log = true;
  if (!(lo > 0) || !(hi >= lo) || !isfinite(hi)) lo = 1, hi = 10;
  a.lo = floor(log10(lo) + 1e-9);
  a.hi = ceil(log10(hi) - 1e-9);
  if (a.hi - a.lo < 1) a.hi = a.lo + 1;
  double per_decade = len_mm / (a.hi - a.lo);
  /* "10^-12": two digits and up to three superscript characters */
  double need = vertical ? 2.4 * ch_mm : (2 * DIGIT_W + 3 * 0.7 * DIGIT_W + 1.5) * ch_mm;
  static const int steps[] = {1, 2, 3, 4, 5, 10, 20};
  a.step = 20;
  for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++)
    if (steps[i] * per_decade >= need) {
      a.step = steps[i];
      break;
    }
  return a;
}

/* ---- coordinates ------------------------------------------------------- */

static double to_wx(const fig *f, double v) { return f->x.log ? (v > 0 ? log10(v) : NAN) : v; }
static double to_wy(const fig *f, double v) { return f->y.log ? (v > 0 ? log10(v) : NAN) : v; }

/* World units per mm on the page, in x and in y. */
static double wx_per_mm(const fig *f) { return (f->x.hi - f->x.lo) / ((f->vx1 - f->vx0) * f->pw); }
static double wy_per_mm(const fig *f) { return (f->y.hi - f->y.lo) / ((f->vy1 - f->vy0) * f->ph); }

static void use_data_area(const fig *f) {
  plvpor(f->vx0, f->vx1, f->vy0, f->vy1);
  plwind(f->x.lo, f->x.hi, f->y.lo, f->y.hi);
}

/* ---- axes -------------------------------------------------------------- */

static void segment(double x0, double y0, double x1, double y1) {
  PLFLT xs[2] = {x0, x1}, ys[2] = {y0, y1};
  plline(2, xs, ys);
}

/* Calls fn(value, major) for the ticks of axis a. */
static void for_ticks(const axis *a, void (*fn)(void *, double, bool, bool), void *user) {
  if (a->log) {
    int d0 = (int)a->lo, d1 = (int)a->hi;
    double decades = a->hi - a->lo;
    bool minors = decades <= 8 || a->step == 1;
    for (int d = d0; d <= d1; d++) {
      bool labelled = ((d % (int)a->step) + (int)a->step) % (int)a->step == 0;
      fn(user, d, true, labelled);
      if (d < d1 && minors && decades <= 14)
        for (int m = 2; m <= 9; m++)
          fn(user, d + log10(m), false, false);
    }
  } else {
    if (!(a->step > 0) || (a->hi - a->lo) / a->step > 1000) return;
    double minor = a->step / a->nsub;
    /* multiples of the step by an integer: no drift from repeated sums */
    for (long k = (long)ceil(a->lo / a->step - 1e-9) - 1;; k++) {
      double v = (double)k * a->step;
      if (v > a->hi + 1e-9 * a->step) break;
      if (v >= a->lo - 1e-9 * a->step) fn(user, v, true, true);
      for (int m = 1; m < a->nsub; m++) {
        double w = v + m * minor;
        if (w > a->lo + 1e-9 * a->step && w < a->hi - 1e-9 * a->step) fn(user, w, false, false);
      }
    }
  }
}

typedef struct {
  fig *f;
  bool is_x;
  bool labels;
  double max_label_ch; /* y: widest label, for the title's distance */
} tick_ctx;

static void grid_line(void *user, double v, bool major, bool labelled) {
  tick_ctx *t = user;
  if (!major || !labelled) return;
  const fig *f = t->f;
  if (t->is_x) {
    if (v > f->x.lo && v < f->x.hi) segment(v, f->y.lo, v, f->y.hi);
  } else if (v > f->y.lo && v < f->y.hi) {
    segment(f->x.lo, v, f->x.hi, v);
  }
}

static void tick_mark(void *user, double v, bool major, bool labelled) {
  tick_ctx *t = user;
  const fig *f = t->f;
  double len = major ? 2.2 : 1.2; /* mm */
  if (t->is_x) {
    if (v < f->x.lo - 1e-9 || v > f->x.hi + 1e-9) return;
    double d = len * wy_per_mm(f);
    segment(v, f->y.lo, v, f->y.lo + d);
    segment(v, f->y.hi, v, f->y.hi - d);
  } else {
    if (v < f->y.lo - 1e-9 || v > f->y.hi + 1e-9) return;
    double d = len * wx_per_mm(f);
    segment(f->x.lo, v, f->x.lo + d, v);
    segment(f->x.hi, v, f->x.hi - d, v);
  }
  if (!labelled || !t->labels) return;
  const axis *a = t->is_x ? &f->x : &f->y;
  char buf[64];
  if (a->log)
    log_label(buf, sizeof buf, (int)lround(v));
  else
    linear_label(buf, sizeof buf, v, a->decimals);
  double pos = (v - a->lo) / (a->hi - a->lo);
  if (t->is_x) {
    plmtex("b", 1.5, pos, 0.5, buf);
  } else {
    plmtex("lv", 0.7, pos, 1.0, buf);
    double w = text_width_ch(buf) + (a->log ? 0.6 : 0);
    if (w > t->max_label_ch) t->max_label_ch = w;
  }
}

static void label_width(void *user, double v, bool major, bool labelled) {
  tick_ctx *t = user;
  const axis *a = &t->f->y;
  if (!major || !labelled || v < a->lo - 1e-9 || v > a->hi + 1e-9) return;
  char buf[64];
  if (a->log)
    log_label(buf, sizeof buf, (int)lround(v));
  else
    linear_label(buf, sizeof buf, v, a->decimals);
  double w = text_width_ch(buf) + (a->log ? 0.6 : 0);
  if (w > t->max_label_ch) t->max_label_ch = w;
}

/* Widens the left margin when the y tick labels and the y title would not
 * fit in it (labels with many decimals); never narrows it, so panels drawn
 * one after the other can share the widest. */
static void fit_left_margin(fig *f) {
  tick_ctx t = {f, false, true, 0};
  for_ticks(&f->y, label_width, &t);
  double need = ((0.7 + t.max_label_ch) * CH_TICK + 2.4 * CH_TITLE) * f->ph + 2.0; /* mm */
  if (need > f->vx0 * f->pw) f->vx0 = need / f->pw;
}

/* Grid, frame, ticks, tick labels and axis titles of the data area.
 * x_labels false: no x tick labels nor title (upper panel). */
static void draw_axes(fig *f, const char *xtitle, const char *ytitle, bool x_labels) {
  fit_left_margin(f);
  use_data_area(f);
  pllsty(1);
  plwidth(1.0);
  set_color(f, GRID);
  tick_ctx gx = {f, true, false, 0}, gy = {f, false, false, 0};
  for_ticks(&f->x, grid_line, &gx);
  for_ticks(&f->y, grid_line, &gy);
  set_color(f, BLACK);
  plwidth(1.2);
  plbox("bc", 0, 0, "bc", 0, 0);
  set_ch(f, CH_TICK);
  tick_ctx tx = {f, true, x_labels, 0}, ty = {f, false, true, 0};
  for_ticks(&f->x, tick_mark, &tx);
  for_ticks(&f->y, tick_mark, &ty);
  set_ch(f, CH_TITLE);
  /* the distances below are in title character heights */
  double r = CH_TICK / CH_TITLE;
  if (x_labels && xtitle) plmtex("b", 3.3, 0.5, 0.5, xtitle);
  if (ytitle) plmtex("l", (0.7 + ty.max_label_ch) * r + 1.45, 0.5, 0.5, ytitle);
}

/* ---- markers and curves ------------------------------------------------ */

/* A marker of size mm (across) at world (wx, wy). */
static void draw_marker(fig *f, double wx, double wy, shape s, double size_mm, rgb fill, rgb edge,
                        bool filled) {
  if (s == M_NONE || !isfinite(wx) || !isfinite(wy)) return;
  PLFLT xs[33], ys[33];
  int n = 0;
  double rx = 0.5 * size_mm * wx_per_mm(f), ry = 0.5 * size_mm * wy_per_mm(f);
  switch (s) {
  case M_CIRCLE:
    n = 24;
    for (int i = 0; i < n; i++) {
      double t = 2 * M_PI * i / n;
      xs[i] = wx + rx * cos(t);
      ys[i] = wy + ry * sin(t);
    }
    break;
  case M_SQUARE:
    n = 4;
    for (int i = 0; i < 4; i++) {
      xs[i] = wx + 0.85 * rx * ((i == 0 || i == 3) ? -1 : 1);
      ys[i] = wy + 0.85 * ry * (i < 2 ? -1 : 1);
    }
    break;
  case M_DIAMOND:
    n = 4;
    for (int i = 0; i < 4; i++) {
      double t = M_PI / 2 * i;
      xs[i] = wx + 1.15 * rx * cos(t);
      ys[i] = wy + 1.15 * ry * sin(t);
    }
    break;
  case M_TRIANGLE:
    n = 3;
    for (int i = 0; i < 3; i++) {
      double t = M_PI / 2 + 2 * M_PI / 3 * i;
      xs[i] = wx + 1.1 * rx * cos(t);
      ys[i] = wy + 1.1 * ry * (sin(t) + 0.2);
    }
    break;
  default: return;
  }
  xs[n] = xs[0];
  ys[n] = ys[0];
  pllsty(1);
  plwidth(1.0); /* the driver strokes a fill's edge with the current pen */
  set_color(f, filled ? fill : WHITE);
  plfill(n, xs, ys);
  set_color(f, edge);
  plwidth(1.5);
  plline(n + 1, xs, ys);
}

/* Joins consecutive finite points of (wx, wy) (world coordinates); NaN
 * breaks the line. A finite point between two gaps gets a dot so that it
 * is seen. */
static void draw_runs(fig *f, size_t n, const double *wx, const double *wy, style st) {
  size_t i = 0;
  while (i < n) {
    while (i < n && !(isfinite(wx[i]) && isfinite(wy[i])))
      i++;
    size_t j = i;
    while (j < n && isfinite(wx[j]) && isfinite(wy[j]))
      j++;
    if (j - i >= 2) {
      set_style(f, st);
      plline((PLINT)(j - i), wx + i, wy + i);
    } else if (j - i == 1) {
      draw_marker(f, wx[i], wy[i], M_CIRCLE, 1.6, st.color, st.color, true);
    }
    i = j;
  }
}

/* Hollow markers for the points that did not converge, on a row just above
 * the x axis (row k for the k-th curve, so curves do not hide each other). */
static size_t draw_failed(fig *f, size_t n, const double *wx, const bool *ok, rgb color, int row) {
  size_t count = 0;
  double wy = f->y.lo + (3.2 + 2.6 * row) * wy_per_mm(f);
  for (size_t i = 0; i < n; i++) {
    if (ok[i] || !isfinite(wx[i])) continue;
    draw_marker(f, wx[i], wy, M_CIRCLE, 2.6, WHITE, color, false);
    count++;
  }
  return count;
}

/* Hollow squares on the curve at the points that converged but are not
 * known to their error target (vl_point_unreliable): drawn where the value
 * is, unlike a failed point, and in another shape, so the two read apart. */
static size_t draw_unreliable(fig *f, size_t n, const double *wx, const double *wy,
                              const vl_point *pts, rgb color) {
  size_t count = 0;
  for (size_t i = 0; i < n; i++) {
    if (!vl_point_unreliable(&pts[i]) || !isfinite(wx[i]) || !isfinite(wy[i])) continue;
    draw_marker(f, wx[i], wy[i], M_SQUARE, 2.8, WHITE, color, false);
    count++;
  }
  return count;
}

static const char *UNRELIABLE_TEXT = "above its error target";

/* ---- legend, title ----------------------------------------------------- */

#define LEGEND_X0 0.715

static void draw_legend(fig *f, double top) {
  if (f->n_legend == 0) return;
  double x0 = LEGEND_X0, x1 = 0.995;
  plvpor(x0, x1, f->vy0, top);
  /* world = mm from the legend's top-left corner */
  double wmm = (x1 - x0) * f->pw, hmm = (top - f->vy0) * f->ph;
  plwind(0, wmm, -hmm, 0);
  double ch = CH_LEGEND * f->ph;
  set_ch(f, CH_LEGEND);
  double row = 1.9 * ch, sample = 2.6 * ch;
  /* room for the text: long labels are cut with an ellipsis */
  double room_ch = (wmm - sample - 1.2 * ch) / ch;
  fig lf = *f; /* markers are sized in mm: a frame of the legend's window */
  lf.vx0 = x0;
  lf.vx1 = x1;
  lf.vy0 = f->vy0;
  lf.vy1 = top;
  lf.x = (axis){.lo = 0, .hi = wmm};
  lf.y = (axis){.lo = -hmm, .hi = 0};
  for (size_t i = 0; i < f->n_legend; i++) {
    const legend_entry *e = &f->legend[i];
    double y = -((double)i + 0.7) * row;
    if (-y > hmm) break;
    if (e->line) {
      set_style(&lf, e->st);
      segment(0.2 * ch, y, sample, y);
    }
    if (e->mark != M_NONE)
      draw_marker(&lf, 0.5 * (0.2 * ch + sample), y, e->mark, e->hollow ? 2.6 : 2.2, e->mark_color,
                  e->mark_color, !e->hollow);
    set_color(&lf, BLACK);
    char text[TEXT_MAX + 8];
    snprintf(text, sizeof text, "%s", e->text);
    if (text_width_ch(text) > room_ch) {
      /* cut at a character boundary */
      size_t len = strlen(text);
      while (len > 0 && text_width_ch(text) > room_ch - 1) {
        do
          len--;
        while (len > 0 && ((unsigned char)text[len] & 0xC0) == 0x80);
        text[len] = '\0';
      }
      strcat(text, "…");
    }
    plptex(sample + 1.0 * ch, y, 1, 0, 0, text);
  }
  f->scratch = lf.scratch;
}

/* One line of text centred at height y of the band above the plot area,
 * cut (at a character boundary) to the width of the page. */
static void band_line(fig *f, const char *text, double y, double ch) {
  char t[TEXT_MAX];
  plain_text(t, sizeof t, text);
  set_ch(f, ch);
  double room = 0.94 * f->pw / (ch * f->ph);
  while (text_width_ch(t) > room && strlen(t) > 4) {
    size_t len = strlen(t);
    do
      len--;
    while (len > 0 && ((unsigned char)t[len] & 0xC0) == 0x80);
    t[len] = '\0';
  }
  plptex(0.5, y, 1, 0, 0.5, t);
}

/* The title, and under it the subtitle (the conditions) in smaller grey
 * type; either may be absent. */
static void draw_title(fig *f, const char *title, const char *subtitle) {
  bool has_title = title && title[0], has_sub = subtitle && subtitle[0];
  if (!has_title && !has_sub) return;
  plvpor(0.03, 0.97, TOP, 0.99);
  plwind(0, 1, 0, 1);
  set_color(f, BLACK);
  /* two lines: the title high in the band, the subtitle clear of the
   * top tick label of the y axis */
  if (has_title) band_line(f, title, has_sub ? 0.80 : 0.45, CH_TITLE);
  set_color(f, GREY);
  if (has_sub) band_line(f, subtitle, has_title ? 0.40 : 0.45, CH_SUBTITLE);
}

/* ---- output ------------------------------------------------------------ */

static char abort_msg[VL_ERROR_MAX];

/* PLplot's recoverable errors: kept instead of printed. */
static void on_abort(PLCHAR_VECTOR msg) {
  if (!abort_msg[0]) snprintf(abort_msg, sizeof abort_msg, "%s", msg ? msg : "error");
}

bool vl_plot_available(vl_error *err) {
  PLCHAR_VECTOR menu[128], names[128];
  PLCHAR_VECTOR *pm = menu, *pn = names;
  int nd = 128;
  plgDevs(&pm, &pn, &nd);
  bool png = false, svg = false;
  for (int i = 0; i < nd; i++) {
    if (!strcmp(names[i], "pngcairo")) png = true;
    if (!strcmp(names[i], "svgcairo")) svg = true;
  }
  if (!png || !svg)
    vl_error_set(err, "PLplot has no %s driver (Debian package plplot-driver-cairo)",
                 !png ? "pngcairo" : "svgcairo");
  return png && svg;
}

void vl_plot_options_defaults(vl_plot_options *opt) {
  *opt = (vl_plot_options){
      VL_PLOT_PNG | VL_PLOT_SVG, PAGE_W_DEFAULT, PAGE_H_DEFAULT, NULL, false, NULL};
}

/* True when the file ends as a complete PNG (IEND chunk) or SVG does. */
static bool file_complete(const char *path, bool png) {
  FILE *f = fopen(path, "rb");
  if (!f) return false;
  unsigned char head[8] = {0}, tail[16] = {0};
  bool ok =
      fread(head, 1, 8, f) == 8 && fseek(f, -12, SEEK_END) == 0 && fread(tail, 1, 12, f) == 12;
  fclose(f);
  if (!ok) return false;
  if (png)
    return !memcmp(head, "\x89PNG\r\n\x1a\n", 8) && !memcmp(tail + 4, "IEND\xae\x42\x60\x82", 8);
  return strstr((const char *)tail, "</svg>") != NULL;
}

/* text with the five XML specials escaped, appended to f. */
static void xml_text(FILE *f, const char *text) {
  for (const char *c = text; *c; c++) {
    switch (*c) {
    case '&': fputs("&amp;", f); break;
    case '<': fputs("&lt;", f); break;
    case '>': fputs("&gt;", f); break;
    case '"': fputs("&quot;", f); break;
    case '\'': fputs("&apos;", f); break;
    default: fputc(*c, f);
    }
  }
}

/* The SVG's own <title> and <desc>, the figure's title and subtitle as
 * text (the drawn ones are glyph outlines): what a browser shows as the
 * page's name, what a search or a test finds. Inserted right after the
 * opening <svg ...> tag by rewriting the temporary whole (PLplot has
 * closed its stream; af->f has written nothing and stands at the start
 * when rewound). A figure written directly (a device, af->tmp empty) is
 * left as drawn. */
static vl_status svg_name(vl_atomic_file *af, const vl_plot_options *opt, vl_error *err) {
  bool has_title = opt->title && opt->title[0], has_sub = opt->subtitle && opt->subtitle[0];
  if (!af->tmp[0] || (!has_title && !has_sub)) return VL_OK;
  FILE *in = fopen(af->tmp, "rb");
  char *text = NULL;
  long len = -1;
  if (in && fseek(in, 0, SEEK_END) == 0 && (len = ftell(in)) > 0 && fseek(in, 0, SEEK_SET) == 0 &&
      (text = malloc((size_t)len + 1)) && fread(text, 1, (size_t)len, in) == (size_t)len)
    text[len] = '\0';
  else
    len = -1;
  if (in) fclose(in);
  char *svg = len > 0 ? strstr(text, "<svg") : NULL;
  char *end = svg ? strchr(svg, '>') : NULL;
  if (!end) {
    free(text);
    vl_error_set(err, "%s: cannot read back the SVG to name it", af->path);
    return VL_EIO;
  }
  size_t head = (size_t)(end + 1 - text);
  rewind(af->f);
  fwrite(text, 1, head, af->f);
  if (has_title) {
    fputs("\n<title>", af->f);
    xml_text(af->f, opt->title);
    fputs("</title>", af->f);
  }
  if (has_sub) {
    fputs("\n<desc>", af->f);
    xml_text(af->f, opt->subtitle);
    fputs("</desc>", af->f);
  }
  fwrite(text + head, 1, (size_t)len - head, af->f); /* longer than before: nothing left over */
  free(text);
  return VL_OK; /* a failed write shows in vl_atomic_file_commit */
}

typedef void (*draw_fn)(fig *f, const void *ctx);

/* A second stream on af's open file, for PLplot, which closes the stream
 * it is given (in plend1) while af must stay open to be fsynced and
 * renamed. NULL when out of descriptors. */
static FILE *plplot_stream(const vl_atomic_file *af) {
  int fd = dup(fileno(af->f));
  FILE *fp = fd >= 0 ? fdopen(fd, "wb") : NULL;
  if (!fp && fd >= 0) close(fd);
  return fp;
}

/* Draws one figure into path with the PLplot device dev, through a
 * temporary renamed into place once PLplot has reported no error and the
 * file ends as a complete PNG (png) or SVG does. */
static vl_status draw_file(const char *path, const char *dev, bool png, const vl_plot_options *opt,
                           draw_fn draw, const void *ctx, fig *f, vl_error *err) {
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  FILE *fp = plplot_stream(&af);
  if (!fp) {
    vl_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    vl_atomic_file_abort(&af);
    return VL_EIO;
  }
  abort_msg[0] = '\0';
  plsabort(on_abort);
  PLINT strm;
  plmkstrm(&strm);
  plsdev(dev);
  plsfile(fp); /* PLplot owns fp from here and closes it in plend1 */
  plspage(0, 0, opt->width_px, opt->height_px, 0, 0);
  plscolbg(255, 255, 255);
  plinit();
  pladv(0); /* exactly once: a second page is dropped with a warning */
  PLFLT x0, x1, y0, y1;
  plgspa(&x0, &x1, &y0, &y1);
  f->pw = x1 - x0;
  f->ph = y1 - y0;
  f->scratch = 14;
  draw(f, ctx);
  draw_title(f, opt->title, opt->subtitle);
  plend1();
  plsabort(NULL);
  if (abort_msg[0]) {
    vl_atomic_file_abort(&af);
    vl_error_set(err, "%s: PLplot: %s", path, abort_msg);
    return VL_EINTERNAL;
  }
  if (!file_complete(af.tmp, png)) {
    vl_atomic_file_abort(&af);
    vl_error_set(err, "%s: write failed (file incomplete)", path);
    return VL_EIO;
  }
  if (!png && svg_name(&af, opt, err) != VL_OK) {
    vl_atomic_file_abort(&af);
    return VL_EIO;
  }
  return vl_atomic_file_commit(&af, err);
}

/* Draws the figure once per selected format into stem.EXT; kind (what the
 * figure shows: "Stribeck curve") is its title when the caller gives none,
 * so that no figure goes out without one. */
static vl_status render(const char *stem, const vl_plot_options *opt_in, const char *kind,
                        draw_fn draw, const void *ctx, vl_plot_report *rep, vl_error *err) {
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  if (opt_in) opt = *opt_in;
  if (!opt.title || !opt.title[0]) opt.title = kind;
  if (!opt.formats) opt.formats = VL_PLOT_PNG | VL_PLOT_SVG;
  if (opt.width_px <= 0) opt.width_px = PAGE_W_DEFAULT;
  if (opt.height_px <= 0) opt.height_px = PAGE_H_DEFAULT;
  if (!stem || !stem[0]) {
    vl_error_set(err, "plot: no file name");
    return VL_EINPUT;
  }
  if (opt.width_px < 200 || opt.height_px < 150 || opt.width_px > 10000 || opt.height_px > 10000) {
    vl_error_set(err, "plot: size %dx%d outside 200x150 .. 10000x10000", opt.width_px,
                 opt.height_px);
    return VL_EINPUT;
  }
  if (!vl_plot_available(err)) return VL_EIO;
  vl_plot_report r = {0};
  snprintf(r.title, sizeof r.title, "%s", opt.title);
  static const struct {
    unsigned flag;
    const char *ext, *dev;
  } formats[] = {{VL_PLOT_PNG, "png", "pngcairo"}, {VL_PLOT_SVG, "svg", "svgcairo"}};
  for (size_t k = 0; k < 2; k++) {
    if (!(opt.formats & formats[k].flag)) continue;
    char path[4200];
    snprintf(path, sizeof path, "%s.%s", stem, formats[k].ext);
    fig f = {0};
    vl_status st =
        draw_file(path, formats[k].dev, formats[k].flag == VL_PLOT_PNG, &opt, draw, ctx, &f, err);
    if (st != VL_OK) return st;
    r.series = f.series;
    r.failed_markers = f.failed;
    r.x_lo = f.x.log ? pow(10.0, f.x.lo) : f.x.lo;
    r.x_hi = f.x.log ? pow(10.0, f.x.hi) : f.x.hi;
    r.files++;
  }
  if (rep) *rep = r;
  return VL_OK;
}

/* ---- curves: shared pieces --------------------------------------------- */

static const char *x_title(vl_sweep_quantity q) {
  switch (q) {
  case VL_SWEEP_V0_ETA: return "#<0x11>v#<0x01>#d0#u#<0x11>η#<0x01> (Pa m)";
  case VL_SWEEP_DEBORAH: return "#<0x11>v#<0x01>#d0#u#<0x11>τ#<0x01>/#<0x11>a#<0x01>#d0#u";
  default: return "#<0x11>v#<0x01>#d0#u (m/s)";
  }
}

/* The sweep coordinate of a point (NAN when undefined). */
static double x_value(const vl_point *p, const vl_curve_meta *m, vl_sweep_quantity q) {
  switch (q) {
  case VL_SWEEP_V0_ETA: return m->eta_pa_s > 0 ? p->v0_m_s * m->eta_pa_s : NAN;
  case VL_SWEEP_DEBORAH: return m->tau_s > 0 && m->a0_m > 0 ? p->v0_m_s * m->tau_s / m->a0_m : NAN;
  default: return p->v0_m_s;
  }
}

static vl_status check_curve(size_t n, const vl_point *pts, const vl_curve_meta *meta,
                             vl_sweep_quantity q, const char *what, vl_error *err) {
  if (n == 0 || !pts || !meta) {
    vl_error_set(err, "plot: %s has no points", what);
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++) {
    double x = x_value(&pts[i], meta, q);
    if (!(x > 0) || !isfinite(x)) {
      vl_error_set(err, "plot: %s: %s is not defined (or not positive) at point %zu", what,
                   vl_sweep_quantity_name(q), i);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

static vl_status check_marks(size_t n, size_t n_marks, const size_t *marks, vl_error *err) {
  if (n_marks && !marks) {
    vl_error_set(err, "plot: %zu marks but no array", n_marks);
    return VL_EINPUT;
  }
  for (size_t j = 0; j < n_marks; j++)
    if (marks[j] >= n) {
      vl_error_set(err, "plot: mark %zu at point %zu of %zu", j + 1, marks[j], n);
      return VL_EINPUT;
    }
  return VL_OK;
}

/* Range of the finite values of v[0..n) (NAN, NAN when none). */
static void range_of(size_t n, const double *v, double *lo, double *hi) {
  *lo = NAN;
  *hi = NAN;
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(v[i])) continue;
    if (!(v[i] >= *lo)) *lo = v[i];
    if (!(v[i] <= *hi)) *hi = v[i];
  }
}

/* Layout of a one-panel figure with a legend on the right. */
static void layout_single(fig *f) {
  f->vx0 = 0.105;
  f->vx1 = 0.69;
  f->vy0 = 0.115;
  f->vy1 = TOP;
}

static double len_x(const fig *f) { return (f->vx1 - f->vx0) * f->pw; }
static double len_y(const fig *f) { return (f->vy1 - f->vy0) * f->ph; }

/* The x axis of a sweep: logarithmic over the points' range. */
static void sweep_x_axis(fig *f, size_t n, const double *xv) {
  double lo, hi;
  range_of(n, xv, &lo, &hi);
  f->x = log_axis(lo, hi, len_x(f), CH_TICK * f->ph, false);
}

/* A linear y axis over [lo, hi] widened by a margin, zero included when
 * the data come near it. */
static void value_y_axis(fig *f, double lo, double hi, bool with_zero) {
  if (!isfinite(lo)) lo = 0, hi = 1;
  /* round-off around zero (-1e-17) is zero */
  if (lo < 0 && -lo < 1e-6 * (hi - lo)) lo = 0;
  if (hi > 0 && hi < 1e-6 * (hi - lo)) hi = 0;
  if (with_zero) {
    if (lo > 0 && lo < 0.5 * hi) lo = 0;
    if (hi < 0 && hi > 0.5 * lo) hi = 0;
  }
  double pad = 0.04 * (hi - lo);
  f->y = linear_axis(lo - (lo == 0 ? 0 : pad), hi + pad, len_y(f), CH_TICK * f->ph, false, true);
}

/* Numbered marks (1..n_marks) at marks[j] on the curve (wx, wy): a dot and
 * its number above it, or below when it would leave the frame or sit on
 * the previous number; right-aligned at the right edge. */
static void draw_numbered_marks(fig *f, size_t n_marks, const size_t *marks, const double *wx,
                                const double *wy) {
  set_ch(f, CH_LEGEND);
  double ch = CH_LEGEND * f->ph, mx = wx_per_mm(f), my = wy_per_mm(f);
  double prev_x = NAN, prev_y = NAN; /* where the previous number went */
  for (size_t j = 0; j < n_marks; j++) {
    size_t i = marks[j];
    if (!isfinite(wx[i]) || !isfinite(wy[i])) continue;
    draw_marker(f, wx[i], wy[i], M_CIRCLE, 2.0, BLACK, BLACK, true);
    double just = 0.5, x = wx[i];
    if ((f->x.hi - wx[i]) / mx < 0.8 * ch) just = 1.0, x -= 1.2 * mx;
    if ((wx[i] - f->x.lo) / mx < 0.8 * ch) just = 0.0, x += 1.2 * mx;
    /* plptex centres the text vertically at y: above the dot, else below */
    double off = (2.4 + 0.5 * ch) * my;
    double y = wy[i] + off;
    bool clash =
        isfinite(prev_x) && fabs(x - prev_x) / mx < 1.3 * ch && fabs(y - prev_y) / my < 1.3 * ch;
    if (clash || y + 0.6 * ch * my > f->y.hi) y = wy[i] - off;
    prev_x = x;
    prev_y = y;
    char num[24];
    snprintf(num, sizeof num, "%d", (int)(j + 1));
    set_color(f, BLACK);
    plptex(x, y, 1, 0, just, num);
  }
}

/* Where the fluid share of the load crosses 0.5 going up (interpolated in
 * the plotted x); false when it does not. */
static bool half_load_at(size_t n, const vl_point *pts, const double *wx, const double *wy,
                         double *hx, double *hy) {
  for (size_t i = 0; i + 1 < n; i++) {
    if (!pts[i].converged || !pts[i + 1].converged) continue;
    double a = pts[i].fluid_load_fraction, b = pts[i + 1].fluid_load_fraction;
    if (a < 0.5 && b >= 0.5 && isfinite(wx[i]) && isfinite(wx[i + 1]) && isfinite(wy[i]) &&
        isfinite(wy[i + 1])) {
      double t = (0.5 - a) / (b - a);
      *hx = wx[i] + t * (wx[i + 1] - wx[i]);
      *hy = wy[i] + t * (wy[i + 1] - wy[i]);
      return true;
    }
  }
  return false;
}

static const char *HALF_LOAD_TEXT = "fluid load = 50 %";
static const char *FAILED_TEXT = "not converged";

/* ---- Stribeck ---------------------------------------------------------- */

typedef struct {
  size_t n;
  const vl_point *pts;
  const vl_curve_meta *meta;
  vl_sweep_quantity q;
  size_t n_marks;
  const size_t *marks;
  bool half;
  double h_rms_m; /* separation figure */
} curve_ctx;

/* A vertical line where the fluid starts to carry half of the load (one
 * curve: it marks the mixed-lubrication transition without covering it). */
static const style HALF_LOAD_STYLE = {{120, 120, 120}, 3, 1.4};

static bool draw_half_load(fig *f, const curve_ctx *c, const double *wx, const double *wy) {
  double hx, hy;
  if (!c->half || !half_load_at(c->n, c->pts, wx, wy, &hx, &hy)) return false;
  set_style(f, HALF_LOAD_STYLE);
  segment(hx, f->y.lo, hx, f->y.hi);
  return true;
}

/* Series c of the Stribeck figure: mu, its four components, and (a seal's
 * both strokes) the instroke's mu, or (a scene swept both ways) the
 * downward sweep's (NAN where it did not converge). */
static double component(const vl_point *p, int c) {
  switch (c) {
  case 5:
    if (p->down.swept) return p->down.converged ? p->down.mu : NAN;
    return p->seal.in_converged ? p->seal.in_mu : NAN;
  case 0: return p->mu;
  case 1: return p->mu_Rc;
  case 2: return p->mu_Rf;
  case 3: return p->mu_Sc;
  default: return p->mu_Sf;
  }
}

static void draw_stribeck(fig *f, const void *vctx) {
  const curve_ctx *c = vctx;
  static const char *const names[6] = {"#<0x11>μ#<0x01> total",
                                       "#<0x11>μ#<0x01>#dRc#u rolling, contact",
                                       "#<0x11>μ#<0x01>#dRf#u rolling, fluid",
                                       "#<0x11>μ#<0x01>#dSc#u sliding, contact",
                                       "#<0x11>μ#<0x01>#dSf#u sliding, fluid",
                                       "#<0x11>μ#<0x01> total, instroke"};
  /* total in the seed's red, rolling dashed, contact blue, fluid orange; a
   * seal's instroke (the rows are the outstroke) dashed black */
  const style styles[6] = {{PALETTE[1], 1, 3.0}, {PALETTE[0], 3, 2.0}, {PALETTE[4], 3, 2.0},
                           {PALETTE[2], 1, 2.0}, {PALETTE[3], 1, 2.0}, {BLACK, 3, 2.5}};
  size_t n = c->n;
  bool down = n && c->pts[0].down.swept; /* [sweep] direction = both */
  int series = n && (c->pts[0].seal.stroke == VL_STROKE_BOTH || down) ? 6 : 5;
  const char *second = down ? "sweeping up" : "outstroke";
  double *wx = calloc(n, sizeof *wx), *wy = calloc(7 * n, sizeof *wy);
  bool *ok = calloc(n, sizeof *ok);
  if (!wx || !wy || !ok) {
    free(wx), free(wy), free(ok);
    return;
  }
  layout_single(f);
  for (size_t i = 0; i < n; i++)
    ok[i] = c->pts[i].converged;
  double *xv = wy + 6 * n;
  for (size_t i = 0; i < n; i++)
    xv[i] = x_value(&c->pts[i], c->meta, c->q);
  sweep_x_axis(f, n, xv);
  bool shown[6] = {true, false, false, false, false, false};
  double lo = NAN, hi = NAN;
  for (int k = 0; k < series; k++) {
    double *y = wy + (size_t)k * n;
    for (size_t i = 0; i < n; i++) {
      y[i] = ok[i] ? component(&c->pts[i], k) : NAN;
      if (ok[i] && y[i] != 0 && isfinite(y[i])) shown[k] = true;
    }
    if (!shown[k]) continue;
    double a, b;
    range_of(n, y, &a, &b);
    if (isfinite(a)) {
      if (!(a >= lo)) lo = a;
      if (!(b <= hi)) hi = b;
    }
  }
  value_y_axis(f, lo, hi, true);
  /* a component that is the whole of mu (dry rolling) would hide under it:
     named in the total's legend entry instead */
  int alone = 0;
  double scale = fmax(fabs(lo), fabs(hi));
  for (int k = 1; k < 5; k++) {
    if (!shown[k]) continue;
    bool same = true;
    for (size_t i = 0; i < n && same; i++)
      if (ok[i] && fabs(wy[(size_t)k * n + i] - wy[i]) > 1e-9 * scale) same = false;
    if (same) alone = k, shown[k] = false;
  }
  for (size_t i = 0; i < n; i++)
    wx[i] = to_wx(f, xv[i]);
  draw_axes(f, x_title(c->q), "friction coefficient #<0x11>μ#<0x01>", true);
  use_data_area(f);
  bool half = draw_half_load(f, c, wx, wy);
  /* the components first, the total over them, a seal's instroke (dashed)
   * over that */
  for (int j = 0; j < series; j++) {
    int k = j < 5 ? 4 - j : j;
    if (!shown[k]) continue;
    double *y = wy + (size_t)k * n;
    draw_runs(f, n, wx, y, styles[k]);
  }
  for (int k = 0; k < series; k++) {
    if (!shown[k]) continue;
    char label[2 * TEXT_MAX];
    if (k == 0 && alone)
      snprintf(label, sizeof label, "#<0x11>μ#<0x01>%s%s = %s", series == 6 ? " " : "",
               series == 6 ? second : "", names[alone]);
    else if (k == 0 && series == 6)
      snprintf(label, sizeof label, "%s, %s", names[0], second);
    else if (k == 5 && down)
      snprintf(label, sizeof label, "%s", "#<0x11>μ#<0x01> total, sweeping down");
    else
      snprintf(label, sizeof label, "%s", names[k]);
    add_legend(f, label, true, styles[k], M_NONE, false, BLACK);
    f->series++;
  }
  if (half) add_legend(f, HALF_LOAD_TEXT, true, HALF_LOAD_STYLE, M_NONE, false, GREY);
  draw_numbered_marks(f, c->n_marks, c->marks, wx, wy);
  if (c->n_marks) {
    style none = {BLACK, 1, 1};
    add_legend(f, "1, 2, …: fields plotted", false, none, M_CIRCLE, false, BLACK);
  }
  f->failed = draw_failed(f, n, wx, ok, BLACK, 0);
  if (f->failed) add_legend(f, FAILED_TEXT, false, styles[0], M_CIRCLE, true, BLACK);
  if (draw_unreliable(f, n, wx, wy, c->pts, BLACK))
    add_legend(f, UNRELIABLE_TEXT, false, styles[0], M_SQUARE, true, BLACK);
  draw_legend(f, f->vy1);
  free(wx);
  free(wy);
  free(ok);
}

vl_status vl_plot_stribeck(const char *stem, size_t n, const vl_point *pts,
                           const vl_curve_meta *meta, vl_sweep_quantity x, size_t n_marks,
                           const size_t *marks, const vl_plot_options *opt, vl_plot_report *report,
                           vl_error *err) {
  vl_status st = check_curve(n, pts, meta, x, "Stribeck curve", err);
  if (st == VL_OK) st = check_marks(n, n_marks, marks, err);
  if (st != VL_OK) return st;
  curve_ctx c = {n, pts, meta, x, n_marks, marks, opt && opt->mark_half_load, 0};
  return render(stem, opt, "Stribeck curve", draw_stribeck, &c, report, err);
}

/* ---- a seal's strokes ---------------------------------------------------- */

/* Quantity k (0 the friction force per length, 1 the flux per unit
 * circumference) of the outstroke (in false) or the instroke at p; NAN where
 * that stroke did not converge. */
static double seal_value(const vl_point *p, bool in, int k) {
  const vl_seal_result *s = &p->seal;
  if (in ? !s->in_converged : !p->converged) return NAN;
  if (k == 0) return in ? s->in_friction_n_per_m : s->friction_n_per_m;
  return in ? s->in_flux_m2_s : p->flux_m2_s;
}

/* A stroke that converged but is not known to its error target. */
static bool seal_unreliable(const vl_point *p, bool in) {
  if (!in) return vl_point_unreliable(p);
  int a = p->seal.in_accuracy;
  return p->seal.in_converged && (a == VL_ACCURACY_ABOVE_TARGET || a == VL_ACCURACY_NO_ESTIMATE);
}

typedef struct {
  size_t n;
  const vl_point *pts;
} seal_ctx;

/* The y axis of a panel over values v[0..2n): logarithmic when they are
 * all positive and span more than a factor 30, else linear. */
static void seal_y_axis(fig *f, size_t n2, const double *v) {
  double lo, hi;
  range_of(n2, v, &lo, &hi);
  if (isfinite(lo) && lo > 0 && hi / lo > 30)
    f->y = log_axis(lo, hi, len_y(f), CH_TICK * f->ph, true);
  else
    value_y_axis(f, lo, hi, true);
}

/* One panel: both strokes of quantity k, their failed and unreliable
 * points; the legend entries once (k = 0). */
static void seal_panel(fig *f, const seal_ctx *c, int k, const double *xv, double *v, double *wx,
                       double *wy, bool *ok) {
  size_t n = c->n;
  static const char *const names[2] = {"outstroke (oil → air)", "instroke (air → oil)"};
  const style styles[2] = {{PALETTE[1], 1, 2.5}, {PALETTE[0], 3, 2.5}};
  for (int s = 0; s < 2; s++)
    for (size_t i = 0; i < n; i++)
      v[s * n + i] = seal_value(&c->pts[i], s == 1, k);
  seal_y_axis(f, 2 * n, v);
  for (size_t i = 0; i < n; i++)
    wx[i] = to_wx(f, xv[i]);
  draw_axes(f, k ? "sliding speed #<0x11>v#<0x01>#d0#u (m/s)" : NULL,
            k ? "flux per circumference (m²/s)" : "friction force per length (N/m)", k == 1);
  use_data_area(f);
  size_t failed = 0, unreliable = 0;
  for (int s = 0; s < 2; s++) {
    for (size_t i = 0; i < n; i++) {
      wy[i] = to_wy(f, v[s * n + i]);
      ok[i] = isfinite(v[s * n + i]);
    }
    draw_runs(f, n, wx, wy, styles[s]);
    if (k == 0) {
      add_legend(f, names[s], true, styles[s], M_NONE, false, BLACK);
      f->series++;
    }
    failed += draw_failed(f, n, wx, ok, styles[s].color, s);
    for (size_t i = 0; i < n; i++)
      if (seal_unreliable(&c->pts[i], s == 1) && isfinite(wx[i]) && isfinite(wy[i])) {
        draw_marker(f, wx[i], wy[i], M_SQUARE, 2.8, WHITE, BLACK, false);
        unreliable++;
      }
  }
  if (k == 1) {
    f->failed = failed;
    if (failed) add_legend(f, FAILED_TEXT, false, styles[0], M_CIRCLE, true, BLACK);
    if (unreliable) add_legend(f, UNRELIABLE_TEXT, false, styles[0], M_SQUARE, true, BLACK);
  }
}

static void draw_seal(fig *f, const void *vctx) {
  const seal_ctx *c = vctx;
  size_t n = c->n;
  double *xv = calloc(n, sizeof *xv), *wx = calloc(n, sizeof *wx);
  double *v = calloc(2 * n, sizeof *v), *wy = calloc(n, sizeof *wy);
  bool *ok = calloc(n, sizeof *ok);
  if (!xv || !wx || !v || !wy || !ok) {
    free(xv), free(wx), free(v), free(wy), free(ok);
    return;
  }
  for (size_t i = 0; i < n; i++)
    xv[i] = c->pts[i].v0_m_s;
  f->vx0 = 0.105;
  f->vx1 = 0.69;
  f->vy0 = 0.53;
  f->vy1 = TOP;
  sweep_x_axis(f, n, xv);
  seal_panel(f, c, 0, xv, v, wx, wy, ok);
  f->vy0 = 0.115;
  f->vy1 = 0.475;
  seal_panel(f, c, 1, xv, v, wx, wy, ok);
  f->vy0 = 0.115;
  draw_legend(f, TOP);
  free(xv), free(wx), free(v), free(wy), free(ok);
}

vl_status vl_plot_seal(const char *stem, size_t n, const vl_point *pts, const vl_plot_options *opt,
                       vl_plot_report *report, vl_error *err) {
  if (n == 0 || !pts || pts[0].seal.stroke != VL_STROKE_BOTH) {
    vl_error_set(err, "plot: a seal's figure needs the points of both strokes");
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++)
    if (!(pts[i].v0_m_s > 0) || !isfinite(pts[i].v0_m_s)) {
      vl_error_set(err, "plot: speed %zu is not positive (%g m/s)", i + 1, pts[i].v0_m_s);
      return VL_EINPUT;
    }
  seal_ctx c = {n, pts};
  return render(stem, opt, "Seal: friction and leakage per stroke", draw_seal, &c, report, err);
}

/* ---- separation -------------------------------------------------------- */

static void draw_separation(fig *f, const void *vctx) {
  const curve_ctx *c = vctx;
  size_t n = c->n;
  double *wx = calloc(n, sizeof *wx), *wy = calloc(n, sizeof *wy), *xv = calloc(n, sizeof *xv);
  bool *ok = calloc(n, sizeof *ok);
  if (!wx || !wy || !xv || !ok) {
    free(wx), free(wy), free(xv), free(ok);
    return;
  }
  layout_single(f);
  double scale = c->h_rms_m > 0 ? 1.0 / c->h_rms_m : 1e6;
  for (size_t i = 0; i < n; i++) {
    ok[i] = c->pts[i].converged;
    xv[i] = x_value(&c->pts[i], c->meta, c->q);
    wy[i] = ok[i] && c->pts[i].u_min_m > 0 ? c->pts[i].u_min_m * scale : NAN;
  }
  sweep_x_axis(f, n, xv);
  double lo, hi;
  range_of(n, wy, &lo, &hi);
  if (isfinite(lo) && lo > 0 && hi / lo > 30) {
    f->y = log_axis(lo, hi, len_y(f), CH_TICK * f->ph, true);
  } else {
    value_y_axis(f, lo, hi, true);
  }
  for (size_t i = 0; i < n; i++) {
    wx[i] = to_wx(f, xv[i]);
    wy[i] = to_wy(f, wy[i]);
  }
  const char *yt = c->h_rms_m > 0 ? "#<0x11>u#<0x01>#dmin#u/#<0x11>h#<0x01>#drms#u"
                                  : "#<0x11>u#<0x01>#dmin#u (µm)";
  draw_axes(f, x_title(c->q), yt, true);
  use_data_area(f);
  style st = {PALETTE[0], 1, 2.5};
  bool half = draw_half_load(f, c, wx, wy);
  draw_runs(f, n, wx, wy, st);
  add_legend(f, "minimum separation", true, st, M_NONE, false, BLACK);
  f->series = 1;
  if (half) add_legend(f, HALF_LOAD_TEXT, true, HALF_LOAD_STYLE, M_NONE, false, GREY);
  draw_numbered_marks(f, c->n_marks, c->marks, wx, wy);
  if (c->n_marks) add_legend(f, "1, 2, …: fields plotted", false, st, M_CIRCLE, false, BLACK);
  f->failed = draw_failed(f, n, wx, ok, BLACK, 0);
  if (f->failed) add_legend(f, FAILED_TEXT, false, st, M_CIRCLE, true, BLACK);
  draw_legend(f, f->vy1);
  free(wx);
  free(wy);
  free(xv);
  free(ok);
}

vl_status vl_plot_separation(const char *stem, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, vl_sweep_quantity x, double h_rms_m,
                             size_t n_marks, const size_t *marks, const vl_plot_options *opt,
                             vl_plot_report *report, vl_error *err) {
  vl_status st = check_curve(n, pts, meta, x, "separation curve", err);
  if (st == VL_OK) st = check_marks(n, n_marks, marks, err);
  if (st != VL_OK) return st;
  if (!(h_rms_m >= 0) || !isfinite(h_rms_m)) {
    vl_error_set(err, "plot: h_rms %g m is not >= 0", h_rms_m);
    return VL_EINPUT;
  }
  curve_ctx c = {n, pts, meta, x, n_marks, marks, opt && opt->mark_half_load, h_rms_m};
  return render(stem, opt, "Minimum separation", draw_separation, &c, report, err);
}

/* ---- fields ------------------------------------------------------------ */

typedef struct {
  vl_plot_field field;
  size_t k;
  const vl_fields *fields;
  const char *const *labels;
  vl_plot_scales sc;
} fields_ctx;

/* A sequential colour (viridis, dark to light but not to its pale yellow
 * end) for curve j of k: the order of the speeds reads from the colours. */
static rgb sequential(size_t j, size_t k) {
  static const rgb stops[6] = {{68, 1, 84},    {65, 68, 135},  {42, 120, 142},
                               {34, 168, 132}, {122, 209, 81}, {200, 220, 30}};
  double t = k > 1 ? 0.86 * (double)j / (double)(k - 1) : 0.3;
  double s = t * 5;
  int i = (int)floor(s);
  if (i >= 5) i = 4;
  double u = s - i;
  rgb c = {(unsigned char)lround(stops[i].r + u * (stops[i + 1].r - stops[i].r)),
           (unsigned char)lround(stops[i].g + u * (stops[i + 1].g - stops[i].g)),
           (unsigned char)lround(stops[i].b + u * (stops[i + 1].b - stops[i].b))};
  /* never a grey: the tests tell series from axes by colour */
  if (c.r == c.g && c.g == c.b) c.b = (unsigned char)(c.b ^ 1);
  return c;
}

static double field_value(const fields_ctx *c, const vl_fields *fl, size_t i) {
  switch (c->field) {
  case VL_PLOT_FIELD_PC: return fl->p_c_pa[i] / c->sc.p0_pa;
  case VL_PLOT_FIELD_PF: return fl->p_f_pa[i] / c->sc.p0_pa;
  case VL_PLOT_FIELD_U: return c->sc.h_rms_m > 0 ? fl->u_m[i] / c->sc.h_rms_m : fl->u_m[i] * 1e6;
  default: return fl->area_ratio[i];
  }
}

/* The x window of the fields plots, in a0: where the total pressure is at
 * least 1e-3 of its peak in any of the fields, widened by half its width on
 * each side and to the Hertz contact [-1, 1], within the data. A lubricated
 * contact's domain reaches tens of a0 upstream (the inlet film), where
 * nothing but the separation's x^2 growth happens; plotted whole, the
 * contact was a sliver at the right edge. Without any pressure: all data. */
static void fields_window(const fields_ctx *c, double *xlo, double *xhi) {
  double dlo = INFINITY, dhi = -INFINITY, plo = INFINITY, phi = -INFINITY;
  for (size_t j = 0; j < c->k; j++) {
    const vl_fields *fl = &c->fields[j];
    double pmax = 0.0;
    for (size_t i = 0; i < fl->n; i++) {
      double x = fl->x_m[i] / c->sc.a0_m, p = fl->p_c_pa[i] + fl->p_f_pa[i];
      if (isfinite(x)) dlo = fmin(dlo, x), dhi = fmax(dhi, x);
      if (isfinite(p)) pmax = fmax(pmax, p);
    }
    for (size_t i = 0; i < fl->n && pmax > 0.0; i++) {
      double x = fl->x_m[i] / c->sc.a0_m, p = fl->p_c_pa[i] + fl->p_f_pa[i];
      if (isfinite(x) && p >= 1e-3 * pmax) plo = fmin(plo, x), phi = fmax(phi, x);
    }
  }
  *xlo = dlo, *xhi = dhi;
  if (!(phi >= plo)) return;
  double half = 0.5 * (phi - plo);
  *xlo = fmax(dlo, fmin(plo - half, -1.0));
  *xhi = fmin(dhi, fmax(phi + half, 1.0));
}

static void draw_fields(fig *f, const void *vctx) {
  const fields_ctx *c = vctx;
  layout_single(f);
  double xlo, xhi, lo = INFINITY, hi = -INFINITY;
  fields_window(c, &xlo, &xhi);
  for (size_t j = 0; j < c->k; j++) {
    const vl_fields *fl = &c->fields[j];
    for (size_t i = 0; i < fl->n; i++) {
      double x = fl->x_m[i] / c->sc.a0_m, v = field_value(c, fl, i);
      if (!(x >= xlo && x <= xhi)) continue; /* the values shown set the y axis */
      if (isfinite(v) && (c->field != VL_PLOT_FIELD_U || !(c->sc.h_rms_m > 0) || v > 0))
        lo = fmin(lo, v), hi = fmax(hi, v);
    }
  }
  if (!(xhi > xlo)) xlo = -1, xhi = 1;
  f->x = linear_axis(xlo, xhi, len_x(f), CH_TICK * f->ph, true, false);
  /* a rough surface never closes the gap: u/h_rms over decades on a log
     axis; a smooth one does (u = 0 in contact, round-off around it) */
  if (c->field == VL_PLOT_FIELD_U && c->sc.h_rms_m > 0 && isfinite(lo) && hi / lo > 30) {
    f->y = log_axis(lo, hi, len_y(f), CH_TICK * f->ph, true);
  } else if (c->field == VL_PLOT_FIELD_AREA) {
    f->y = linear_axis(0, hi > 0 && hi <= 1 ? fmax(hi * 1.04, 0.01) : 1, len_y(f), CH_TICK * f->ph,
                       false, true);
  } else {
    value_y_axis(f, isfinite(lo) ? lo : 0, isfinite(hi) ? hi : 1, true);
  }
  static const char *const ytitles[4] = {
      "#<0x11>p#<0x01>#dc#u/#<0x11>p#<0x01>#d0#u", "#<0x11>p#<0x01>#df#u/#<0x11>p#<0x01>#d0#u",
      "#<0x11>u#<0x01>/#<0x11>h#<0x01>#drms#u", "#<0x11>A#<0x01>/#<0x11>A#<0x01>#d0#u"};
  const char *yt = c->field == VL_PLOT_FIELD_U && !(c->sc.h_rms_m > 0) ? "#<0x11>u#<0x01> (µm)"
                                                                       : ytitles[c->field];
  draw_axes(f, "#<0x11>x#<0x01>/#<0x11>a#<0x01>#d0#u", yt, true);
  use_data_area(f);
  /* the Hertz contact edges */
  set_style(f, (style){GREY, 2, 1.0});
  for (int s = -1; s <= 1; s += 2)
    if (s > f->x.lo && s < f->x.hi) segment(s, f->y.lo, s, f->y.hi);
  for (size_t j = 0; j < c->k; j++) {
    const vl_fields *fl = &c->fields[j];
    rgb col = sequential(j, c->k);
    style st = {col, 1, 2.2};
    char label[TEXT_MAX];
    if (c->labels && c->labels[j])
      plain_text(label, sizeof label, c->labels[j]);
    else
      snprintf(label, sizeof label, "%zu", j + 1);
    if (fl->n == 0) {
      char l2[TEXT_MAX + 32];
      snprintf(l2, sizeof l2, "%s (not converged)", label);
      add_legend(f, l2, false, st, M_CIRCLE, true, col);
      f->failed++;
      continue;
    }
    double *wx = malloc(fl->n * sizeof *wx), *wy = malloc(fl->n * sizeof *wy);
    if (!wx || !wy) {
      free(wx), free(wy);
      return;
    }
    size_t m = 0; /* the nodes inside the window */
    for (size_t i = 0; i < fl->n; i++) {
      double x = fl->x_m[i] / c->sc.a0_m;
      if (!(x >= f->x.lo && x <= f->x.hi)) continue;
      wx[m] = x;
      wy[m++] = to_wy(f, field_value(c, fl, i));
    }
    draw_runs(f, m, wx, wy, st);
    free(wx);
    free(wy);
    add_legend(f, label, true, st, M_NONE, false, col);
    f->series++;
  }
  draw_legend(f, f->vy1);
}

/* The default titles of the fields figures, by field. */
static const char *const FIELD_KIND[4] = {"Contact pressure", "Fluid pressure", "Separation",
                                          "Contact area"};

vl_status vl_plot_fields(const char *stem, vl_plot_field field, size_t k, const vl_fields *fields,
                         const char *const *labels, const vl_plot_scales *scales,
                         const vl_plot_options *opt, vl_plot_report *report, vl_error *err) {
  if (k == 0 || !fields || !scales) {
    vl_error_set(err, "plot: no fields");
    return VL_EINPUT;
  }
  if ((int)field < 0 || field > VL_PLOT_FIELD_AREA) {
    vl_error_set(err, "plot: unknown field %d", (int)field);
    return VL_EINPUT;
  }
  if (!(scales->a0_m > 0) || !(scales->p0_pa > 0) || !(scales->h_rms_m >= 0) ||
      !isfinite(scales->a0_m) || !isfinite(scales->p0_pa) || !isfinite(scales->h_rms_m)) {
    vl_error_set(err, "plot: scales need a0 > 0, p0 > 0, h_rms >= 0");
    return VL_EINPUT;
  }
  for (size_t j = 0; j < k; j++) {
    const vl_fields *fl = &fields[j];
    if (fl->n && (!fl->x_m || !fl->p_c_pa || !fl->p_f_pa || !fl->u_m || !fl->area_ratio)) {
      vl_error_set(err, "plot: fields %zu without arrays", j + 1);
      return VL_EINPUT;
    }
  }
  fields_ctx c = {field, k, fields, labels, *scales};
  return render(stem, opt, FIELD_KIND[field], draw_fields, &c, report, err);
}

/* ---- compare ----------------------------------------------------------- */

typedef struct {
  size_t k;
  const vl_plot_curve *curves;
  vl_sweep_quantity q;
  vl_plot_y y;
  bool half;
} compare_ctx;

static double y_value(const vl_plot_curve *c, const vl_point *p, vl_plot_y y) {
  switch (y) {
  case VL_PLOT_Y_MU_RC: return p->mu_Rc;
  case VL_PLOT_Y_MU_RF: return p->mu_Rf;
  case VL_PLOT_Y_MU_SC: return p->mu_Sc;
  case VL_PLOT_Y_MU_SF: return p->mu_Sf;
  case VL_PLOT_Y_MU_ROLLING: return p->mu_Rc + p->mu_Rf;
  case VL_PLOT_Y_U_MIN:
    return p->u_min_m > 0 ? p->u_min_m * (c->h_rms_m > 0 ? 1 / c->h_rms_m : 1e6) : NAN;
  case VL_PLOT_Y_FLUID_LOAD: return p->fluid_load_fraction;
  default: return p->mu;
  }
}

static const char *y_title(vl_plot_y y, bool hrms) {
  switch (y) {
  case VL_PLOT_Y_MU_RC: return "#<0x11>μ#<0x01>#dRc#u";
  case VL_PLOT_Y_MU_RF: return "#<0x11>μ#<0x01>#dRf#u";
  case VL_PLOT_Y_MU_SC: return "#<0x11>μ#<0x01>#dSc#u";
  case VL_PLOT_Y_MU_SF: return "#<0x11>μ#<0x01>#dSf#u";
  case VL_PLOT_Y_MU_ROLLING: return "#<0x11>μ#<0x01>#dRc#u + #<0x11>μ#<0x01>#dRf#u";
  case VL_PLOT_Y_U_MIN:
    return hrms ? "#<0x11>u#<0x01>#dmin#u/#<0x11>h#<0x01>#drms#u" : "#<0x11>u#<0x01>#dmin#u (µm)";
  case VL_PLOT_Y_FLUID_LOAD: return "share of the load carried by the fluid";
  default: return "friction coefficient #<0x11>μ#<0x01>";
  }
}

static void draw_compare(fig *f, const void *vctx) {
  const compare_ctx *c = vctx;
  layout_single(f);
  size_t total = 0;
  for (size_t j = 0; j < c->k; j++)
    total += c->curves[j].n;
  double *xv = calloc(total, sizeof *xv), *yv = calloc(total, sizeof *yv);
  bool *ok = calloc(total, sizeof *ok);
  if (!xv || !yv || !ok) {
    free(xv), free(yv), free(ok);
    return;
  }
  size_t off = 0;
  bool hrms = true;
  for (size_t j = 0; j < c->k; j++) {
    const vl_plot_curve *cv = &c->curves[j];
    if (!(cv->h_rms_m > 0)) hrms = false;
    for (size_t i = 0; i < cv->n; i++, off++) {
      ok[off] = cv->pts[i].converged;
      xv[off] = x_value(&cv->pts[i], &cv->meta, c->q);
      yv[off] = ok[off] ? y_value(cv, &cv->pts[i], c->y) : NAN;
    }
  }
  sweep_x_axis(f, total, xv);
  double lo, hi;
  range_of(total, yv, &lo, &hi);
  if (c->y == VL_PLOT_Y_U_MIN && isfinite(lo) && lo > 0 && hi / lo > 30)
    f->y = log_axis(lo, hi, len_y(f), CH_TICK * f->ph, true);
  else if (c->y == VL_PLOT_Y_FLUID_LOAD)
    f->y = linear_axis(0, 1, len_y(f), CH_TICK * f->ph, false, true);
  else
    value_y_axis(f, lo, hi, c->y != VL_PLOT_Y_U_MIN);
  for (size_t i = 0; i < total; i++) {
    xv[i] = to_wx(f, xv[i]);
    yv[i] = to_wy(f, yv[i]);
  }
  draw_axes(f, x_title(c->q), y_title(c->y, hrms), true);
  use_data_area(f);
  off = 0;
  bool any_half = false, any_failed = false, any_unreliable = false;
  for (size_t j = 0; j < c->k; j++) {
    const vl_plot_curve *cv = &c->curves[j];
    style st = {PALETTE[j % 8], 1 + (int)((j / 8) % 4) * 1, 2.4};
    if (j / 8 % 4 == 1)
      st.dash = 3;
    else if (j / 8 % 4 == 2)
      st.dash = 2;
    else if (j / 8 % 4 == 3)
      st.dash = 4;
    draw_runs(f, cv->n, xv + off, yv + off, st);
    char label[TEXT_MAX];
    plain_text(label, sizeof label, cv->label ? cv->label : "");
    add_legend(f, label, true, st, M_NONE, false, st.color);
    f->series++;
    double hx, hy;
    if (c->half && half_load_at(cv->n, cv->pts, xv + off, yv + off, &hx, &hy)) {
      draw_marker(f, hx, hy, M_DIAMOND, 3.2, st.color, BLACK, true);
      any_half = true;
    }
    size_t nf = draw_failed(f, cv->n, xv + off, ok + off, st.color, (int)(j % 6));
    f->failed += nf;
    if (nf) any_failed = true;
    if (draw_unreliable(f, cv->n, xv + off, yv + off, cv->pts, st.color)) any_unreliable = true;
    off += cv->n;
  }
  style none = {BLACK, 1, 1};
  if (any_half) add_legend(f, HALF_LOAD_TEXT, false, none, M_DIAMOND, false, GREY);
  if (any_failed) add_legend(f, FAILED_TEXT, false, none, M_CIRCLE, true, BLACK);
  if (any_unreliable) add_legend(f, UNRELIABLE_TEXT, false, none, M_SQUARE, true, BLACK);
  draw_legend(f, f->vy1);
  free(xv);
  free(yv);
  free(ok);
}

/* The default titles of the comparisons, by quantity. */
static const char *const COMPARE_KIND[8] = {
    "Friction coefficient",    "Hysteresis friction under the contact",
    "Fluid-pressure friction", "Shear friction in the real contact area",
    "Fluid shear friction",    "Rolling friction",
    "Minimum separation",      "Share of the load on the fluid"};

vl_status vl_plot_compare(const char *stem, size_t k, const vl_plot_curve *curves,
                          vl_sweep_quantity x, vl_plot_y y, const vl_plot_options *opt,
                          vl_plot_report *report, vl_error *err) {
  if (k == 0 || !curves) {
    vl_error_set(err, "plot: no curves to compare");
    return VL_EINPUT;
  }
  if ((int)y < 0 || y > VL_PLOT_Y_FLUID_LOAD) {
    vl_error_set(err, "plot: unknown quantity %d", (int)y);
    return VL_EINPUT;
  }
  for (size_t j = 0; j < k; j++) {
    char what[64];
    snprintf(what, sizeof what, "curve %zu", j + 1);
    vl_status st = check_curve(curves[j].n, curves[j].pts, &curves[j].meta, x, what, err);
    if (st != VL_OK) return st;
  }
  compare_ctx c = {k, curves, x, y, opt && opt->mark_half_load};
  return render(stem, opt, COMPARE_KIND[y], draw_compare, &c, report, err);
}

/* ---- moduli ------------------------------------------------------------ */

static void draw_modulus(fig *f, const void *vctx) {
  const vl_plot_modulus_data *d = vctx;
  size_t n = d->n, m = d->n_fit;
  /* frequency and modulus ranges over measured and fitted values */
  double wlo = INFINITY, whi = -INFINITY, elo = INFINITY, ehi = -INFINITY, tlo = INFINITY,
         thi = -INFINITY;
  for (size_t i = 0; i < n + m; i++) {
    double w = i < n ? d->omega_rad_s[i] : d->fit_omega_rad_s[i - n];
    double e1 = i < n ? d->storage_pa[i] : d->fit_storage_pa[i - n];
    double e2 = i < n ? d->loss_pa[i] : d->fit_loss_pa[i - n];
    if (i >= n && (w < wlo || w > whi) && n > 0) continue; /* fit beyond the data: not widened */
    if (i < n || n == 0) wlo = fmin(wlo, w), whi = fmax(whi, w);
    elo = fmin(elo, fmin(e1, e2));
    ehi = fmax(ehi, fmax(e1, e2));
    tlo = fmin(tlo, e2 / e1);
    thi = fmax(thi, e2 / e1);
  }
  f->vx0 = 0.105;
  f->vx1 = 0.69;
  /* top panel: moduli */
  f->vy0 = 0.40;
  f->vy1 = TOP;
  f->x = log_axis(wlo, whi, len_x(f), CH_TICK * f->ph, false);
  /* the lower panel's labels first: both panels get the wider margin */
  f->y = log_axis(tlo, thi, (0.355 - 0.115) * f->ph, CH_TICK * f->ph, true);
  fit_left_margin(f);
  f->y = log_axis(elo, ehi, len_y(f), CH_TICK * f->ph, true);
  draw_axes(f, NULL, "#<0x11>E#<0x01>′, #<0x11>E#<0x01>″ (Pa)", false);
  const char *ml = d->measured_label ? d->measured_label : "measured";
  const char *fl = d->fit_label ? d->fit_label : "Prony fit";
  style s1 = {PALETTE[0], 1, 2.2}, s2 = {PALETTE[1], 1, 2.2}, s3 = {PALETTE[2], 1, 2.2};
  double *wx = malloc((n + m) * sizeof *wx), *wy = malloc((n + m) * sizeof *wy);
  if (!wx || !wy) {
    free(wx), free(wy);
    return;
  }
  for (int panel = 0; panel < 2; panel++) {
    if (panel == 1) {
      f->vy0 = 0.115;
      f->vy1 = 0.355;
      f->y = log_axis(tlo, thi, len_y(f), CH_TICK * f->ph, true);
      draw_axes(f, "angular frequency #<0x11>ω#<0x01> (rad/s)", "tan #<0x11>δ#<0x01>", true);
    }
    use_data_area(f);
    int nq = panel == 0 ? 2 : 1;
    for (int q = 0; q < nq; q++) {
      style st = panel == 1 ? s3 : q == 0 ? s1 : s2;
      /* markers first, the fit over them; many points, smaller markers */
      shape sh = panel == 1 ? M_TRIANGLE : q == 0 ? M_CIRCLE : M_SQUARE;
      double size = n > 60 ? 1.6 : 2.2;
      rgb light = tint(st.color, 0.5); /* the fit's colour, lighter */
      for (size_t i = 0; i < n; i++) {
        double e1 = d->storage_pa[i], e2 = d->loss_pa[i];
        double v = panel == 1 ? e2 / e1 : q == 0 ? e1 : e2;
        draw_marker(f, to_wx(f, d->omega_rad_s[i]), log10(v), sh, size, light, light, true);
      }
      if (m > 0) {
        for (size_t i = 0; i < m; i++) {
          double e1 = d->fit_storage_pa[i], e2 = d->fit_loss_pa[i];
          wx[i] = to_wx(f, d->fit_omega_rad_s[i]);
          wy[i] = log10(panel == 1 ? e2 / e1 : q == 0 ? e1 : e2);
        }
        draw_runs(f, m, wx, wy, st);
      }
      static const char *const qn[3] = {"#<0x11>E#<0x01>′ storage", "#<0x11>E#<0x01>″ loss",
                                        "tan #<0x11>δ#<0x01>"};
      add_legend(f, qn[panel == 1 ? 2 : q], m > 0, st, n > 0 ? sh : M_NONE, false, light);
      f->series += (m > 0) + (n > 0);
    }
  }
  /* what markers and lines stand for */
  char t[TEXT_MAX];
  plain_text(t, sizeof t, ml);
  if (n > 0) add_legend(f, t, false, s1, M_CIRCLE, false, tint(GREY, 0.5));
  if (m > 0) {
    plain_text(t, sizeof t, fl);
    add_legend(f, t, true, (style){GREY, 1, 2.2}, M_NONE, false, GREY);
  }
  free(wx);
  free(wy);
  draw_legend(f, TOP);
}

static bool positive_finite(size_t n, const double *v) {
  if (n && !v) return false;
  for (size_t i = 0; i < n; i++)
    if (!(v[i] > 0) || !isfinite(v[i])) return false;
  return true;
}

vl_status vl_plot_modulus(const char *stem, const vl_plot_modulus_data *d,
                          const vl_plot_options *opt, vl_plot_report *report, vl_error *err) {
  if (!d || (d->n == 0 && d->n_fit == 0)) {
    vl_error_set(err, "plot: no moduli");
    return VL_EINPUT;
  }
  if (!positive_finite(d->n, d->omega_rad_s) || !positive_finite(d->n, d->storage_pa) ||
      !positive_finite(d->n, d->loss_pa) || !positive_finite(d->n_fit, d->fit_omega_rad_s) ||
      !positive_finite(d->n_fit, d->fit_storage_pa) || !positive_finite(d->n_fit, d->fit_loss_pa)) {
    vl_error_set(err, "plot: moduli and frequencies must be positive and finite");
    return VL_EINPUT;
  }
  return render(stem, opt, "Storage and loss moduli", draw_modulus, d, report, err);
}

/* ---- a pair's calibration ---------------------------------------------- */

static void widen_positive(size_t n, const double *v, double *lo, double *hi) {
  for (size_t i = 0; v && i < n; i++)
    if (v[i] > 0 && isfinite(v[i])) *lo = fmin(*lo, v[i]), *hi = fmax(*hi, v[i]);
}

static void draw_calibration(fig *f, const void *vctx) {
  const vl_plot_calibration_data *d = vctx;
  layout_single(f);
  sweep_x_axis(f, d->n, d->v_m_s);
  double lo = INFINITY, hi = 0.0;
  widen_positive(d->n, d->mu, &lo, &hi);
  widen_positive(d->n, d->mu_fit, &lo, &hi);
  widen_positive(d->n, d->mu_other, &lo, &hi);
  widen_positive(d->n, d->mu_sc, &lo, &hi);
  if (!(hi > 0)) lo = 0.01, hi = 1.0;
  if (hi < 1.5 * lo) lo /= 1.5, hi *= 1.5;
  f->y = log_axis(lo, hi, len_y(f), CH_TICK * f->ph, true);
  draw_axes(f, "sliding speed #<0x11>v#<0x01> (m/s)", "friction coefficient #<0x11>μ#<0x01>", true);
  use_data_area(f);
  PLFLT *xs = malloc(d->n * sizeof *xs), *ys = malloc(d->n * sizeof *ys);
  if (!xs || !ys) {
    free(xs), free(ys);
    return;
  }
  for (size_t i = 0; i < d->n; i++)
    xs[i] = to_wx(f, d->v_m_s[i]);
  const struct {
    const double *y;
    const char *label;
    style st;
  } lines[] = {{d->mu_fit, d->fit_label ? d->fit_label : "fitted μ", {PALETTE[0], 1, 2.2}},
               {d->mu_sc, "μ#dSc#u of the fitted law", {PALETTE[1], 2, 1.6}},
               {d->mu_other, "μ without σ#ds#u", {PALETTE[2], 3, 1.6}}};
  for (size_t k = 0; k < sizeof lines / sizeof *lines; k++) {
    if (!lines[k].y) continue;
    for (size_t i = 0; i < d->n; i++)
      ys[i] = isfinite(lines[k].y[i]) ? to_wy(f, lines[k].y[i]) : NAN;
    draw_runs(f, d->n, xs, ys, lines[k].st);
    add_legend(f, lines[k].label, true, lines[k].st, M_NONE, false, lines[k].st.color);
    f->series++;
  }
  bool any_hollow = false;
  for (size_t i = 0; i < d->n; i++) {
    if (!(d->mu[i] > 0 && isfinite(d->mu[i]))) continue;
    bool hollow = d->informative && !d->informative[i];
    any_hollow |= hollow;
    draw_marker(f, xs[i], to_wy(f, d->mu[i]), M_CIRCLE, 2.6, hollow ? WHITE : PALETTE[3],
                PALETTE[3], !hollow);
  }
  style mst = {PALETTE[3], 1, 1.0};
  add_legend(f, "measured", false, mst, M_CIRCLE, false, PALETTE[3]);
  if (any_hollow)
    add_legend(f, "measured, μ#dSc#u < 10 % of μ", false, mst, M_CIRCLE, true, PALETTE[3]);
  f->series++;
  draw_legend(f, f->vy1);
  free(xs);
  free(ys);
}

vl_status vl_plot_calibration(const char *stem, const vl_plot_calibration_data *d,
                              const vl_plot_options *opt, vl_plot_report *report, vl_error *err) {
  if (!d || d->n == 0 || !d->v_m_s || !d->mu || !positive_finite(d->n, d->v_m_s)) {
    vl_error_set(err, "plot: no measured points, or a speed that is not positive");
    return VL_EINPUT;
  }
  return render(stem, opt, "Calibration of a sigma_s law", draw_calibration, d, report, err);
}

/* ---- shift factors ----------------------------------------------------- */

typedef struct {
  size_t n;
  const double *t, *a;
  double tref, c1, c2;
} shifts_ctx;

static void draw_shifts(fig *f, const void *vctx) {
  const shifts_ctx *c = vctx;
  layout_single(f);
  double tlo, thi, alo, ahi;
  range_of(c->n, c->t, &tlo, &thi);
  range_of(c->n, c->a, &alo, &ahi);
  bool wlf = c->c1 > 0 && c->c2 > 0;
  double xlo = fmin(tlo, c->tref), xhi = fmax(thi, c->tref), xpad = 0.04 * fmax(xhi - xlo, 1.0);
  f->x = linear_axis(xlo - xpad, xhi + xpad, len_x(f), CH_TICK * f->ph, false, false);
  double pad = 0.05 * fmax(ahi - alo, 1.0);
  f->y =
      linear_axis(fmin(alo, 0) - pad, fmax(ahi, 0) + pad, len_y(f), CH_TICK * f->ph, false, true);
  draw_axes(f, "temperature #<0x11>T#<0x01> (°C)", "log#d10#u #<0x11>a#<0x01>#dT#u", true);
  use_data_area(f);
  set_style(f, (style){GREY, 2, 1.0});
  segment(c->tref, f->y.lo, c->tref, f->y.hi);
  style st = {PALETTE[0], 1, 2.2};
  if (wlf) {
    enum { NW = 200 };
    PLFLT xs[NW], ys[NW];
    int k = 0;
    for (int i = 0; i < NW; i++) {
      double t = f->x.lo + (f->x.hi - f->x.lo) * i / (NW - 1);
      double den = c->c2 + t - c->tref;
      if (den <= 0) continue; /* outside WLF's domain */
      xs[k] = t;
      ys[k] = -c->c1 * (t - c->tref) / den;
      k++;
    }
    draw_runs(f, (size_t)k, xs, ys, st);
    add_legend(f, "WLF fit", true, st, M_NONE, false, st.color);
    char label[TEXT_MAX];
    snprintf(label, sizeof label, "#<0x11>C#<0x01>#d1#u = %.4g, #<0x11>C#<0x01>#d2#u = %.4g K",
             c->c1, c->c2);
    add_legend(f, label, false, st, M_NONE, false, st.color);
    f->series++;
  }
  for (size_t i = 0; i < c->n; i++)
    draw_marker(f, c->t[i], c->a[i], M_CIRCLE, 2.6, PALETTE[1], PALETTE[1], true);
  add_legend(f, "shifts of the isotherms", false, st, M_CIRCLE, false, PALETTE[1]);
  f->series++;
  char ref[TEXT_MAX];
  snprintf(ref, sizeof ref, "reference %.4g °C", c->tref);
  add_legend(f, ref, true, (style){GREY, 2, 1.0}, M_NONE, false, GREY);
  draw_legend(f, f->vy1);
}

vl_status vl_plot_shifts(const char *stem, size_t n, const double *t_c, const double *log10_a_t,
                         double tref_c, double c1, double c2_k, const vl_plot_options *opt,
                         vl_plot_report *report, vl_error *err) {
  if (n == 0 || !t_c || !log10_a_t || !isfinite(tref_c)) {
    vl_error_set(err, "plot: no shift factors");
    return VL_EINPUT;
  }
  for (size_t i = 0; i < n; i++)
    if (!isfinite(t_c[i]) || !isfinite(log10_a_t[i])) {
      vl_error_set(err, "plot: shift %zu is not finite", i + 1);
      return VL_EINPUT;
    }
  shifts_ctx c = {n, t_c, log10_a_t, tref_c, isfinite(c1) ? c1 : 0, isfinite(c2_k) ? c2_k : 0};
  return render(stem, opt, "Time-temperature shift factors", draw_shifts, &c, report, err);
}

/* ---- flow factors ------------------------------------------------------ */

/* One series of a flow-factor panel: its values and how it is drawn. */
typedef struct {
  const double *v;
  const char *label;
  style st;
} factor_series;

/* The y axis of a panel of k series: linear over their finite values, zero
 * included. */
static void factor_y_axis(fig *f, const vl_plot_flow_factor_data *d, size_t k,
                          const factor_series *s) {
  double lo = NAN, hi = NAN;
  for (size_t j = 0; j < k; j++) {
    double a, b;
    range_of(d->n, s[j].v, &a, &b);
    if (!(a >= lo)) lo = a;
    if (!(b <= hi)) hi = b;
  }
  value_y_axis(f, lo, hi, true);
}

/* A panel of k series against the shared log x axis, with the percolation
 * line. */
static void draw_factor_panel(fig *f, const vl_plot_flow_factor_data *d, size_t k,
                              const factor_series *s, const char *ytitle, bool x_labels, double *wx,
                              double *wy) {
  factor_y_axis(f, d, k, s);
  draw_axes(f, "#<0x11>u#<0x01>/#<0x11>h#<0x01>#drms#u", ytitle, x_labels);
  use_data_area(f);
  double xp = to_wx(f, d->x_percolation);
  if (isfinite(xp) && xp > f->x.lo && xp < f->x.hi) {
    set_style(f, (style){GREY, 2, 1.0});
    segment(xp, f->y.lo, xp, f->y.hi);
  }
  for (size_t j = 0; j < k; j++) {
    for (size_t i = 0; i < d->n; i++) {
      wx[i] = to_wx(f, d->x[i]);
      wy[i] = to_wy(f, s[j].v[i]);
    }
    draw_runs(f, d->n, wx, wy, s[j].st);
    add_legend(f, s[j].label, true, s[j].st, M_NONE, false, s[j].st.color);
    f->series++;
  }
}

static void draw_flow_factors(fig *f, const void *vctx) {
  const vl_plot_flow_factor_data *d = vctx;
  double *wx = malloc(d->n * sizeof *wx), *wy = malloc(d->n * sizeof *wy);
  if (!wx || !wy) {
    free(wx), free(wy);
    return;
  }
  factor_series top[4] = {
      {d->phi_p, "#<0x11>φ#<0x01>#dp#u pressure flow", {PALETTE[0], 1, 2.4}},
      {d->phi_fp, "#<0x11>φ#<0x01>#dfp#u Poiseuille shear", {PALETTE[1], 3, 2.4}},
      {d->phi_s, "#<0x11>φ#<0x01>#ds#u shear flow", {PALETTE[2], 1, 2.4}},
      {d->area_ratio, "#<0x11>A#<0x01>/#<0x11>A#<0x01>#d0#u contact", {PALETTE[3], 1, 2.0}}};
  factor_series bottom[2] = {
      {d->phi_f, "#<0x11>φ#<0x01>#df#u Couette shear", {PALETTE[4], 1, 2.4}},
      {d->phi_fs, "#<0x11>φ#<0x01>#dfs#u roughness shear", {PALETTE[6], 1, 2.4}}};
  double xlo, xhi;
  range_of(d->n, d->x, &xlo, &xhi);
  f->vx0 = 0.105;
  f->vx1 = 0.69;
  f->x = log_axis(xlo, xhi, len_x(f), CH_TICK * f->ph, false);
  /* the lower panel's labels first: both panels get the wider margin */
  f->vy0 = 0.115;
  f->vy1 = 0.395;
  factor_y_axis(f, d, 2, bottom);
  fit_left_margin(f);
  f->vy0 = 0.44;
  f->vy1 = TOP;
  draw_factor_panel(f, d, d->area_ratio ? 4 : 3, top, "flow factors", false, wx, wy);
  f->vy0 = 0.115;
  f->vy1 = 0.395;
  draw_factor_panel(f, d, 2, bottom, "shear stress factors", true, wx, wy);
  double xp = to_wx(f, d->x_percolation);
  if (isfinite(xp) && xp > f->x.lo && xp < f->x.hi) { /* as draw_factor_panel drew it */
    char v[48], label[TEXT_MAX];
    vl_plot_format_value(v, sizeof v, d->x_percolation);
    snprintf(label, sizeof label, "percolation at %s", v);
    add_legend(f, label, true, (style){GREY, 2, 1.0}, M_NONE, false, GREY);
  }
  free(wx);
  free(wy);
  draw_legend(f, TOP);
}

vl_status vl_plot_flow_factors(const char *stem, const vl_plot_flow_factor_data *d,
                               const vl_plot_options *opt, vl_plot_report *report, vl_error *err) {
  if (!d || d->n < 2 || !d->x || !d->phi_p || !d->phi_s || !d->phi_fp || !d->phi_fs || !d->phi_f) {
    vl_error_set(err, "plot: no flow factors (at least 2 rows of x and the five factors)");
    return VL_EINPUT;
  }
  if (!positive_finite(d->n, d->x)) {
    vl_error_set(err, "plot: flow factors: u/h_rms must be positive and finite");
    return VL_EINPUT;
  }
  return render(stem, opt, "Flow factors", draw_flow_factors, d, report, err);
}

/* ---- power spectra ----------------------------------------------------- */

static void draw_psd(fig *f, const void *vctx) {
  const vl_plot_psd_data *d = vctx;
  size_t n = d->n, m = d->n_fit;
  double qlo, qhi, clo, chi;
  range_of(n, d->q_per_m, &qlo, &qhi);
  range_of(n, d->c_m4, &clo, &chi);
  layout_single(f);
  f->x = log_axis(qlo, qhi, len_x(f), CH_TICK * f->ph, false);
  f->y = log_axis(clo, chi, len_y(f), CH_TICK * f->ph, true);
  fit_left_margin(f);
  f->x = log_axis(qlo, qhi, len_x(f), CH_TICK * f->ph, false);
  draw_axes(f, "wavevector #<0x11>q#<0x01> (1/m)", "#<0x11>C#<0x01>(#<0x11>q#<0x01>) (m#u4#d)",
            true);
  use_data_area(f);
  size_t k = n > m ? n : m;
  double *wx = malloc(k * sizeof *wx), *wy = malloc(k * sizeof *wy);
  if (!wx || !wy) {
    free(wx), free(wy);
    return;
  }
  style st = {PALETTE[0], 1, 2.4}, sf = {PALETTE[1], 3, 2.2};
  bool marks = n <= 60;
  for (size_t i = 0; i < n; i++) {
    wx[i] = log10(d->q_per_m[i]);
    wy[i] = log10(d->c_m4[i]);
  }
  draw_runs(f, n, wx, wy, st);
  for (size_t i = 0; marks && i < n; i++)
    draw_marker(f, wx[i], wy[i], M_CIRCLE, 2.0, st.color, st.color, true);
  char t[TEXT_MAX];
  plain_text(t, sizeof t, d->label ? d->label : "C(q)");
  add_legend(f, t, true, st, marks ? M_CIRCLE : M_NONE, false, st.color);
  f->series++;
  if (m > 0) {
    /* clipped to the axes: a law steeper than the data leaves the frame */
    for (size_t i = 0; i < m; i++) {
      wx[i] = log10(d->fit_q_per_m[i]);
      double y = log10(d->fit_c_m4[i]);
      wy[i] = y < f->y.lo || y > f->y.hi ? NAN : y;
    }
    draw_runs(f, m, wx, wy, sf);
    plain_text(t, sizeof t, d->fit_label ? d->fit_label : "self-affine fit");
    add_legend(f, t, true, sf, M_NONE, false, sf.color);
    f->series++;
  }
  free(wx);
  free(wy);
  draw_legend(f, f->vy1);
}

vl_status vl_plot_psd(const char *stem, const vl_plot_psd_data *d, const vl_plot_options *opt,
                      vl_plot_report *report, vl_error *err) {
  if (!d || d->n < 2) {
    vl_error_set(err, "plot: no spectrum (at least 2 points)");
    return VL_EINPUT;
  }
  if (!positive_finite(d->n, d->q_per_m) || !positive_finite(d->n, d->c_m4) ||
      !positive_finite(d->n_fit, d->fit_q_per_m) || !positive_finite(d->n_fit, d->fit_c_m4)) {
    vl_error_set(err, "plot: spectrum: q and C must be positive and finite");
    return VL_EINPUT;
  }
  return render(stem, opt, "Roughness power spectrum", draw_psd, d, report, err);
}

/* ---- a point contact's field over the contact plane --------------------- */

typedef struct {
  vl_plot_field field;
  const vl_plot_map_data *d;
  vl_plot_scales sc;
  double hertz_ax, hertz_by; /* the Hertz ellipse, in a0 (0: not drawn) */
  double *scratch;           /* 2 nx ny values: the centres in a0 */
} map_ctx;

/* The value of cell k shown (NAN: the cell is left white: out of contact). */
static double map_value(const map_ctx *c, size_t k) {
  if (c->field == VL_PLOT_FIELD_PC)
    return c->d->p_c_pa[k] > 0.0 ? c->d->p_c_pa[k] / c->sc.p0_pa : NAN;
  if (c->field == VL_PLOT_FIELD_PF) /* the cavitated film's residue (1e-12 p0) left white */
    return c->d->p_f_pa[k] > 1e-9 * c->sc.p0_pa ? c->d->p_f_pa[k] / c->sc.p0_pa : NAN;
  return c->d->u_m[k] * 1e6;
}

/* The extent of cell i of a row of n centres t[i * stride] (units a0):
 * half way to each neighbour, the end cells as wide as the gap to theirs. */
static void cell_extent(const double *t, size_t stride, size_t n, size_t i, double *lo,
                        double *hi) {
  double c = t[i * stride];
  if (n < 2) {
    *lo = c - 0.5, *hi = c + 0.5;
    return;
  }
  double left = i > 0 ? t[(i - 1) * stride] : 2 * c - t[stride * (i + 1)];
  double right = i + 1 < n ? t[(i + 1) * stride] : 2 * c - t[stride * (i - 1)];
  *lo = 0.5 * (left + c), *hi = 0.5 * (c + right);
}

/* Viridis from dark (t = 0) to yellow (t = 1), as `sequential` but to its end. */
static rgb viridis(double t) {
  static const rgb stops[6] = {{68, 1, 84},    {65, 68, 135},  {42, 120, 142},
                               {34, 168, 132}, {122, 209, 81}, {253, 231, 37}};
  t = t < 0 ? 0 : t > 1 ? 1 : t;
  double s = t * 5;
  int i = (int)floor(s);
  if (i >= 5) i = 4;
  double u = s - i;
  return (rgb){(unsigned char)lround(stops[i].r + u * (stops[i + 1].r - stops[i].r)),
               (unsigned char)lround(stops[i].g + u * (stops[i + 1].g - stops[i].g)),
               (unsigned char)lround(stops[i].b + u * (stops[i + 1].b - stops[i].b))};
}

static void fill_rect(fig *f, double x0, double y0, double x1, double y1, rgb col) {
  PLFLT xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
  set_color(f, col);
  plfill(4, xs, ys);
}

/* The cells (and their mirror images across y = 0), coloured by value over
 * [0, hi]. */
static void draw_map_cells(fig *f, const map_ctx *c, const double *xs, const double *ys,
                           double hi) {
  const vl_plot_map_data *d = c->d;
  pllsty(1);
  plwidth(0.0); /* the driver strokes a fill's edge with the current pen */
  for (size_t k = 0; k < d->nx * d->ny; k++) {
    double v = map_value(c, k);
    if (!isfinite(v)) continue;
    rgb col = viridis(hi > 0 ? v / hi : 0);
    double x0, x1, y0, y1;
    cell_extent(xs, d->ny, d->nx, k / d->ny, &x0, &x1);
    cell_extent(ys, 1, d->ny, k % d->ny, &y0, &y1);
    fill_rect(f, x0, y0, x1, y1, col);
    fill_rect(f, x0, -y1, x1, -y0, col);
  }
}

/* The colour bar right of the map: 64 bands over [0, hi] and its labels. */
static void draw_colour_bar(fig *f, double hi, const char *title) {
  double x0 = f->vx1 + 0.03, x1 = x0 + 0.025, top = f->vy1 - 0.05; /* room for its title */
  plvpor(x0, x1, f->vy0, top);
  fig b = *f;
  b.vx0 = x0, b.vx1 = x1, b.vy1 = top;
  b.x = (axis){.lo = 0, .hi = 1};
  b.y = linear_axis(0, hi > 0 ? hi : 1, len_y(&b), CH_TICK * f->ph, true, true);
  plwind(0, 1, b.y.lo, b.y.hi);
  pllsty(1);
  plwidth(0.0);
  for (int i = 0; i < 64; i++) {
    double y0 = b.y.lo + (b.y.hi - b.y.lo) * i / 64.0,
           y1 = b.y.lo + (b.y.hi - b.y.lo) * (i + 1) / 64.0;
    fill_rect(&b, 0, y0, 1, y1, viridis((i + 0.5) / 64.0));
  }
  set_color(&b, BLACK);
  plwidth(1.0);
  plbox("bc", 0, 0, "bc", 0, 0);
  set_ch(&b, CH_TICK);
  for (long k = 0;; k++) {
    double v = (double)k * b.y.step;
    if (v > b.y.hi + 1e-9 * b.y.step) break;
    char buf[64];
    linear_label(buf, sizeof buf, v, b.y.decimals);
    plmtex("rv", 0.6, (v - b.y.lo) / (b.y.hi - b.y.lo), 0.0, buf);
  }
  set_ch(&b, CH_TITLE);
  plmtex("t", 1.0, 0.5, 0.5, title);
  f->scratch = b.scratch;
}

/* The ellipse (semi-axes ax, by in a0), dashed. */
static void draw_ellipse(fig *f, double ax, double by) {
  PLFLT xs[129], ys[129];
  for (int i = 0; i <= 128; i++) {
    double t = 2 * M_PI * i / 128.0;
    xs[i] = ax * cos(t), ys[i] = by * sin(t);
  }
  set_style(f, (style){BLACK, 3, 1.6});
  plline(129, xs, ys);
}

static void draw_map(fig *f, const void *vctx) {
  const map_ctx *c = vctx;
  const vl_plot_map_data *d = c->d;
  size_t n = d->nx * d->ny;
  /* the colour scale's top, the centres in a0, and the cells' outer edges */
  double hi = 0.0, *xs = c->scratch, *ys = c->scratch + n, lo, hi_edge;
  for (size_t k = 0; k < n; k++) {
    double v = map_value(c, k);
    if (isfinite(v)) hi = fmax(hi, v);
    xs[k] = d->x_m[k] / c->sc.a0_m, ys[k] = d->y_m[k] / c->sc.a0_m;
  }
  cell_extent(xs, d->ny, d->nx, 0, &lo, &hi_edge);
  double X0 = lo;
  cell_extent(xs, d->ny, d->nx, d->nx - 1, &lo, &hi_edge);
  double X1 = hi_edge;
  cell_extent(ys, 1, d->ny, d->ny - 1, &lo, &hi_edge);
  double Y1 = hi_edge;
  /* equal scales: the data area fitted into the room left of the colour bar */
  double room_x = 0.70 - 0.105, room_y = TOP - 0.115;
  double sx = room_x * f->pw / (X1 - X0), sy = room_y * f->ph / (2 * Y1), s = fmin(sx, sy);
  f->vx0 = 0.105, f->vx1 = 0.105 + s * (X1 - X0) / f->pw;
  f->vy0 = 0.115, f->vy1 = 0.115 + s * 2 * Y1 / f->ph;
  f->x = linear_axis(X0, X1, len_x(f), CH_TICK * f->ph, true, false);
  f->y = linear_axis(-Y1, Y1, len_y(f), CH_TICK * f->ph, true, true);
  /* the axes (and their grid) first: the cells cover the grid where they
   * are coloured; the frame again over them */
  draw_axes(f, "#<0x11>x#<0x01>/#<0x11>a#<0x01>#d0#u (sliding direction)",
            "#<0x11>y#<0x01>/#<0x11>a#<0x01>#d0#u", true);
  use_data_area(f);
  draw_map_cells(f, c, xs, ys, hi);
  if (c->hertz_ax > 0 && c->hertz_by > 0) draw_ellipse(f, c->hertz_ax, c->hertz_by);
  set_color(f, BLACK);
  pllsty(1);
  plwidth(1.2);
  plbox("bc", 0, 0, "bc", 0, 0);
  const char *title = c->field == VL_PLOT_FIELD_PC   ? "#<0x11>p#<0x01>#dc#u/#<0x11>p#<0x01>#d0#u"
                      : c->field == VL_PLOT_FIELD_PF ? "#<0x11>p#<0x01>#df#u/#<0x11>p#<0x01>#d0#u"
                                                     : "#<0x11>u#<0x01> (µm)";
  draw_colour_bar(f, hi, title);
  if (c->hertz_ax > 0 && c->hertz_by > 0) { /* the key of the dashed line, bottom right */
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    set_style(f, (style){BLACK, 3, 1.6});
    segment(0.72, 0.035, 0.77, 0.035);
    set_color(f, BLACK);
    set_ch(f, CH_LEGEND);
    plptex(0.78, 0.035, 1, 0, 0, "Hertz, relaxed modulus");
  }
  f->series = 1;
}

vl_status vl_plot_map(const char *stem, vl_plot_field field, const vl_plot_map_data *d,
                      const vl_plot_scales *scales, double hertz_ax_m, double hertz_by_m,
                      const vl_plot_options *opt, vl_plot_report *report, vl_error *err) {
  if (!d || !scales || d->nx == 0 || d->ny == 0 || !d->x_m || !d->y_m ||
      (field == VL_PLOT_FIELD_PC && !d->p_c_pa) || (field == VL_PLOT_FIELD_U && !d->u_m) ||
      (field == VL_PLOT_FIELD_PF && !d->p_f_pa)) {
    vl_error_set(err, "plot: no map");
    return VL_EINPUT;
  }
  if (field != VL_PLOT_FIELD_PC && field != VL_PLOT_FIELD_U && field != VL_PLOT_FIELD_PF) {
    vl_error_set(err, "plot: a map of p_c, p_f or u only (got field %d)", (int)field);
    return VL_EINPUT;
  }
  if (!(scales->a0_m > 0) || !(scales->p0_pa > 0) || !isfinite(scales->a0_m) ||
      !isfinite(scales->p0_pa)) {
    vl_error_set(err, "plot: scales need a0 > 0, p0 > 0");
    return VL_EINPUT;
  }
  double *scratch = malloc(2 * d->nx * d->ny * sizeof *scratch);
  if (!scratch) {
    vl_error_set(err, "plot: out of memory for a map of %zu cells", d->nx * d->ny);
    return VL_ENOMEM;
  }
  map_ctx c = {field, d, *scales, hertz_ax_m / scales->a0_m, hertz_by_m / scales->a0_m, scratch};
  static const char *const names[] = {[VL_PLOT_FIELD_PC] = "Contact pressure map",
                                      [VL_PLOT_FIELD_PF] = "Fluid pressure map",
                                      [VL_PLOT_FIELD_U] = "Separation map"};
  vl_status st = render(stem, opt, names[field], draw_map, &c, report, err);
  free(scratch);
  return st;
}
