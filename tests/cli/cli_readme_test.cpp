// The README's "Commands and options" section is the manual a user reads; `hrad SUBCOMMAND --help` is
// what the program accepts. The two must name the same options, so that neither tells a user of an option
// that does not exist nor hides one that does.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run_hrad.h"
#include "support/source_tree.h"

namespace hrad::test {
namespace {

// The options (`--name`) of the table under the README's "### `hrad SUBCOMMAND`" heading: cells that
// start a table row.
std::set<std::string> readme_options(const std::string& readme, const std::string& subcommand) {
  const std::string heading = "### `hrad " + subcommand + "`\n";
  const std::size_t start = readme.find(heading);
  if (start == std::string::npos) return {};
  std::size_t end = readme.find("\n#", start + heading.size());
  if (end == std::string::npos) end = readme.size();
  std::istringstream section(readme.substr(start, end - start));
  const std::regex row(R"(^\| `(--[a-z0-9-]+)[^`]*` \|)");
  std::set<std::string> options;
  std::smatch m;
  for (std::string line; std::getline(section, line);)
    if (std::regex_search(line, m, row)) options.insert(m[1]);
  return options;
}

// The first capture of `pattern` on each line of a `--help` section ("Options:", "Subcommands:"):
// the indented lines that follow its header, up to the next unindented line.
std::vector<std::string> section_matches(const std::string& help, const std::string& header,
                                         const std::regex& pattern) {
  std::istringstream in(help);
  std::vector<std::string> found;
  bool inside = false;
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (line == header)
      inside = true;
    else if (!line.empty() && line[0] != ' ')
      inside = false;
    else if (inside && std::regex_search(line, m, pattern))
      found.push_back(m[1]);
  }
  return found;
}

// The options CLI11 lists under "Options:" in `--help`, without --help itself.
std::set<std::string> help_options(const std::string& help) {
  std::set<std::string> options;
  for (const std::string& o : section_matches(help, "Options:", std::regex(R"(^  (?:-[a-z],)?(--[a-z0-9-]+))")))
    if (o != "--help") options.insert(o);
  return options;
}

// The names CLI11 lists under "Subcommands:" in `--help`.
std::vector<std::string> help_subcommands(const std::string& help) {
  return section_matches(help, "Subcommands:", std::regex(R"(^  ([a-z][a-z0-9-]*) )"));
}

TEST(CliReadme, OptionTablesMatchHelp) {
  // Every (sub)subcommand `hrad --help` lists, so a new command without a README table fails too.
  const std::string readme = slurp(test::source_dir() + "/README.md");
  ASSERT_FALSE(readme.empty());
  TempDir dir;
  const RunResult top = run_hrad("--help", dir);
  ASSERT_EQ(top.exit_code, 0) << top.err;
  std::vector<std::string> pending = help_subcommands(top.out), checked;
  ASSERT_GE(pending.size(), 5u) << top.out;
  while (!pending.empty()) {
    const std::string subcommand = pending.back();
    pending.pop_back();
    const RunResult r = run_hrad(subcommand + " --help", dir);
    ASSERT_EQ(r.exit_code, 0) << subcommand << ": " << r.err;
    if (const std::vector<std::string> nested = help_subcommands(r.out); !nested.empty()) {
      for (const std::string& n : nested) pending.push_back(subcommand + " " + n);
      continue;
    }
    checked.push_back(subcommand);
    const std::set<std::string> help = help_options(r.out);
    ASSERT_FALSE(help.empty()) << subcommand << ": no options parsed from --help:\n" << r.out;
    const std::set<std::string> documented = readme_options(readme, subcommand);
    EXPECT_FALSE(documented.empty()) << "the README has no table under ### `hrad " << subcommand << "`";
    for (const std::string& o : help)
      EXPECT_TRUE(documented.count(o)) << "hrad " << subcommand << " " << o << " is missing from the README's table";
    for (const std::string& o : documented)
      EXPECT_TRUE(help.count(o)) << "the README documents hrad " << subcommand << " " << o << ", which --help lacks";
  }
  EXPECT_NE(std::find(checked.begin(), checked.end(), "scene generate"), checked.end());
}

// The parsers above on text whose answer is known, so that the test above cannot pass by parsing nothing.
TEST(CliReadme, ParsersReadTablesAndHelp) {
  const std::string readme =
      "### `hrad x`\n\n| option | meaning |\n| --- | --- |\n| `--a INT` | A |\n| `--b-c` | B |\n"
      "see `--d` in prose\n\n### `hrad y`\n\n| `--e` | E |\n";
  EXPECT_EQ(readme_options(readme, "x"), (std::set<std::string>{"--a", "--b-c"}));
  EXPECT_EQ(readme_options(readme, "y"), (std::set<std::string>{"--e"}));
  EXPECT_TRUE(readme_options(readme, "z").empty());
  const std::string help =
      "Usage: hrad x [OPTIONS]\n\nOptions:\n  -h,--help   Print\n  --a INT     A\n  --b-c       B\n"
      "                (continued --not-an-option)\n\nSubcommands:\n  --f  not an option\n";
  EXPECT_EQ(help_options(help), (std::set<std::string>{"--a", "--b-c"}));
  const std::string top =
      "Usage: hrad\n\nOptions:\n  --version  V\n\nSubcommands:\n  info     Print\n  scene    Scene\n";
  EXPECT_EQ(help_subcommands(top), (std::vector<std::string>{"info", "scene"}));
}

}  // namespace
}  // namespace hrad::test
