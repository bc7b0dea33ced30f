#include "spectrum/spectrum_argument.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_node.h"
#include "spectrum/builtin_spectra.h"
#include "spectrum/spectrum_parser.h"

namespace kasha {

SpectrumPtr parse_spectrum_argument(const std::string& text, const std::string& option) {
  if (SpectrumPtr s = builtin_spectrum(text)) return s;
  if (std::filesystem::is_regular_file(text)) return read_spectrum_csv(text);
  nlohmann::json document = nlohmann::json::parse(text, nullptr, /*allow_exceptions*/ false);
  if (document.is_discarded()) {
    std::string known;
    for (const auto& n : builtin_spectrum_names()) known += (known.empty() ? "" : ", ") + n;
    throw Error(option + " " + text + ": not a built-in spectrum (" + known +
                "), an existing CSV file or a JSON spectrum value");
  }
  // Relative "csv" paths inside the JSON resolve against the working directory.
  return parse_spectrum(JsonNode::from_json(document, option + " " + text));
}

}  // namespace kasha
