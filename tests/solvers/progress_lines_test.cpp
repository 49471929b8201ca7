// Long phases say how far they are with an estimate of the time left (SolveOptions::progress, one
// line per progress_interval_seconds; 0 here, so that a small box prints a line at every step): the
// form factors of the full matrix and of substructuring, every level of the hierarchical refinement,
// and the iterations of an iterative solve with their current change. The counts in the lines are
// the work done, so they must add up to the solver's own counts: n(n-1)/2 pairs for the full matrix
// (one kernel call per unordered pair), n N factors for substructuring, the candidate pairs of the
// refinement, one line per iteration from the second to the one before the last (the last one ends
// the solve and is told by its summary instead).
#include <gtest/gtest.h>

#include <mutex>
#include <regex>
#include <string>
#include <vector>

#include "hrad/solvers/solve.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

struct Lines {
  std::mutex mutex;
  std::vector<std::string> lines;
  std::vector<std::string> matching(const std::string& prefix) const {
    std::vector<std::string> out;
    for (const std::string& l : lines)
      if (l.rfind(prefix, 0) == 0) out.push_back(l);
    return out;
  }
};

// A closed box with a bright ceiling: every method has form factors to compute and light to bounce.
Scene lit_box() {
  return test::make_box(
      1, 1, 1, {test::material(Rgb::Constant(0.5), Rgb::Zero()), test::material(Rgb::Constant(0.5), Rgb::Constant(1))},
      {0, 1, 0, 0, 0, 0});
}

SolveSummary solve_with_lines(const Scene& s, SolveOptions options, Lines& out) {
  options.progress_interval_seconds = 0.0;
  options.progress = [&out](std::string_view line) {
    const std::lock_guard<std::mutex> lock(out.mutex);
    out.lines.emplace_back(line);
  };
  return solve(s, options, nullptr);
}

std::uint64_t count_in(const std::string& line, const std::regex& pattern) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(line, m, pattern)) << line;
  std::string digits = m.size() > 1 ? m[1].str() : "0";
  std::erase(digits, ',');
  return std::stoull(digits);
}

bool any_with_time_left(const std::vector<std::string>& lines) {
  for (const std::string& l : lines)
    if (l.find(" left") != std::string::npos) return true;
  return false;
}

TEST(ProgressLines, FullMatrixFormFactorsCountEveryPairOnce) {
  Lines lines;
  SolveOptions o;
  o.method = Method::kFull;
  o.max_area = 1.0 / 16;  // 96 elements
  const SolveSummary s = solve_with_lines(lit_box(), o, lines);
  const std::vector<std::string> ff = lines.matching("full: form factors: ");
  ASSERT_GE(ff.size(), 2u);
  EXPECT_TRUE(any_with_time_left(ff));
  const std::uint64_t n = s.elements;
  EXPECT_EQ(count_in(ff.back(), std::regex("done, ([0-9,]+) pairs")), n * (n - 1) / 2) << ff.back();
}

TEST(ProgressLines, SubstructuringFormFactorsCountEveryElementPatchPair) {
  Lines lines;
  SolveOptions o;
  o.method = Method::kSubstructure;
  o.max_area = 1.0 / 64;
  o.patch_area = 1.0 / 4;
  const SolveSummary s = solve_with_lines(lit_box(), o, lines);
  const std::vector<std::string> ff = lines.matching("substructure: form factors: ");
  ASSERT_GE(ff.size(), 2u) << "no progress during the form factors";
  EXPECT_TRUE(any_with_time_left(ff));
  const auto patches = static_cast<std::uint64_t>(s.figures.at("shooting_patches"));
  EXPECT_EQ(count_in(ff.back(), std::regex("done, ([0-9,]+) factors")), s.elements * patches) << ff.back();
  EXPECT_EQ(s.elements * patches, s.links);
}

TEST(ProgressLines, HierarchicalLevelsAddUpToTheCandidatePairs) {
  Lines lines;
  SolveOptions o;  // hierarchical at its defaults
  const SolveSummary s = solve_with_lines(lit_box(), o, lines);
  const std::vector<std::string> levels = lines.matching("refine: level ");
  ASSERT_FALSE(levels.empty());
  EXPECT_TRUE(any_with_time_left(levels));
  std::uint64_t examined = 0;
  const std::regex summary_line("^refine: level [0-9]+: ([0-9]+) pairs examined");
  for (const std::string& l : levels)
    if (std::regex_search(l, summary_line)) examined += count_in(l, summary_line);
  EXPECT_EQ(examined, s.work.candidate_pairs);
}

TEST(ProgressLines, IterationsShowTheirChangeAfterTheFirst) {
  Lines lines;
  SolveOptions o;
  o.method = Method::kFull;
  o.linear_solver = LinearSolver::kJacobi;
  o.max_area = 1.0 / 4;
  const SolveSummary s = solve_with_lines(lit_box(), o, lines);
  const std::vector<std::string> it = lines.matching("iteration ");
  ASSERT_GT(s.iterations, 2);
  EXPECT_EQ(it.size(), static_cast<std::size_t>(s.iterations - 2));
  const std::regex change("^iteration ([0-9]+): relative change ");
  EXPECT_EQ(count_in(it.front(), change), 2u);
  EXPECT_EQ(count_in(it.back(), change), static_cast<std::uint64_t>(s.iterations - 1));
  EXPECT_NE(it.back().find("more iterations"), std::string::npos) << it.back();
}

}  // namespace
}  // namespace hrad
