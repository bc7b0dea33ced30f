/* Linear sRGB (D65) <-> CIE XYZ, IEC 61966-2-1 at full precision (derived from the primaries and
 * the D65 white point; see host/data/sRGB_XYZ_constants.txt). Shared by host and kernels. */
#ifndef KASHA_COLOR_CONSTANTS_H
#define KASHA_COLOR_CONSTANTS_H

#ifdef __OPENCL_VERSION__
#define KASHA_F(x) x##f
#else
#define KASHA_F(x) x
#endif

#define KASHA_SRGB_TO_XYZ                                  \
  {                                                        \
    {KASHA_F(0.4123907993), KASHA_F(0.3575843394), KASHA_F(0.1804807884)},            \
    {KASHA_F(0.2126390059), KASHA_F(0.7151686788), KASHA_F(0.0721923154)},            \
    {KASHA_F(0.0193308187), KASHA_F(0.1191947798), KASHA_F(0.9505321522)}             \
  }
#define KASHA_XYZ_TO_SRGB                                  \
  {                                                        \
    {KASHA_F(3.2409699419), KASHA_F(-1.5373831776), KASHA_F(-0.4986107603)},          \
    {KASHA_F(-0.9692436363), KASHA_F(1.8759675015), KASHA_F(0.0415550574)},           \
    {KASHA_F(0.0556300797), KASHA_F(-0.2039769589), KASHA_F(1.0569715142)}            \
  }

#endif
