/* viscolube (private): the byte-level pieces of the serialised tables the
 * database caches (persson.c's u(s) table, flow_factors_emt.c's factors),
 * defined in persson.c. Every field is little-endian and a double travels as
 * its IEEE-754 bits, so a blob reads the same on any machine; a table
 * records the PSD it was built from by psd_fingerprint and ends with an
 * FNV-1a checksum of all its bytes. */
#ifndef VISCOLUBE_BLOB_H
#define VISCOLUBE_BLOB_H

#include <stddef.h>
#include <stdint.h>

#include "viscolube/roughness.h"

#define VL_BLOB_FNV_OFFSET 0xcbf29ce484222325ULL

void vl_blob_put_u64(unsigned char *p, uint64_t v);
uint64_t vl_blob_get_u64(const unsigned char *p);
uint64_t vl_blob_bits(double v);   /* the IEEE-754 bits of v */
double vl_blob_double(uint64_t b); /* and back */

/* FNV-1a of n bytes continuing from hash h (VL_BLOB_FNV_OFFSET to start). */
uint64_t vl_blob_fnv1a(uint64_t h, const unsigned char *p, size_t n);

/* The 8 fingerprint words of a PSD as vl_psd_init_* left it: kind, H, q0,
 * q1, C0, h_rms (bits), the number of points and a hash of the points. */
#define VL_BLOB_PSD_WORDS 8
void vl_blob_psd_fingerprint(const vl_psd *psd, uint64_t fp[VL_BLOB_PSD_WORDS]);

#endif
