/* An RGB colour's spectrum as host/spectrum/rgb_spectrum.h fits it (Jakob & Hanika 2019): the
 * sigmoid S(x) = ½ + x / (2√(1 + x²)) of a quadratic in the wavelength, inside (0, 1). */
#ifndef KASHA_RGB_SPECTRUM_H
#define KASHA_RGB_SPECTRUM_H

/* S(c0 nm² + c1 nm + c2); far out it is 0 or 1 (and x² would overflow). */
inline float rgb_sigmoid(const __global float* c, float nm) {
  float x = (c[0] * nm + c[1]) * nm + c[2];
  return fabs(x) > 1e18f ? (x > 0.0f ? 1.0f : 0.0f) : 0.5f + x / (2.0f * sqrt(1.0f + x * x));
}

#endif
