#include "render/texture_program.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/printable.h"

namespace kasha {

namespace {

// At most this many terms in one spectral program: each is a pass over the bins.
constexpr int kMaxTerms = 64;

// One program: steps over slots, then (spectral) terms. Each texture is compiled once per program
// (a texture two operands share is one slot).
class TextureCompiler {
 public:
  TextureCompiler(const Scene& scene, int root, TextureProgramTables& tables)
      : scene_(scene), tables_(tables), root_(scene.textures[root]) {}

  KTexture compile(int texture, bool spectral) {
    if (spectral) {
      spectral_texture(texture, one());
    } else {
      int r = scalar(texture);
      // The value is the last step's: a folded result (a product with 1) is copied there.
      if (steps_.empty() || steps_.back().dst != r) {
        KTexOp op = step(KASHA_TEXOP_MUL);
        op.a = r;
        op.b = one();
        r = emit(op);
      }
    }
    KTexture k{};
    k.type = KASHA_TEXTURE_PROGRAM;
    k.spectral = spectral;
    k.data = k.even = k.odd = k.lambda = -1;
    k.uscale = k.vscale = 1.0f;
    k.first_op = static_cast<int>(tables_.ops.size());
    k.ops = static_cast<int>(steps_.size());
    tables_.ops.insert(tables_.ops.end(), steps_.begin(), steps_.end());
    k.first_term = static_cast<int>(tables_.ops.size());
    k.terms = static_cast<int>(terms_.size());
    tables_.ops.insert(tables_.ops.end(), terms_.begin(), terms_.end());
    return k;
  }

 private:
  const Scene& scene_;
  TextureProgramTables& tables_;
  const Texture& root_;
  std::vector<KTexOp> steps_, terms_;
  int slots_ = 0, one_ = -1;
  std::map<int, int> scalar_memo_, map_memo_;

  [[noreturn]] void fail(const std::string& where, const std::string& why) const {
    throw Error(where + ": " + why);
  }

  static KTexOp step(int type) {
    KTexOp op{};
    op.type = type;
    op.ref = -1;
    return op;
  }

  // Appends a step writing `width` new slots; its first slot.
  int emit(KTexOp op, int width = 1) {
    if (slots_ + width > KASHA_TEXTURE_SLOTS)
      fail(root_.where, "the texture \"" + printable(root_.name) + "\" needs more than " +
                            std::to_string(KASHA_TEXTURE_SLOTS) +
                            " steps, the most kasha's kernels evaluate");
    op.dst = slots_;
    slots_ += width;
    steps_.push_back(op);
    return op.dst;
  }

  int constant(double v) {
    KTexOp op = step(KASHA_TEXOP_CONST);
    op.f[0] = static_cast<float>(v);
    return emit(op);
  }

  int one() { return one_ >= 0 ? one_ : (one_ = constant(1)); }

  int binary(int type, int a, int b, int c = 0) {
    KTexOp op = step(type);
    op.a = a;
    op.b = b;
    op.c = c;
    return emit(op);
  }

  int mul(int a, int b) { return a == one_ ? b : b == one_ ? a : binary(KASHA_TEXOP_MUL, a, b); }
  int one_minus(int a) { return binary(KASHA_TEXOP_ONE_MINUS, a, 0); }
  int lerp(int t, int a, int b) { return binary(KASHA_TEXOP_LERP, t, a, b); }

  // The texture's 3×4 texture-from-world matrix in the data buffer.
  int matrix(const Texture& t) {
    const int at = static_cast<int>(tables_.data.size());
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        tables_.data.push_back(static_cast<float>(t.texture_from_world.matrix()(r, c)));
    return at;
  }

  // The slots of a 2D texture's (s, t).
  int map2d(int index) {
    auto found = map_memo_.find(index);
    if (found != map_memo_.end()) return found->second;
    const Texture& t = scene_.textures[index];
    KTexOp op = step(KASHA_TEXOP_MAP_UV);
    if (t.mapping == TextureMapping::uv) {
      op.f[0] = static_cast<float>(t.uscale);
      op.f[1] = static_cast<float>(t.vscale);
      op.f[2] = static_cast<float>(t.udelta);
      op.f[3] = static_cast<float>(t.vdelta);
    } else {
      op.type = t.mapping == TextureMapping::spherical     ? KASHA_TEXOP_MAP_SPHERE
                : t.mapping == TextureMapping::cylindrical ? KASHA_TEXOP_MAP_CYLINDER
                                                           : KASHA_TEXOP_MAP_PLANE;
      op.ref = matrix(t);
      for (int k = 0; k < 3; ++k) {
        op.f[k] = static_cast<float>(t.v1[k]);
        op.f[3 + k] = static_cast<float>(t.v2[k]);
      }
      op.f[6] = static_cast<float>(t.udelta);
      op.f[7] = static_cast<float>(t.vdelta);
    }
    return map_memo_[index] = emit(op, 2);
  }

  // The slots of a 3D texture's point.
  int map3d(int index) {
    auto found = map_memo_.find(index);
    if (found != map_memo_.end()) return found->second;
    KTexOp op = step(KASHA_TEXOP_MAP_3D);
    op.ref = matrix(scene_.textures[index]);
    return map_memo_[index] = emit(op, 3);
  }

  // A checkerboard's 0 (even) or 1 (odd) at the point.
  int checker(int index) {
    const Texture& t = scene_.textures[index];
    if (t.dimension == 3) return binary(KASHA_TEXOP_CHECKER_3D, map3d(index), 0);
    const int s = map2d(index);
    return binary(KASHA_TEXOP_CHECKER_2D, s, s + 1);
  }

  int noise(int index, int type) {
    const Texture& t = scene_.textures[index];
    KTexOp op = step(type);
    op.a = map3d(index);
    op.octaves = t.octaves;
    op.f[0] = static_cast<float>(t.roughness);
    op.f[1] = static_cast<float>(t.marble_scale);
    op.f[2] = static_cast<float>(t.variation);
    return emit(op);
  }

  int direction(const Texture& t) {
    KTexOp op = step(KASHA_TEXOP_DIRECTION);
    for (int k = 0; k < 3; ++k) op.f[k] = static_cast<float>(t.dir[k]);
    return emit(op);
  }

  static const TextureInput& input(const Texture& t, const char* key) { return t.inputs.at(key); }

  int scalar_input(const TextureInput& in) {
    if (in.texture >= 0) return scalar(in.texture);
    if (!in.is_number) fail(in.where, "a spectrum where a texture of numbers needs a number");
    return constant(in.number);
  }

  int scalar(int index) {
    auto found = scalar_memo_.find(index);
    if (found != scalar_memo_.end()) return found->second;
    const Texture& t = scene_.textures[index];
    int r = -1;
    switch (t.type) {
      case TextureType::image: {
        const int s = map2d(index);
        KTexOp op = step(KASHA_TEXOP_IMAGE);
        op.a = s;
        op.b = s + 1;
        op.ref = tables_.image(index, false);
        r = emit(op);
        break;
      }
      case TextureType::checkerboard: {
        const int c = checker(index);
        r = lerp(c, scalar_input(input(t, "even")), scalar_input(input(t, "odd")));
        break;
      }
      case TextureType::constant:
        r = scalar_input(input(t, "value"));
        break;
      case TextureType::scale:
        r = mul(scalar_input(input(t, "tex")), scalar_input(input(t, "scale")));
        break;
      case TextureType::mix: {
        const int a = scalar_input(input(t, "amount"));
        r = lerp(a, scalar_input(input(t, "tex1")), scalar_input(input(t, "tex2")));
        break;
      }
      case TextureType::directionmix: {
        const int a = direction(t);
        r = lerp(a, scalar_input(input(t, "tex2")), scalar_input(input(t, "tex1")));
        break;
      }
      case TextureType::bilerp: {
        const int s = map2d(index);
        KTexOp op = step(KASHA_TEXOP_BILERP);
        op.a = s;
        op.b = s + 1;
        const char* corners[4] = {"v00", "v01", "v10", "v11"};
        for (int k = 0; k < 4; ++k) {
          const TextureInput& in = input(t, corners[k]);
          if (!in.is_number) fail(in.where, "a spectrum where a texture of numbers needs a number");
          op.f[k] = static_cast<float>(in.number);
        }
        r = emit(op);
        break;
      }
      case TextureType::dots: {
        const int s = map2d(index);
        const int d = binary(KASHA_TEXOP_DOTS, s, s + 1);
        r = lerp(d, scalar_input(input(t, "outside")), scalar_input(input(t, "inside")));
        break;
      }
      case TextureType::fbm:
        r = noise(index, KASHA_TEXOP_FBM);
        break;
      case TextureType::wrinkled:
        r = noise(index, KASHA_TEXOP_WRINKLED);
        break;
      case TextureType::windy:
        r = noise(index, KASHA_TEXOP_WINDY);
        break;
      case TextureType::marble:
        fail(t.where, "a marble texture is a colour, and a number is needed here");
    }
    return scalar_memo_[index] = r;
  }

  void term(KTexOp op) {
    if (static_cast<int>(terms_.size()) >= kMaxTerms)
      fail(root_.where, "the texture \"" + printable(root_.name) + "\" sums more than " +
                            std::to_string(kMaxTerms) + " spectra");
    terms_.push_back(op);
  }

  void term_spectrum(int weight, const SpectrumPtr& s) {
    KTexOp op = step(KASHA_TEXOP_TERM_SPECTRUM);
    op.a = weight;
    op.ref = tables_.spectrum(s);
    term(op);
  }

  void spectral_input(const TextureInput& in, int weight) {
    if (in.texture >= 0) return spectral_texture(in.texture, weight);
    if (in.is_number && in.number == 0) return;  // adds nothing
    term_spectrum(weight, in.spectrum);
  }

  void spectral_texture(int index, int w) {
    const Texture& t = scene_.textures[index];
    switch (t.type) {
      case TextureType::image: {
        const int s = map2d(index);
        KTexOp op = step(KASHA_TEXOP_TERM_IMAGE);
        op.a = w;
        op.b = s;
        op.c = s + 1;
        op.ref = tables_.image(index, true);
        term(op);
        return;
      }
      case TextureType::checkerboard: {
        const int c = checker(index);
        spectral_input(input(t, "even"), mul(w, one_minus(c)));
        spectral_input(input(t, "odd"), mul(w, c));
        return;
      }
      case TextureType::constant:
        return spectral_input(input(t, "value"), w);
      case TextureType::scale:
        return spectral_input(input(t, "tex"), mul(w, scalar_input(input(t, "scale"))));
      case TextureType::mix: {
        const int a = scalar_input(input(t, "amount"));
        spectral_input(input(t, "tex1"), mul(w, one_minus(a)));
        spectral_input(input(t, "tex2"), mul(w, a));
        return;
      }
      case TextureType::directionmix: {
        const int a = direction(t);
        spectral_input(input(t, "tex1"), mul(w, a));
        spectral_input(input(t, "tex2"), mul(w, one_minus(a)));
        return;
      }
      case TextureType::bilerp: {
        const int s = map2d(index);
        const char* corners[4] = {"v00", "v01", "v10", "v11"};
        for (int k = 0; k < 4; ++k) {
          const TextureInput& in = input(t, corners[k]);
          if (in.is_number && in.number == 0) continue;
          KTexOp op = step(KASHA_TEXOP_BILERP);
          op.a = s;
          op.b = s + 1;
          op.f[k] = 1.0f;  // this corner's weight
          term_spectrum(mul(w, emit(op)), in.spectrum);
        }
        return;
      }
      case TextureType::dots: {
        const int s = map2d(index);
        const int d = binary(KASHA_TEXOP_DOTS, s, s + 1);
        spectral_input(input(t, "inside"), mul(w, d));
        spectral_input(input(t, "outside"), mul(w, one_minus(d)));
        return;
      }
      case TextureType::fbm:
      case TextureType::wrinkled:
      case TextureType::windy:
        // A texture of numbers as a grey.
        return term_spectrum(mul(w, scalar(index)), std::make_shared<ConstantSpectrum>(1.0));
      case TextureType::marble: {
        KTexOp op = step(KASHA_TEXOP_TERM_IMAGE);
        op.a = w;
        op.b = noise(index, KASHA_TEXOP_MARBLE);
        op.c = constant(0.5);
        op.ref = tables_.palette(marble_palette());
        term(op);
        return;
      }
    }
  }

  // The marble colours at 1024 values of the spline parameter, looked up between them.
  static const RgbImage& marble_palette() {
    static const RgbImage palette = [] {
      RgbImage p;
      p.width = 1024;
      p.height = 1;
      for (int i = 0; i < p.width; ++i)
        for (double c : marble_rgb((i + 0.5) / p.width)) p.rgb.push_back(static_cast<float>(c));
      return p;
    }();
    return palette;
  }
};

}  // namespace

std::array<double, 3> marble_rgb(double t) {
  static const double colors[9][3] = {{.58, .58, .6}, {.58, .58, .6}, {.58, .58, .6},
                                      {.5, .5, .5},   {.6, .59, .58}, {.58, .58, .6},
                                      {.58, .58, .6}, {.2, .2, .33},  {.58, .58, .6}};
  const int segments = 6;
  const int first = std::min(static_cast<int>(std::floor(t * segments)), segments - 1);
  const double u = t * segments - first;
  // The cubic Bézier of colours first..first + 3 (pbrt-v4's EvaluateCubicBezier), times 1.5.
  const double b[4] = {(1 - u) * (1 - u) * (1 - u), 3 * u * (1 - u) * (1 - u), 3 * u * u * (1 - u),
                       u * u * u};
  std::array<double, 3> rgb{};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 4; ++k) rgb[c] += 1.5 * b[k] * colors[first + k][c];
  return rgb;
}

KTexture compile_texture_program(const Scene& scene, int texture, bool spectral,
                                 TextureProgramTables& tables) {
  return TextureCompiler(scene, texture, tables).compile(texture, spectral);
}

}  // namespace kasha
