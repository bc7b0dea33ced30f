/* The film's rows. Defines: KASHA_BINS, KASHA_SPECTRAL_FILM. */
#ifndef KASHA_FILM_ROWS_H
#define KASHA_FILM_ROWS_H

/* C, the film's rows over bins: x̄ȳz̄ times the bin width (XYZ film) or the identity (spectral). */
inline float film_row_weight(const __global float* cmf, int r, int i) {
#if KASHA_SPECTRAL_FILM
  return r == i ? 1.0f : 0.0f;
#else
  return cmf[r * KASHA_BINS + i];
#endif
}

#endif
