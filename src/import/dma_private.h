/* The private part of viscolube/dma.h: the DMA reader on a string and the
 * names of its enums, for the import layer, the database and the tests. */
#ifndef VISCOLUBE_DMA_PRIVATE_H
#define VISCOLUBE_DMA_PRIVATE_H

#include "viscolube/dma.h"

/* "storage-loss", "storage-tan-delta", "compliance". */
const char *vl_dma_kind_name(vl_dma_kind kind);

/* "auto", "tensile", "shear". */
const char *vl_dma_moduli_name(vl_dma_moduli moduli);

/* As vl_measured_read_file for text[0..len) in memory, named source. */
vl_status vl_measured_read_text(const char *text, size_t len, const char *source,
                                const vl_dma_options *opts, vl_measured *out, vl_error *err);

/* One point's place in the import's order: isotherm, then frequency
 * (dma.c sorts the points once; the quality checks read that order). */
typedef struct {
  size_t iso;
  double omega;
  size_t idx;
} vl_dma_order;

/* The measured ranges, the join misfit of neighbouring isotherms, the
 * tan delta rise at the top of each isotherm and Einf/E0 against the
 * measured moduli (dma.h) of a finished import m, with a note for the
 * ranges and a "warning: " note for each threshold exceeded
 * (VL_DMA_WARN_*). ord: m's points in the import's order (isotherm, then
 * frequency). Fills m->iso_join_rms and m->iso_tan_delta_rise (freed by
 * vl_measured_free). VL_ENOMEM (err set). */
vl_status vl_dma_quality(vl_measured *m, const vl_dma_order *ord, vl_error *err);

#endif
