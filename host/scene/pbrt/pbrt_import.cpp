#include "scene/pbrt/pbrt_import.h"

#include <Eigen/Dense>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "core/error.h"
#include "core/gzip_input.h"
#include "core/input_file.h"
#include "core/printable.h"
#include "scene/pbrt/pbrt_color_space.h"
#include "scene/pbrt/pbrt_integrator.h"
#include "scene/pbrt/pbrt_materials.h"
#include "scene/pbrt/pbrt_parameters.h"
#include "scene/pbrt/pbrt_shapes.h"
#include "scene/pbrt/pbrt_spectra.h"
#include "scene/pbrt/pbrt_tokenizer.h"
#include "scene/pixel_filter.h"
#include "scene/vdb_grid.h"

namespace kasha {

bool is_pbrt_scene(const std::string& path) {
  std::filesystem::path p(path);
  if (is_gzip_name(path)) p = p.stem();  // scene.pbrt.gz, as pbrt-v4 reads it
  const std::string ext = p.extension().string();
  return ext == ".pbrt" || ext == ".PBRT";
}

namespace {

using Matrix = Eigen::Matrix4d;

// Include and Import nest at most this deep: a file that includes itself ends here.
constexpr int kMaxIncludeDepth = 32;

nlohmann::json row_major(const Matrix& m) {
  std::vector<double> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.push_back(m(r, c));
  return out;
}

// A JSON pointer's segment (RFC 6901: '~' and '/' escaped), as JsonNode writes paths.
std::string pointer_segment(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

nlohmann::json triple(const Eigen::Vector3d& v) {
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d point(const Matrix& m, const Eigen::Vector3d& p) {
  const Eigen::Vector4d h = m * Eigen::Vector4d(p[0], p[1], p[2], 1);
  return h.head<3>() / h[3];
}

Eigen::Vector3d direction(const Matrix& m, const Eigen::Vector3d& d) {
  return m.topLeftCorner<3, 3>() * d;
}

struct AreaLight {
  std::string type;
  PbrtParameters params;
  PbrtLocation where;
};

// What AttributeBegin saves and AttributeEnd restores (pbrt-v4's GraphicsState).
struct GraphicsState {
  Matrix ctm = Matrix::Identity();
  bool reverse_orientation = false;
  std::string material;  // kasha material name; empty: pbrt-v4's default diffuse
  std::shared_ptr<const AreaLight> area_light;
  std::string inside_medium, outside_medium;
  std::string color_space = "srgb";  // pbrt-v4's ColorSpace, part of its graphics state
  std::map<std::string, PbrtParameters> attributes;  // Attribute "shape" | "light" | …
};

struct SavedState {
  GraphicsState state;
  bool transform_only;  // TransformBegin: only the CTM comes back
  PbrtLocation where;
};

struct DefinedShape {
  nlohmann::json shape;  // with its material, without its transform
  Matrix ctm;            // object to instance space
  PbrtLocation where;
};

struct ObjectDefinition {
  std::vector<DefinedShape> shapes;
  PbrtLocation where;
  std::string material;  // --material's replacement for all its shapes, when it has one
};

class Importer {
 public:
  Importer(const std::string& path, const std::vector<MaterialOverride>& overrides)
      : main_file_(path), base_dir_(std::filesystem::path(path).parent_path()) {
    for (const MaterialOverride& o : overrides) overrides_[o.name] = o.file;
  }

  const JsonSourceMap& sources() const { return sources_; }

  nlohmann::json run() {
    parse_file(main_file_, main_file_, PbrtLocation{}, 0);
    if (!stack_.empty()) pbrt_fail(stack_.back().where, "AttributeBegin without its AttributeEnd");
    if (object_) pbrt_fail(object_->where, "ObjectBegin without its ObjectEnd");
    if (!camera_seen_) make_camera(Matrix::Identity(), "perspective", PbrtParameters{}, {});
    if (shapes_.empty() && instances_.empty())
      throw Error(printable(main_file_) + ": the scene has no shape that kasha renders");
    for (const auto& [name, where] : named_material_uses_)
      if (!materials_.contains(name) && !interfaces_.count(name))
        pbrt_fail(where, "NamedMaterial " + in_quotes(name) + ": no material of that name");
    for (const auto& [key, where] : anonymous_mixes_) check_mix_parts(key, where);
    for (const auto& [name, file] : overrides_) {
      const bool material = materials_.contains(name) && named_materials_.count(name);
      if (material) materials_[name] = {{"file", absolute(file)}};
      if (!material && !overridden_objects_.count(name))
        throw Error("--material " + printable(name) + "=" + printable(file) + ": " +
                    printable(main_file_) + " has no material or object named " + in_quotes(name));
    }
    if (uses_default_material_)
      materials_[kDefaultMaterial] = {{"passive", {{"reflectance", 0.5}}}};
    camera_["filter"] = filter_;
    if (exposure_time_ * iso_ / 100 != 1) camera_["exposure"] = exposure_time_ * iso_ / 100;
    // Moved, not copied: a scene of millions of shapes or instances is held once.
    nlohmann::json scene = {{"kasha_scene", 1}};
    scene["camera"] = std::move(camera_);
    scene["materials"] = std::move(materials_);
    if (!instances_.empty()) {
      scene["objects"] = placed_objects();
      scene["instances"] = std::move(instances_);
    }
    scene["shapes"] = std::move(shapes_);
    if (!lights_.empty()) scene["lights"] = std::move(lights_);
    check_medium_uses();
    if (!media_.empty()) scene["media"] = std::move(media_);
    if (!textures_.kasha.empty()) scene["textures"] = std::move(textures_.kasha);
    if (max_depth_) scene["max_depth"] = *max_depth_;
    return scene;
  }

 private:
  static constexpr const char* kDefaultMaterial = "pbrt-v4 default (diffuse 0.5)";

  static std::string absolute(const std::string& file) {
    return std::filesystem::absolute(file).lexically_normal().string();
  }

  void parse_file(const std::string& path, const std::string& shown, const PbrtLocation& from,
                  int depth) {
    if (depth > kMaxIncludeDepth)
      pbrt_fail(from, "Include nested deeper than " + std::to_string(kMaxIncludeDepth) +
                          " files (a file that includes itself?)");
    std::string text;
    try {
      // pbrt-v4 inflates any scene or Include whose name ends in .gz (core/gzip_input.h).
      text = read_input_file_inflated(path, kMaxBinaryInputBytes);
    } catch (const Error& e) {
      if (depth == 0) throw;
      pbrt_fail(from, e.what());
    }
    PbrtTokenizer tokens(std::move(text), shown);
    for (;;) {
      PbrtToken t = tokens.next();
      if (t.kind == PbrtToken::kEnd) return;
      if (t.kind != PbrtToken::kWord)
        pbrt_fail(t.where, "expected a directive, found " + in_quotes(t.text));
      directive(t, tokens, depth);
    }
  }

  // One argument of a directive.
  std::string string_arg(PbrtTokenizer& tokens, const PbrtToken& d) {
    PbrtToken t = tokens.next();
    if (t.kind != PbrtToken::kString) pbrt_fail(d.where, d.text + " expects a quoted string");
    return t.text;
  }

  std::vector<double> number_args(PbrtTokenizer& tokens, const PbrtToken& d, size_t n) {
    std::vector<double> v;
    PbrtToken t = tokens.next();
    const bool bracketed = t.kind == PbrtToken::kOpen;
    if (bracketed) t = tokens.next();
    for (;;) {
      if (t.kind == PbrtToken::kWord && v.size() < n) {
        char* end = nullptr;
        const double x = std::strtod(t.text.c_str(), &end);
        if (*end != '\0' || !std::isfinite(x))
          pbrt_fail(t.where, d.text + ": " + in_quotes(t.text) + " is not a finite number");
        v.push_back(x);
        if (v.size() == n && !bracketed) break;
        t = tokens.next();
        continue;
      }
      if (bracketed && t.kind == PbrtToken::kClose && v.size() == n) break;
      pbrt_fail(d.where, d.text + " expects " + std::to_string(n) + " numbers");
    }
    return v;
  }

  void apply(const Matrix& m, const PbrtToken& d) {
    if (end_time_only_) {
      warn_once(d.where, "motion",
                "ActiveTransform EndTime: kasha renders the start of the "
                "shutter, so transforms for the end time are ignored");
      return;
    }
    // A transform of the start time alone makes start and end differ: the scene moves.
    if (start_time_only_)
      warn_once(d.where, "motion",
                "motion blur is not built in kasha: the scene is rendered at the start of the "
                "shutter");
    state_.ctm = state_.ctm * m;
  }

  void warn_once(const PbrtLocation& where, const std::string& key, const std::string& what) {
    if (warned_.insert(key).second) pbrt_warn(where, what);
  }

  // A directive's parameters, with what Attribute set for `target` added (pbrt-v4's
  // Attribute "shape" | "light" | "material" | "medium" | "texture").
  PbrtParameters read_parameters(PbrtTokenizer& tokens, const std::string& target) {
    PbrtParameters params = PbrtParameters::read(tokens);
    params.set_color_space(state_.color_space);
    params.add_defaults(state_.attributes[target]);
    return params;
  }

  // pbrt-v4's two blocks (scene.cpp's VERIFY_OPTIONS and VERIFY_WORLD): rendering options before
  // WorldBegin, the scene's description after it.
  void check_block(const PbrtToken& d) const {
    static const std::set<std::string> options_only = {
        "Camera",      "Film",        "Sampler",        "Integrator",
        "PixelFilter", "Accelerator", "TransformTimes", "WorldBegin"};
    static const std::set<std::string> world_only = {
        "ReverseOrientation", "AttributeBegin",    "AttributeEnd",    "TransformBegin",
        "TransformEnd",       "LightSource",       "AreaLightSource", "Shape",
        "ObjectBegin",        "ObjectEnd",         "ObjectInstance",  "Texture",
        "Material",           "MakeNamedMaterial", "NamedMaterial"};
    if (world_begun_ && options_only.count(d.text))
      pbrt_fail(d.where, "options cannot be set inside the world block: " + in_quotes(d.text) +
                             " after WorldBegin (pbrt-v4 refuses it too)");
    if (!world_begun_ && world_only.count(d.text))
      pbrt_fail(d.where, "the scene's description belongs inside the world block: " +
                             in_quotes(d.text) + " before WorldBegin (pbrt-v4 refuses it too)");
  }

  void directive(const PbrtToken& d, PbrtTokenizer& tokens, int depth) {
    check_block(d);
    if (attribute_directive(d, tokens) || transform_directive(d, tokens) ||
        rendering_option_directive(d, tokens) || scene_element_directive(d, tokens) ||
        object_directive(d, tokens))
      return;
    if (d.text == "Include" || d.text == "Import") {
      const std::string file = string_arg(tokens, d);
      std::filesystem::path path(file);
      if (path.is_relative()) path = base_dir_ / path;
      parse_file(path.string(), file, d.where, depth + 1);
      return;
    }
    pbrt_fail(d.where, "unknown directive " + in_quotes(d.text));
  }

  // The graphics state's own directives: its save and restore, attributes, orientation and media.
  // False for a directive of another kind.
  bool attribute_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string& name = d.text;
    if (name == "AttributeBegin" || name == "TransformBegin") {
      stack_.push_back({state_, name == "TransformBegin", d.where});
    } else if (name == "AttributeEnd" || name == "TransformEnd") {
      if (stack_.empty() || stack_.back().transform_only != (name == "TransformEnd"))
        pbrt_fail(d.where, name + " without its " +
                               (name == "AttributeEnd" ? "AttributeBegin" : "TransformBegin"));
      if (stack_.back().transform_only)
        state_.ctm = stack_.back().state.ctm;
      else
        state_ = stack_.back().state;
      stack_.pop_back();
    } else if (name == "Attribute") {
      const std::string target = string_arg(tokens, d);
      if (target != "shape" && target != "light" && target != "material" && target != "medium" &&
          target != "texture")
        pbrt_fail(d.where, "Attribute: unknown target " + in_quotes(target));
      state_.attributes[target] = read_parameters(tokens, target);
    } else if (name == "ReverseOrientation") {
      state_.reverse_orientation = !state_.reverse_orientation;
    } else if (name == "MediumInterface") {
      state_.inside_medium = string_arg(tokens, d);
      PbrtToken t = tokens.next();
      if (t.kind == PbrtToken::kString)
        state_.outside_medium = t.text;
      else {
        state_.outside_medium = state_.inside_medium;
        tokens.put_back(std::move(t));
      }
    } else {
      return false;
    }
    return true;
  }

  // Directives that change the current transformation matrix or name it; false for others.
  bool transform_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string& name = d.text;
    if (name == "Identity") {
      if (!end_time_only_) state_.ctm = Matrix::Identity();
    } else if (name == "Translate") {
      const auto v = number_args(tokens, d, 3);
      Matrix m = Matrix::Identity();
      m.topRightCorner<3, 1>() = Eigen::Vector3d(v[0], v[1], v[2]);
      apply(m, d);
    } else if (name == "Scale") {
      const auto v = number_args(tokens, d, 3);
      apply(Eigen::Vector4d(v[0], v[1], v[2], 1).asDiagonal().toDenseMatrix(), d);
    } else if (name == "Rotate") {
      const auto v = number_args(tokens, d, 4);
      const Eigen::Vector3d axis(v[1], v[2], v[3]);
      if (axis.norm() == 0) pbrt_fail(d.where, "Rotate about a zero axis");
      Matrix m = Matrix::Identity();
      m.topLeftCorner<3, 3>() =
          Eigen::AngleAxisd(v[0] * M_PI / 180.0, axis.normalized()).toRotationMatrix();
      apply(m, d);
    } else if (name == "LookAt") {
      const auto v = number_args(tokens, d, 9);
      apply(look_at(d, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}), d);
    } else if (name == "Transform" || name == "ConcatTransform") {
      const auto v = number_args(tokens, d, 16);
      Matrix m;
      for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = v[i];  // pbrt's files are column-major
      if (name == "Transform") {
        if (!end_time_only_) state_.ctm = m;
      } else {
        apply(m, d);
      }
    } else if (name == "CoordinateSystem") {
      named_frames_[string_arg(tokens, d)] = state_.ctm;
    } else if (name == "CoordSysTransform") {
      const std::string frame = string_arg(tokens, d);
      auto f = named_frames_.find(frame);
      if (f == named_frames_.end())
        pbrt_warn(d.where, "CoordSysTransform: no coordinate system named " + in_quotes(frame) +
                               " (ignored, as pbrt-v4 does)");
      else
        state_.ctm = f->second;
    } else {
      return motion_directive(d, tokens);
    }
    return true;
  }

  // Motion blur's directives: kasha renders the start of the shutter. False for others.
  bool motion_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    if (d.text == "TransformTimes") {
      number_args(tokens, d, 2);
      warn_once(d.where, "motion",
                "motion blur is not built in kasha: the scene is rendered "
                "at the start of the shutter");
    } else if (d.text == "ActiveTransform") {
      PbrtToken which = tokens.next();
      start_time_only_ = which.text == "StartTime";
      if (which.text == "StartTime" || which.text == "All")
        end_time_only_ = false;
      else if (which.text == "EndTime")
        end_time_only_ = true;
      else
        pbrt_fail(d.where, "ActiveTransform takes StartTime, EndTime or All");
    } else {
      return false;
    }
    return true;
  }

  // The name a directive that kasha does not build gives, its parameters read and dropped.
  std::string skipped_directive(PbrtTokenizer& tokens, const PbrtToken& d) {
    const std::string type = string_arg(tokens, d);
    PbrtParameters::read(tokens);
    return type;
  }

  // The directives of the options block (camera, film, what kasha's command line decides) and
  // the start of the world; false for others.
  bool rendering_option_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string& name = d.text;
    if (name == "Option") {
      PbrtParameters::read(tokens).warn_unused("Option");
    } else if (name == "ColorSpace") {
      const std::string space = string_arg(tokens, d);
      const PbrtColorSpace* known = pbrt_color_space(space);
      if (!known)
        pbrt_fail(d.where, "ColorSpace " + in_quotes(space) +
                               ": unknown color space (srgb, rec2020, dci-p3, aces2065-1)");
      state_.color_space = known->name;
    } else if (name == "Camera") {
      const std::string type = string_arg(tokens, d);
      make_camera(state_.ctm, type, PbrtParameters::read(tokens), d.where);
      sources_["/camera"] = d.where.str();
      named_frames_["camera"] = state_.ctm.inverse();
    } else if (name == "Film") {
      const std::string type = string_arg(tokens, d);  // before the parameters that follow it
      film(type, PbrtParameters::read(tokens), d.where);
      sources_["/camera/width"] = sources_["/camera/height"] = d.where.str();
    } else if (name == "PixelFilter") {
      const std::string type = string_arg(tokens, d);
      pixel_filter(type, PbrtParameters::read(tokens), d.where);
      sources_["/camera/filter"] = d.where.str();
    } else if (name == "Integrator") {
      const std::string type = string_arg(tokens, d);
      max_depth_ = pbrt_integrator_max_depth(type, PbrtParameters::read(tokens), d.where);
    } else if (name == "Sampler" || name == "Accelerator") {
      pbrt_warn(d.where, name + " " + in_quotes(skipped_directive(tokens, d)) +
                             " is ignored: kasha's --integrator, --spp " +
                             "and --passes decide (docs/pbrt-import.md)");
    } else if (name == "MakeNamedMedium") {
      const std::string medium = string_arg(tokens, d);
      make_medium(medium, PbrtParameters::read(tokens), d.where);
    } else if (name == "WorldBegin") {
      if (!camera_seen_) make_camera(Matrix::Identity(), "perspective", PbrtParameters{}, d.where);
      state_.ctm = Matrix::Identity();
      named_frames_["world"] = state_.ctm;
      world_begun_ = true;
    } else if (name == "WorldEnd") {
      pbrt_warn(d.where, "WorldEnd is pbrt-v3's: ignored");
    } else {
      return false;
    }
    return true;
  }

  // Textures, materials, lights and shapes; false for other directives.
  bool scene_element_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string& name = d.text;
    if (name == "Texture") {
      const std::string tex = string_arg(tokens, d), kind = string_arg(tokens, d),
                        cls = string_arg(tokens, d);
      const PbrtParameters params = read_parameters(tokens, "texture");
      pbrt_define_texture(tex, kind, cls, params, d.where, state_.ctm, textures_, base_dir_);
      for (const std::string& made : textures_.added)
        sources_["/textures/" + pointer_segment(made)] = d.where.str();
      textures_.added.clear();
    } else if (name == "Material") {
      const std::string type = string_arg(tokens, d);
      const PbrtParameters params = read_parameters(tokens, "material");
      const std::string key = "pbrt material at " + d.where.str();
      define_material(key, type, params, d.where);
      // pbrt-v4 creates the named materials first: a mix here may name any of them.
      if (type == "mix") anonymous_mixes_.emplace_back(key, d.where);
      state_.material = key;
    } else if (name == "MakeNamedMaterial") {
      make_named_material(d, tokens);
    } else if (name == "NamedMaterial") {
      state_.material = string_arg(tokens, d);
      named_material_uses_.emplace(state_.material, d.where);
    } else if (name == "LightSource") {
      const std::string type = string_arg(tokens, d);
      light(type, read_parameters(tokens, "light"), d.where);
    } else if (name == "AreaLightSource") {
      auto area = std::make_shared<AreaLight>();
      area->type = string_arg(tokens, d);
      area->params = read_parameters(tokens, "light");
      area->where = d.where;
      if (area->type != "diffuse")
        pbrt_fail(d.where,
                  "AreaLightSource " + in_quotes(area->type) + " is not built in kasha (diffuse)");
      state_.area_light = area;
    } else if (name == "Shape") {
      const std::string type = string_arg(tokens, d);
      shape(type, read_parameters(tokens, "shape"), d.where);
    } else {
      return false;
    }
    return true;
  }

  void make_named_material(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string material = string_arg(tokens, d);
    const PbrtParameters params = read_parameters(tokens, "material");
    const std::string type = params.get_string("type", "");
    if (type.empty())
      pbrt_fail(d.where, "MakeNamedMaterial " + in_quotes(material) + " has no \"string type\"");
    if (named_materials_.count(material))
      pbrt_fail(d.where, "MakeNamedMaterial " + in_quotes(material) + " defined twice");
    named_materials_.insert(material);
    define_material(material, type, params, d.where);
    check_mix_parts(material, d.where);
  }

  // A mix's materials are named materials that are surfaces; pbrt-v4 creates named materials in
  // order, so a named mix may name only those defined before it (which also rules out a loop).
  void check_mix_parts(const std::string& key, const PbrtLocation& where) const {
    const auto m = materials_.find(key);
    if (m == materials_.end() || !m->contains("mix")) return;
    for (const auto& part : (*m)["mix"]["materials"]) {
      const std::string name = part.get<std::string>();
      if (interfaces_.count(name))
        pbrt_fail(where, "mix: " + in_quotes(name) +
                             " is an \"interface\" material, which a mix cannot hold");
      if (name == key || !named_materials_.count(name) || !materials_.contains(name))
        pbrt_fail(where, "mix: no named material " + in_quotes(name) + " defined before it");
    }
  }

  // Object definitions and their instances; false for other directives.
  bool object_directive(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string& name = d.text;
    if (name == "ObjectBegin") {
      if (object_) pbrt_fail(d.where, "ObjectBegin inside another object");
      const std::string object = string_arg(tokens, d);
      if (objects_.count(object)) pbrt_fail(d.where, "ObjectBegin " + in_quotes(object) + " twice");
      stack_.push_back({state_, false, d.where});
      object_ = &objects_[object];
      object_->where = d.where;
    } else if (name == "ObjectEnd") {
      if (!object_) pbrt_fail(d.where, "ObjectEnd without its ObjectBegin");
      object_ = nullptr;
      if (stack_.empty() || stack_.back().transform_only)
        pbrt_fail(d.where, "ObjectEnd without its ObjectBegin");
      state_ = stack_.back().state;
      stack_.pop_back();
    } else if (name == "ObjectInstance") {
      instance_object(d, tokens);
    } else {
      return false;
    }
    return true;
  }

  void instance_object(const PbrtToken& d, PbrtTokenizer& tokens) {
    const std::string object = string_arg(tokens, d);
    if (object_) pbrt_fail(d.where, "ObjectInstance inside an object definition");
    auto o = objects_.find(object);
    if (o == objects_.end())
      pbrt_fail(d.where, "ObjectInstance: no object named " + in_quotes(object));
    std::string material;
    if (overrides_.count(object)) {
      material = "pbrt object " + object;
      materials_[material] = {{"file", absolute(overrides_[object])}};
      overridden_objects_.insert(object);
    }
    if (o->second.shapes.empty()) return;
    // Kept as an instance (docs/formats.md#instances): the object's triangles are stored
    // once, however often it is placed.
    check_affine(state_.ctm, d.where);
    const std::string at = "/instances/" + std::to_string(instances_.size());
    sources_[at] = d.where.str();
    instances_.push_back({{"object", object}, {"transform", {{"matrix", row_major(state_.ctm)}}}});
    o->second.material = material;
  }

  // The objects that instances place, as kasha's "objects" (their shapes in object space).
  nlohmann::json placed_objects() {
    nlohmann::json out = nlohmann::json::object();
    for (const nlohmann::json& in : instances_) {
      const std::string name = in["object"].get<std::string>();
      if (out.contains(name)) continue;
      const ObjectDefinition& o = objects_.at(name);
      nlohmann::json shapes = nlohmann::json::array();
      for (const DefinedShape& s : o.shapes) {
        nlohmann::json shape = s.shape;
        if (!o.material.empty()) shape["material"] = o.material;
        if (!s.ctm.isIdentity(0)) shape["transform"] = {{"matrix", row_major(s.ctm)}};
        sources_["/objects/" + escape_pointer(name) + "/" + std::to_string(shapes.size())] =
            s.where.str();
        shapes.push_back(std::move(shape));
      }
      out[name] = std::move(shapes);
    }
    return out;
  }

  Matrix look_at(const PbrtToken& d, const Eigen::Vector3d& pos, const Eigen::Vector3d& look,
                 const Eigen::Vector3d& up) {
    // pbrt-v4's LookAt: the camera-from-world matrix of a left-handed frame.
    const Eigen::Vector3d dir = look - pos;
    if (dir.norm() == 0) pbrt_fail(d.where, "LookAt: the eye and the target are the same point");
    const Eigen::Vector3d right = up.normalized().cross(dir.normalized());
    if (up.norm() == 0 || right.norm() < 1e-9)
      pbrt_fail(d.where, "LookAt: \"up\" is zero or parallel to the view direction");
    const Eigen::Vector3d r = right.normalized(), z = dir.normalized(), u = z.cross(r);
    Matrix world_from_camera = Matrix::Identity();
    world_from_camera.block<3, 1>(0, 0) = r;
    world_from_camera.block<3, 1>(0, 1) = u;
    world_from_camera.block<3, 1>(0, 2) = z;
    world_from_camera.block<3, 1>(0, 3) = pos;
    return world_from_camera.inverse();
  }

  // pbrt-v4's PixelFilter, kept with the camera (scene/pixel_filter.h); pbrt-v4's default when a
  // scene names none is its gaussian, set in run().
  void pixel_filter(const std::string& type, const PbrtParameters& params,
                    const PbrtLocation& where) {
    if (!is_pixel_filter(type))
      pbrt_fail(where, "PixelFilter " + in_quotes(type) + " is not one of pbrt-v4's filters");
    const PixelFilter defaults = default_pixel_filter(type);
    const double rx = params.get_float("xradius", defaults.radius[0]);
    const double ry = params.get_float("yradius", defaults.radius[1]);
    if (!(rx > 0 && ry > 0 && rx <= KASHA_FILTER_MAX_RADIUS && ry <= KASHA_FILTER_MAX_RADIUS))
      pbrt_fail(where, "a PixelFilter radius must be above 0 and at most " +
                           std::to_string(KASHA_FILTER_MAX_RADIUS) + " pixels in kasha");
    filter_ = {{"type", type}, {"radius", {rx, ry}}};
    if (type == "gaussian") filter_["sigma"] = params.get_float("sigma", defaults.sigma);
    if (type == "mitchell") {
      filter_["B"] = params.get_float("B", defaults.b);
      filter_["C"] = params.get_float("C", defaults.c);
    }
    if (type == "lanczos") filter_["tau"] = params.get_float("tau", defaults.tau);
    params.warn_unused("PixelFilter " + in_quotes(type));
    if (defaults.has_negative_lobes())
      pbrt_warn(where, "PixelFilter " + in_quotes(type) +
                           ": kasha keeps its positive part (the negative lobes sharpen "
                           "pbrt-v4's image slightly)");
  }

  void make_camera(const Matrix& camera_from_world, const std::string& type,
                   const PbrtParameters& params, const PbrtLocation& where) {
    if (camera_seen_) pbrt_fail(where, "a second Camera");
    camera_seen_ = true;
    if (type != "perspective" && type != "orthographic" && type != "spherical")
      pbrt_fail(where, "Camera " + in_quotes(type) +
                           " is not built in kasha (perspective, orthographic, spherical)");
    if (std::abs(camera_from_world.determinant()) < 1e-300)
      pbrt_fail(where, "the camera's transform is singular");
    const Matrix world_from_camera = camera_from_world.inverse();
    const Eigen::Vector3d pos = point(world_from_camera, {0, 0, 0});
    const Eigen::Vector3d forward = direction(world_from_camera, {0, 0, 1}).normalized();
    const Eigen::Vector3d up = direction(world_from_camera, {0, 1, 0}).normalized();
    const Eigen::Vector3d right = direction(world_from_camera, {1, 0, 0});
    if (std::abs(forward.dot(up)) > 1e-6)
      pbrt_warn(where,
                "the camera's transform shears its axes: kasha uses its view direction "
                "and up");
    camera_["position"] = triple(pos);
    camera_["look_at"] = triple(pos + forward);
    camera_["up"] = triple(up);
    // kasha's image right is forward × up; pbrt-v4's is the camera's +x, the other way in its
    // left-handed frame (unless the scene mirrors it, as `Scale -1 1 1` does).
    camera_["mirror"] = right.dot(forward.cross(up)) < 0;
    camera_["type"] = type;
    camera_projection(type, params, where);
    // pbrt-v4's exposure time, a factor of the film's imaging ratio (PixelSensor::Create).
    // pbrt-v4 swaps a shutter that closes before it opens.
    exposure_time_ =
        std::abs(params.get_float("shutterclose", 1) - params.get_float("shutteropen", 0));
    if (!(exposure_time_ > 0))
      pbrt_fail(where, "Camera: the shutter opens and closes at once (no exposure)");
    params.warn_unused("Camera " + in_quotes(type));
    // pbrt-v4's CameraMedium: the current outside medium.
    if (!state_.outside_medium.empty())
      camera_["medium"] = used_medium(state_.outside_medium, where);
    if (!camera_.contains("width")) {
      camera_["width"] = 1280;  // pbrt-v4's film defaults, unless a Film came first
      camera_["height"] = 720;
    }
  }

  // What pbrt-v4's CameraBase and each camera's Create read besides the transform (cameras.cpp).
  void camera_projection(const std::string& type, const PbrtParameters& params,
                         const PbrtLocation& where) {
    if (type == "spherical") {
      const std::string mapping = params.get_string("mapping", "equalarea");
      if (mapping != "equalarea" && mapping != "equirectangular")
        pbrt_fail(where, "Camera \"spherical\": unknown \"mapping\" " + in_quotes(mapping) +
                             " (equalarea, equirectangular)");
      camera_["mapping"] = mapping;
      params.get_float("lensradius", 0);  // pbrt-v4 reads them and renders a pinhole
      params.get_float("focaldistance", 1e30);
      params.get_float("frameaspectratio", 1);
      params.get_numbers("screenwindow", "float");
      return;
    }
    if (type == "perspective") camera_["fov_deg"] = params.get_float("fov", 90);
    const double lens = params.get_float("lensradius", 0);
    const double focus = params.get_float("focaldistance", 1e6);
    if (lens < 0 || !(focus > 0))
      pbrt_fail(where, "a negative \"lensradius\" or a \"focaldistance\" ≤ 0");
    if (lens > 0 && type == "perspective") {
      camera_["lens_radius"] = lens;
      camera_["focal_distance"] = focus;
    } else if (lens > 0) {
      pbrt_warn(where, "the orthographic camera's lens is not built in kasha: a pinhole renders");
    }
    // pbrt-v4's default screen window: the shorter side spans [−1, 1] at the frame's aspect.
    const double frame = params.get_float("frameaspectratio", 0);
    if (frame > 0)
      camera_["screen_window"] = frame > 1 ? std::vector<double>{-frame, frame, -1, 1}
                                           : std::vector<double>{-1, 1, -1 / frame, 1 / frame};
    const std::vector<double> w = params.get_numbers("screenwindow", "float");
    if (!w.empty()) {
      if (w.size() != 4 || !(w[0] < w[1] && w[2] < w[3]))
        pbrt_fail(where, "\"screenwindow\" is four numbers x0 < x1, y0 < y1");
      camera_["screen_window"] = w;
    }
  }

  void film(const std::string& type, const PbrtParameters& params, const PbrtLocation& where) {
    if (type != "rgb" && type != "spectral" && type != "gbuffer")
      pbrt_fail(where, "Film " + in_quotes(type) + " is not built in kasha");
    const int w = params.get_int("xresolution", 1280), h = params.get_int("yresolution", 720);
    if (w < 1 || w > 16384 || h < 1 || h > 16384)
      pbrt_fail(where, "a film of " + std::to_string(w) + " × " + std::to_string(h) +
                           " pixels (kasha renders 1–16384 a side)");
    camera_["width"] = w;
    camera_["height"] = h;
    params.get_string("filename", "");  // kasha writes where -o says
    if (params.find("cropwindow", "float") || params.find("pixelbounds", "integer"))
      pbrt_warn(where, "a crop window is not built in kasha: the whole frame renders");
    // pbrt-v4's imaging ratio, exposure time × ISO / 100, scales the image (camera "exposure");
    // another sensor's curves and a white balance are not built.
    iso_ = params.get_float("iso", 100);
    if (!(iso_ > 0)) pbrt_fail(where, "Film: \"iso\" must be positive");
    const std::string sensor = params.get_string("sensor", "cie1931");
    const double white = params.get_float("whitebalance", 0);
    if (sensor != "cie1931" || white != 0)
      pbrt_warn(where,
                "the film's \"sensor\" and \"whitebalance\" are not built in kasha: it records "
                "XYZ as pbrt-v4's default cie1931 sensor (its ISO and exposure time are applied)");
    for (const char* ignored : {"maxcomponentvalue", "diagonal"}) params.get_float(ignored, 0);
    params.get_bool("savefp16", true);
    // The film's own output space: kasha's film records XYZ and writes its own (formats.md).
    const std::string space = params.get_string("colorspace", "srgb");
    if (!pbrt_color_space(space))
      pbrt_fail(where, "Film: unknown \"colorspace\" " + in_quotes(space) +
                           " (srgb, rec2020, dci-p3, aces2065-1)");
    params.get_bool("writefp16", true);
    params.warn_unused("Film " + in_quotes(type));
  }

  void define_material(const std::string& key, const std::string& type,
                       const PbrtParameters& params, const PbrtLocation& where) {
    nlohmann::json m = pbrt_material(type, params, where, textures_, base_dir_);
    // A scaled texture the material made for itself (a roughness texture's) is the material's.
    for (const std::string& made : textures_.added)
      sources_["/textures/" + pointer_segment(made)] = where.str();
    textures_.added.clear();
    if (m.is_null()) {
      interfaces_.insert(key);
    } else {
      materials_[key] = m;
      sources_["/materials/" + pointer_segment(key)] = where.str();
    }
  }

  // MakeNamedMedium (pbrt-v4's media.cpp): a homogeneous, uniformgrid or nanovdb medium as kasha's
  // "media" entry; the other types are read but refused where a shape, the camera or a light is put
  // in one.
  void make_medium(const std::string& name, const PbrtParameters& params, const PbrtLocation& where) {
    const std::string type = params.get_string("type", "");
    if (type.empty()) pbrt_fail(where, "MakeNamedMedium " + in_quotes(name) + ": no \"type\"");
    if (name.empty()) pbrt_fail(where, "MakeNamedMedium: a medium's name must not be empty");
    if (type != "homogeneous" && type != "uniformgrid" && type != "rgbgrid" && type != "nanovdb") {
      refuse_medium(name, where,
                    "is a " + in_quotes(type) +
                        " medium, which kasha does not build (homogeneous, "
                        "uniformgrid, rgbgrid, nanovdb)");
      return;
    }
    if (type == "rgbgrid") return rgb_grid_medium(name, params, where);
    if (type == "nanovdb" && params.get_string("filename", "").empty())
      pbrt_fail(where, "MakeNamedMedium " + in_quotes(name) +
                           ": Must supply \"filename\" to \"nanovdb\" medium");
    if (params.find("preset", "string"))
      pbrt_fail(where, "MakeNamedMedium " + in_quotes(name) +
                           ": \"preset\" is not built in kasha: give \"sigma_a\" and \"sigma_s\"");
    const PbrtParameter* le =
        type == "nanovdb" ? nullptr : params.find("Le", "rgb spectrum blackbody float");
    nlohmann::json emission;
    if (le) {
      const nlohmann::json v = pbrt_spectrum(*le, PbrtSpectrumUse::kIlluminant, base_dir_);
      // pbrt-v4: Le over its photometric integral, as a light's, times "Lescale" — a number for
      // a homogeneous medium, a grid of its own for a uniformgrid (grid_medium).
      const double le_scale = type == "homogeneous" ? params.get_float("Lescale", 1) : 1;
      if (!(v.is_number() && v.get<double>() == 0) && le_scale != 0)
        emission = pbrt_light_spectrum(le, le_scale, base_dir_);
    }
    nlohmann::json m = {{"type", "homogeneous"}};
    if (type == "uniformgrid")
      m = grid_medium(name, params, where, le != nullptr, !emission.is_null());
    if (type == "nanovdb") m = vdb_medium(name, params, where);
    for (const char* key : {"sigma_a", "sigma_s"})
      if (const PbrtParameter* p = params.find(key, "rgb spectrum blackbody float"))
        m[key] = pbrt_spectrum(*p, PbrtSpectrumUse::kUnbounded, base_dir_);
    m["scale"] = params.get_float("scale", 1);
    m["g"] = params.get_float("g", 0);
    if (!emission.is_null()) m["emission"] = emission;
    add_medium(name, m, params, where);
  }

  // A medium kasha builds as the JSON entry m: its parameters not read are warned about, and it
  // takes the place of any earlier one of its name (refused or not).
  void add_medium(const std::string& name, const nlohmann::json& m, const PbrtParameters& params,
                  const PbrtLocation& where) {
    params.warn_unused("MakeNamedMedium " + in_quotes(name));
    media_[name] = m;
    refused_media_.erase(name);
    sources_["/media/" + pointer_segment(name)] = where.str();
  }

  // pbrt-v4's uniformgrid (GridMedium::Create): its density samples over [p0, p1] in the space of
  // the transform current at MakeNamedMedium; its emission (an "Le" or a "temperature" grid,
  // times an "Lescale" grid) in emitting_grid.
  nlohmann::json grid_medium(const std::string& name, const PbrtParameters& params,
                             const PbrtLocation& where, bool has_le, bool emits_le) {
    const std::string what = "MakeNamedMedium " + in_quotes(name);
    const std::vector<double> density = params.get_numbers("density", "float");
    if (density.empty()) pbrt_fail(where, what + ": no \"density\" value provided for grid medium");
    const int nx = params.get_int("nx", 1), ny = params.get_int("ny", 1),
              nz = params.get_int("nz", 1);
    if (nx < 1 || ny < 1 || nz < 1 ||
        static_cast<double>(nx) * ny * nz != static_cast<double>(density.size()))
      pbrt_fail(where, what + ": " + std::to_string(density.size()) +
                           " density values for nx*ny*nz = " +
                           std::to_string(static_cast<long long>(nx) * ny * nz));
    for (double v : density)
      if (!(v >= 0 && std::isfinite(v)))
        pbrt_fail(where, what + ": a density must be finite and not negative");
    nlohmann::json m = {{"type", "grid"},
                        {"density", {{"size", {nx, ny, nz}}, {"values", density}}}};
    grid_box(m, params, where, what);
    emitting_grid(m, params, where, what, density.size(), has_le, emits_le);
    return m;
  }

  // A grid medium's box, [p0, p1] in the space of the transform current at MakeNamedMedium.
  void grid_box(nlohmann::json& m, const PbrtParameters& params, const PbrtLocation& where,
                const std::string& what) {
    // pbrt-v4's Bounds3f(p0, p1) takes the corners in either order.
    auto p0 = params.get_triple("p0").value_or(std::array<double, 3>{0, 0, 0});
    auto p1 = params.get_triple("p1").value_or(std::array<double, 3>{1, 1, 1});
    for (int c = 0; c < 3; ++c) {
      if (p1[c] < p0[c]) std::swap(p0[c], p1[c]);
      if (!(p0[c] < p1[c]))
        pbrt_fail(where, what + ": \"p0\" and \"p1\" must differ on every axis");
    }
    check_affine(state_.ctm, where);
    m["bounds"] = {{"min", p0}, {"max", p1}};
    m["transform"] = {{"matrix", row_major(state_.ctm)}};
  }

  // pbrt-v4's rgbgrid (RGBGridMedium::Create): an RGB of σa and of σs per sample (either may be
  // absent: 1 in the whole box), "scale", "g", and an RGB illuminant "Le" per sample times
  // "Lescale" (1): it emits σa·Le (none where Lescale ≤ 0, as pbrt-v4's IsEmissive).
  void rgb_grid_medium(const std::string& name, const PbrtParameters& params,
                       const PbrtLocation& where) {
    const std::string what = "MakeNamedMedium " + in_quotes(name);
    const std::vector<double> sigma_a = colour_array(params, "sigma_a", where, what, true);
    const std::vector<double> sigma_s = colour_array(params, "sigma_s", where, what, true);
    const std::vector<double> le = colour_array(params, "Le", where, what, false);
    if (sigma_a.empty() && sigma_s.empty())
      pbrt_fail(where,
                what + ": RGB grid requires \"sigma_a\" and/or \"sigma_s\" parameter values.");
    const size_t n = (sigma_a.empty() ? sigma_s : sigma_a).size() / 3;
    if (!sigma_a.empty() && !sigma_s.empty() && sigma_a.size() != sigma_s.size())
      pbrt_fail(where, what + ": Different number of samples (" + std::to_string(n) + " vs " +
                           std::to_string(sigma_s.size() / 3) +
                           ") provided for \"sigma_a\" and \"sigma_s\".");
    if (!le.empty() && sigma_a.empty())
      pbrt_fail(where, what + ": RGB grid requires \"sigma_a\" if \"Le\" value provided.");
    if (!le.empty() && le.size() != 3 * n)
      pbrt_fail(where, what + ": Expected " + std::to_string(n) +
                           " values for \"Le\" parameter but were given " +
                           std::to_string(le.size() / 3) + ".");
    const int nx = params.get_int("nx", 1), ny = params.get_int("ny", 1),
              nz = params.get_int("nz", 1);
    if (nx < 1 || ny < 1 || nz < 1 || static_cast<double>(nx) * ny * nz != static_cast<double>(n))
      pbrt_fail(where, what + ": RGB grid medium has " + std::to_string(n) +
                           " density values; expected nx*ny*nz = " +
                           std::to_string(static_cast<long long>(nx) * ny * nz));
    nlohmann::json m = {{"type", "rgbgrid"}, {"size", {nx, ny, nz}}};
    if (!sigma_a.empty()) m["sigma_a"] = {{"rgb_values", sigma_a}};
    if (!sigma_s.empty()) m["sigma_s"] = {{"rgb_values", sigma_s}};
    grid_box(m, params, where, what);
    m["scale"] = params.get_float("scale", 1);
    m["g"] = params.get_float("g", 0);
    if (const double scale = params.get_float("Lescale", 1); !le.empty() && scale > 0) {
      m["emission"] = {{"rgb_values", le}};
      m["emission_scale"] = scale;
    }
    add_medium(name, m, params, where);
  }

  // An "rgb" array of an rgbgrid as linear sRGB (from its ColorSpace), each part ≥ 0; `adapt`:
  // a coefficient's colour (chromatically adapted), else an illuminant's (its XYZ kept).
  std::vector<double> colour_array(const PbrtParameters& params, const std::string& key,
                                   const PbrtLocation& where, const std::string& what, bool adapt) {
    const PbrtParameter* p = params.find(key, "rgb");
    if (!p) return {};
    std::vector<double> v = p->numbers;
    if (v.size() % 3 != 0) pbrt_fail(where, what + ": \"rgb " + key + "\" takes RGB triples");
    for (double x : v)
      if (!(x >= 0 && std::isfinite(x)))
        pbrt_fail(where, what + ": \"rgb " + key + "\" has a negative component");
    if (p->color_space == "srgb") return v;
    const PbrtColorSpace* space = pbrt_color_space(p->color_space);
    if (!space) pbrt_fail(where, "unknown color space " + in_quotes(p->color_space));
    for (size_t i = 0; i < v.size(); i += 3) {
      const std::array<double, 3> c = pbrt_rgb_to_srgb(*space, {v[i], v[i + 1], v[i + 2]}, adapt);
      for (int k = 0; k < 3; ++k) v[i + k] = std::max(c[k], 0.0);
    }
    return v;
  }

  // A uniformgrid's emission as pbrt-v4's GridMedium::Create reads it: a "temperature" per sample
  // (its blackbody, with "temperatureoffset" or "temperaturecutoff" and "temperaturescale") or
  // "Le", either times an "Lescale" per sample.
  void emitting_grid(nlohmann::json& m, const PbrtParameters& params, const PbrtLocation& where,
                     const std::string& what, size_t samples, bool has_le, bool emits_le) {
    const std::vector<double> temperature = params.get_numbers("temperature", "float");
    const std::vector<double> le_scale = params.get_numbers("Lescale", "float");
    const double offset =
        params.get_float("temperatureoffset", params.get_float("temperaturecutoff", 0));
    const double scale = params.get_float("temperaturescale", 1);
    if (!temperature.empty()) {
      if (temperature.size() != samples)
        pbrt_fail(where, what + ": different number of samples (" + std::to_string(samples) +
                             " vs " + std::to_string(temperature.size()) +
                             ") provided for \"density\" and \"temperature\"");
      if (has_le) pbrt_fail(where, what + ": both \"Le\" and \"temperature\" values were provided");
      m["temperature"] = {{"values", temperature}};
      m["temperature_offset"] = offset;
      m["temperature_scale"] = scale;
    }
    if (!le_scale.empty() && le_scale.size() != samples)
      pbrt_fail(where, what + ": expected " + std::to_string(samples) +
                           " values for \"Lescale\" but were given " +
                           std::to_string(le_scale.size()));
    if (!le_scale.empty() && (emits_le || !temperature.empty()))
      m["emission_scale"] = {{"values", le_scale}};
  }

  // A medium kasha does not build: refused where a shape, the camera or a light is put in it.
  void refuse_medium(const std::string& name, const PbrtLocation& where, const std::string& why) {
    refused_media_[name] = "MakeNamedMedium " + in_quotes(name) + " (" + where.str() + ") " + why;
    media_.erase(name);
  }

  std::filesystem::path vdb_file(const PbrtParameters& params) const {
    std::filesystem::path path(params.get_string("filename", ""));
    return path.is_relative() && !path.empty() ? base_dir_ / path : path;
  }

  // pbrt-v4's nanovdb medium (NanoVDBMedium::Create): its "gridname" grid of a NanoVDB .nvdb file
  // (or of an OpenVDB .vdb file: the contents decide), in the space of the transform current at
  // MakeNamedMedium; with its "temperaturename" grid, the blackbody of its temperature times
  // "Lescale".
  nlohmann::json vdb_medium(const std::string& name, const PbrtParameters& params,
                            const PbrtLocation& where) {
    const std::string what = "MakeNamedMedium " + in_quotes(name);
    const std::filesystem::path file = vdb_file(params);
    const std::string grid = params.get_string("gridname", "density");
    const std::string temperature = params.get_string("temperaturename", "temperature");
    const double le_scale = params.get_float("Lescale", 1);
    const double offset =
        params.get_float("temperatureoffset", params.get_float("temperaturecutoff", 0));
    const double scale = params.get_float("temperaturescale", 1);
    check_affine(state_.ctm, where);
    // As a mesh's "filename": relative to the scene's folder, which the JSON reader resolves.
    nlohmann::json m = {{"type", "grid"},
                        {"density", {{"vdb", params.get_string("filename", "")}, {"grid", grid}}},
                        {"transform", {{"matrix", row_major(state_.ctm)}}}};
    // NanoVDBMedium: a file with its temperature grid emits LeScale times the blackbody.
    if (le_scale != 0 && vdb_has_grid(file.string(), temperature)) {
      if (!(le_scale > 0)) pbrt_fail(where, what + ": \"Lescale\" must not be negative");
      m["temperature"] = {{"vdb", params.get_string("filename", "")}, {"grid", temperature}};
      m["temperature_offset"] = offset;
      m["temperature_scale"] = scale;
      m["emission_scale"] = le_scale;
    }
    return m;
  }

  // A medium that a shape, the camera or a light is put in: its name, or null for vacuum ("").
  // pbrt-v4 resolves the names once the whole file is read (check_medium_uses).
  nlohmann::json used_medium(const std::string& name, const PbrtLocation& where) {
    if (name.empty()) return nullptr;
    medium_uses_.emplace(name, where);
    return name;
  }

  void check_medium_uses() const {
    for (const auto& [name, where] : medium_uses_) {
      if (auto r = refused_media_.find(name); r != refused_media_.end()) pbrt_fail(where, r->second);
      if (!media_.contains(name))
        pbrt_fail(where, "no medium named " + in_quotes(name) + " (MakeNamedMedium)");
    }
  }

  void light(const std::string& type, const PbrtParameters& params, const PbrtLocation& where) {
    if (object_) pbrt_fail(where, "LightSource inside an object definition");
    const double scale = params.get_float("scale", 1);
    if (!(scale >= 0)) pbrt_fail(where, "a light's \"scale\" must not be negative");
    const Matrix& m = state_.ctm;
    nlohmann::json l;
    if (type == "point" || type == "spot") {
      const PbrtParameter* I = params.find("I", "rgb spectrum blackbody float");
      double power_scale = 1;
      const double power = params.get_float("power", -1);
      const Eigen::Vector3d from = vec(params.get_triple("from"), {0, 0, 0});
      l = {{"type", type}};
      if (type == "point") {
        if (power > 0) power_scale = power / (4 * M_PI);
        l["position"] = triple(point(m, from));
      } else {
        const Eigen::Vector3d to = vec(params.get_triple("to"), {0, 0, 1});
        const double cone = params.get_float("coneangle", 30),
                     delta = params.get_float("conedeltaangle", 5);
        if (power > 0) {
          const double c_end = std::cos(cone * M_PI / 180),
                       c_start = std::cos((cone - delta) * M_PI / 180);
          power_scale = power / (2 * M_PI * ((1 - c_start) + (c_start - c_end) / 2));
        }
        l["from"] = triple(point(m, from));
        l["to"] = triple(point(m, to));
        l["cone_deg"] = cone;
        l["cone_delta_deg"] = delta;
      }
      l["intensity"] = pbrt_light_spectrum(I, scale * power_scale, base_dir_);
    } else if (type == "distant") {
      const PbrtParameter* L = params.find("L", "rgb spectrum blackbody float");
      const Eigen::Vector3d from = vec(params.get_triple("from"), {0, 0, 0}),
                            to = vec(params.get_triple("to"), {0, 0, 1});
      const double illuminance = params.get_float("illuminance", -1);
      l = {{"type", "distant"},
           {"from", triple(point(m, from))},
           {"to", triple(point(m, to))},
           {"irradiance",
            pbrt_light_spectrum(L, scale * (illuminance > 0 ? illuminance : 1), base_dir_)}};
    } else if (type == "infinite") {
      const PbrtParameter* L = params.find("L", "rgb spectrum blackbody float");
      const std::string file = params.get_string("filename", "");
      if (params.find("portal", "point3"))
        pbrt_warn(where, "portals are not built in kasha: the light is sampled without them");
      const double illuminance = params.get_float("illuminance", -1);
      if (illuminance > 0)
        pbrt_fail(where,
                  "an infinite light's \"illuminance\" is not built in kasha: give "
                  "\"scale\"");
      if (L && !file.empty())
        pbrt_fail(where, "an infinite light takes \"L\" or \"filename\", not both");
      l = {{"type", "infinite"}};
      if (!file.empty()) {
        // pbrt-v4's environment maps are square, equal-area, and divided by D65's photometric
        // integral as its RGB-illuminant lights are.
        l["image"] = file;
        l["mapping"] = "equal_area";
        l["scale"] = scale / pbrt_d65_photometric();
        // Any invertible transform, as pbrt-v4 applies it to directions (normalised after it):
        // its 3 × 3 part alone, so a translation or a projective bottom row changes nothing.
        Matrix rot = m;
        rot.topRightCorner<3, 1>().setZero();
        rot.bottomLeftCorner<1, 3>().setZero();
        rot(3, 3) = 1;
        const Eigen::Matrix3d r = rot.topLeftCorner<3, 3>();
        if (!(std::abs(r.determinant()) > 1e-12 * std::pow(r.norm(), 3)))
          pbrt_fail(where, "an environment image's transform is not invertible");
        if (!r.isApprox(Eigen::Matrix3d::Identity(), 1e-12))
          l["transform"] = {{"matrix", row_major(rot)}};
      } else {
        l["radiance"] = pbrt_light_spectrum(L, scale, base_dir_);
      }
    } else if (type == "goniometric" || type == "projection") {
      pbrt_fail(where, "LightSource " + in_quotes(type) +
                           " is not built in kasha (point, spot, "
                           "distant, infinite)");
    } else {
      pbrt_fail(where, "unknown light type " + in_quotes(type));
    }
    params.warn_unused("LightSource " + in_quotes(type));
    // pbrt-v4 puts a light in the current outside medium; only a point or spot is inside the scene.
    if ((type == "point" || type == "spot") && !state_.outside_medium.empty())
      l["medium"] = used_medium(state_.outside_medium, where);
    sources_["/lights/" + std::to_string(lights_.size())] = where.str();
    lights_.push_back(l);
  }

  static Eigen::Vector3d vec(const std::optional<std::array<double, 3>>& a,
                             const Eigen::Vector3d& fallback) {
    return a ? Eigen::Vector3d((*a)[0], (*a)[1], (*a)[2]) : fallback;
  }

  void shape(const std::string& type, const PbrtParameters& params, const PbrtLocation& where) {
    nlohmann::json s = pbrt_shape(type, params, where);
    if (s.is_null()) return;
    pbrt_shape_alpha(params, textures_, s);
    std::string material = state_.material;
    if (material.empty()) {
      material = kDefaultMaterial;
      uses_default_material_ = true;
    }
    // A boundary between two media (pbrt-v4 keeps a ray's medium across any other shape).
    const bool transition = state_.inside_medium != state_.outside_medium;
    if (transition)
      s["medium"] = {{"inside", used_medium(state_.inside_medium, where)},
                     {"outside", used_medium(state_.outside_medium, where)}};
    if (interfaces_.count(material)) {
      if (state_.area_light) pbrt_fail(where, "an area light on an \"interface\" (no surface)");
      if (!transition) {
        warn_once(where, "interface", "an \"interface\" shape between the same media on both "
                                      "sides bounds nothing: left out");
        return;
      }
      s["interface"] = true;
    } else {
      s["material"] = material;
    }
    // A mesh's own normals decide its front in pbrt-v4 (pbrt_shapes.cpp turned the winding to
    // them), whatever ReverseOrientation says; every other shape is turned.
    const bool normals_decide =
        (type == "trianglemesh" || type == "loopsubdiv") && s.contains("normals");
    if (state_.reverse_orientation && !normals_decide)
      s["reverse_orientation"] = !s.value("reverse_orientation", false);
    if (object_) {
      if (state_.area_light)
        pbrt_fail(where, "an area light inside an object definition (pbrt-v4 refuses it too)");
      check_affine(state_.ctm, where);
      object_->shapes.push_back({s, state_.ctm, where});
      return;
    }
    if (state_.area_light) {
      const AreaLight& a = *state_.area_light;
      const PbrtParameter* L = a.params.find("L", "rgb spectrum blackbody float");
      const double scale = a.params.get_float("scale", 1);
      if (a.params.get_float("power", -1) > 0)
        pbrt_fail(a.where, "an area light's \"power\" is not built in kasha: give \"scale\"");
      if (a.params.find("filename", "string"))
        pbrt_fail(a.where, "an area light's image (\"filename\") is not built in kasha");
      const bool two_sided = a.params.get_bool("twosided", false);
      a.params.warn_unused("AreaLightSource \"diffuse\"");
      s["emission"] = pbrt_light_spectrum(L, scale, base_dir_);
      if (two_sided) {
        // kasha's lamps emit from the front: a two-sided one is two copies, wound both ways.
        nlohmann::json back = s;
        back["reverse_orientation"] = !s.value("reverse_orientation", false);
        place(back, state_.ctm, where);
      }
    }
    place(s, state_.ctm, where);
  }

  static void check_affine(const Matrix& ctm, const PbrtLocation& where) {
    if (!(std::abs(ctm.topLeftCorner<3, 3>().determinant()) > 1e-300) ||
        ctm.row(3) != Eigen::RowVector4d(0, 0, 0, 1) || !ctm.allFinite())
      pbrt_fail(where, "the shape's transform is singular or projective");
  }

  void place(nlohmann::json s, const Matrix& ctm, const PbrtLocation& where) {
    check_affine(ctm, where);
    if (!ctm.isIdentity(0)) s["transform"] = {{"matrix", row_major(ctm)}};
    const std::string at = "/shapes/" + std::to_string(shapes_.size());
    sources_[at] = where.str();
    if (s.contains("emission") && state_.area_light)
      sources_[at + "/emission"] = state_.area_light->where.str();
    shapes_.push_back(std::move(s));
  }

  std::string main_file_;
  std::filesystem::path base_dir_;
  std::map<std::string, std::string> overrides_;
  std::set<std::string> overridden_objects_;
  GraphicsState state_;
  std::vector<SavedState> stack_;
  std::map<std::string, Matrix> named_frames_;
  bool end_time_only_ = false;
  bool start_time_only_ = false;  // ActiveTransform StartTime: what moves the scene
  bool camera_seen_ = false;
  std::optional<int> max_depth_ = kPbrtDefaultMaxDepth;  // the Integrator's (pbrt_integrator.h)
  bool world_begun_ = false;
  nlohmann::json camera_ = nlohmann::json::object();
  double exposure_time_ = 1, iso_ = 100;  // pbrt-v4's imaging ratio: their product / 100
  // pbrt-v4's default filter (filters.cpp): a gaussian of radius 1.5 and sigma 0.5.
  nlohmann::json filter_ = {{"type", "gaussian"}, {"radius", {1.5, 1.5}}, {"sigma", 0.5}};
  nlohmann::json materials_ = nlohmann::json::object();
  std::set<std::string> named_materials_, interfaces_;
  std::multimap<std::string, PbrtLocation> named_material_uses_;
  std::vector<std::pair<std::string, PbrtLocation>> anonymous_mixes_;  // checked at the end
  bool uses_default_material_ = false;
  PbrtTextures textures_;
  nlohmann::json lights_ = nlohmann::json::array();
  nlohmann::json media_ = nlohmann::json::object();   // MakeNamedMedium's homogeneous media
  std::map<std::string, std::string> refused_media_;  // the others: why each is refused
  std::multimap<std::string, PbrtLocation> medium_uses_;
  nlohmann::json shapes_ = nlohmann::json::array();
  nlohmann::json instances_ = nlohmann::json::array();
  std::map<std::string, ObjectDefinition> objects_;
  ObjectDefinition* object_ = nullptr;
  std::set<std::string> warned_;
  JsonSourceMap sources_;  // JSON pointer → FILE:LINE of its statement
};

}  // namespace

nlohmann::json import_pbrt_scene(const std::string& path,
                                 const std::vector<MaterialOverride>& overrides,
                                 JsonSourceMap* sources) {
  Importer importer(path, overrides);
  nlohmann::json scene = importer.run();
  if (sources) *sources = importer.sources();
  return scene;
}

}  // namespace kasha
