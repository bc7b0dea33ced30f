#pragma once
// Strict reading of JSON input files: every value is reached through a JsonNode that knows its file
// and JSON path, so each error names both; finish() rejects keys nobody asked for.
#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kasha {

// Where parts of a document made from another file came from: a JSON pointer ("/shapes/3") to the
// source's "FILE:LINE" (an imported pbrt-v4 scene's statements).
using JsonSourceMap = std::map<std::string, std::string>;

// A key as one step of a JSON pointer (RFC 6901: ~ as ~0, / as ~1).
std::string escape_pointer(const std::string& key);

class JsonNode {
 public:
  // Parses a whole file; a syntax error names the file, line and column.
  static JsonNode load_file(const std::filesystem::path& file);
  // Parses JSON text given elsewhere (the command line) as strictly as a file; `where` (the option
  // and its value, as given) starts each message, escaped; relative paths resolve against
  // `base_dir` ("" for the working directory).
  static JsonNode parse_text(const std::string& text, const std::string& where,
                             const std::filesystem::path& base_dir);
  // Wraps an already parsed document (tests); `file` is used in messages.
  static JsonNode from_json(nlohmann::json document, const std::string& file);
  // The same, with each error under a mapped pointer naming its source's FILE:LINE instead.
  static JsonNode from_json(nlohmann::json document, const std::string& file,
                            std::shared_ptr<const JsonSourceMap> sources);

  const std::string& file() const { return file_; }
  std::string path() const { return path_.empty() ? "/" : path_; }
  // Directory that relative paths in this document are resolved against (empty: the working
  // directory).
  std::filesystem::path base_dir() const { return base_dir_; }
  // This string as a file's path, a relative one resolved against base_dir(); an empty one fails.
  std::filesystem::path file_path() const;

  bool is_object() const { return json_->is_object(); }
  bool is_array() const { return json_->is_array(); }
  bool is_number() const { return json_->is_number(); }
  bool is_string() const { return json_->is_string(); }
  bool is_bool() const { return json_->is_boolean(); }
  bool is_null() const { return json_->is_null(); }

  bool has(const std::string& key) const;
  JsonNode at(const std::string& key) const;  // required key of an object
  std::optional<JsonNode> find(const std::string& key) const;
  std::vector<std::string> keys() const;    // an object's keys, all marked as read
  size_t size() const;                      // array length
  JsonNode operator[](size_t index) const;  // array element

  double number() const;  // finite
  double number_in(double lo, double hi) const;
  int integer_in(int lo, int hi) const;
  std::string string() const;
  bool boolean() const;
  std::vector<double> numbers() const;  // array of finite numbers
  std::array<double, 3> vec3() const;

  // Rejects keys of this object that were never read: "unknown key".
  void finish() const;
  // "FILE: PATH", or the source's "FILE:LINE" of the deepest mapped pointer above PATH: what
  // messages about this value start with.
  std::string where() const;
  // Throws kasha::Error "FILE: PATH: why" (where(): why).
  [[noreturn]] void fail(const std::string& why) const;

 private:
  JsonNode(std::shared_ptr<const nlohmann::json> root, const nlohmann::json* json, std::string file,
           std::filesystem::path base_dir, std::string path);
  void expect_object() const;
  std::string where_at(const std::string& path) const;
  std::string type_name() const;

  std::shared_ptr<const nlohmann::json> root_;  // keeps the document alive
  const nlohmann::json* json_;
  std::string file_;
  std::filesystem::path base_dir_;
  std::string path_;
  std::shared_ptr<std::set<std::string>> read_keys_;
  std::shared_ptr<const JsonSourceMap> sources_;  // null: the document is its own source
};

}  // namespace kasha
