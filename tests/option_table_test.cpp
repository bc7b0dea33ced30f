// The render options gathered from the integrators' declarations (render/option_table.h): the
// table of integrator options in docs/commands.md lists the same options, takers and choices,
// and the MPI fingerprint tells apart every setting but the device's own.
#include "render/option_table.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <variant>

#include "test_support.h"

using namespace kasha;

namespace {

std::vector<std::string> split(const std::string& text, const std::string& by) {
  std::vector<std::string> parts;
  size_t start = 0, at;
  while ((at = text.find(by, start)) != std::string::npos) {
    parts.push_back(text.substr(start, at - start));
    start = at + by.size();
  }
  parts.push_back(text.substr(start));
  return parts;
}

std::string trimmed(const std::string& s) {
  const size_t a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

struct DocRow {
  std::set<std::string> takers;
  std::vector<std::string> choices;  // from `--merges auto\|caustic\|first\|every`
};

// The rows of the table under "### Integrator options", by option name.
std::map<std::string, DocRow> documented_options() {
  std::ifstream in(test::source_path("docs/commands.md"));
  std::string line;
  while (std::getline(in, line) && line != "### Integrator options") {
  }
  std::map<std::string, DocRow> rows;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("| `--", 0) != 0) {
      if (in_table) break;
      continue;
    }
    in_table = true;
    const std::vector<std::string> cells = split(line, " | ");
    const std::string option = cells[0].substr(3, cells[0].find('`', 3) - 3);  // "--merges a\|b"
    const size_t space = option.find_first_of(" [");
    DocRow& row = rows[option.substr(0, space)];
    for (const std::string& taker : split(cells[1], ",")) row.takers.insert(trimmed(taker));
    if (option.find("\\|") != std::string::npos)
      row.choices = split(option.substr(space + 1), "\\|");
  }
  return rows;
}

}  // namespace

TEST(OptionTable, CommandsDocListsTheDeclaredOptions) {
  const std::map<std::string, DocRow> doc = documented_options();
  size_t declared = 0;
  for (const RenderOption& o : render_options()) {
    if (o.common()) continue;
    ++declared;
    SCOPED_TRACE(o.option.name);
    auto row = doc.find(o.option.name);
    ASSERT_NE(row, doc.end()) << "docs/commands.md's integrator options lack it";
    EXPECT_EQ(row->second.takers, std::set<std::string>(o.takers.begin(), o.takers.end()));
    IntegratorSettings s;
    const SettingField field = o.option.field(s);
    if (const auto* choice = std::get_if<ChoiceField>(&field)) {
      EXPECT_EQ(row->second.choices, *choice->names);
    }
  }
  EXPECT_EQ(doc.size(), declared) << "docs/commands.md documents an option nobody declares";
}

// Each taker's default reaches the assembled help, from the declaration.
TEST(OptionTable, HelpNamesEveryTakersDefault) {
  for (const RenderOption& o : render_options()) {
    SCOPED_TRACE(o.option.name);
    for (const std::string& taker : o.takers)
      EXPECT_NE(o.option.help.find(taker), std::string::npos) << o.option.help;
    EXPECT_NE(o.option.help.find("default"), std::string::npos) << o.option.help;
  }
}

TEST(OptionTable, FingerprintTellsApartEverySettingButTheDevicesOwn) {
  const std::string base = settings_fingerprint(IntegratorSettings{});
  for (const RenderOption& o : render_options()) {
    SCOPED_TRACE(o.option.name);
    IntegratorSettings s;
    std::visit(
        [](const auto& field) {
          using T = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<T, ChoiceField>)
            field.set((field.get() + 1) % field.names->size());
          else if constexpr (std::is_same_v<T, bool*>)
            *field = !*field;
          else
            *field = *field + 1;
        },
        o.option.field(s));
    EXPECT_EQ(settings_fingerprint(s) == base, o.option.device_own);
  }
}
