// AllocationScope (core/memory.h): running out of memory inside named work is reported as what was
// being allocated and how to make it smaller. The record is the innermost scope the exception left,
// nothing is recorded when a scope ends normally, and entering a scope forgets an older record.
#include "hrad/core/memory.h"

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>

namespace hrad {
namespace {

TEST(AllocationScope, ExceptionRecordsTheInnermostScopeItLeft) {
  try {
    const AllocationScope solve("the hierarchical solve", "raise --aeps");
    const AllocationScope phase("the links of the refinement", "raise --aeps");
    throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
  }
  EXPECT_EQ(failed_allocation(), "the links of the refinement: raise --aeps");
}

TEST(AllocationScope, InnerScopeEndedNormallyIsNotBlamed) {
  try {
    const AllocationScope solve("the full solve", "raise --max-area");
    { const AllocationScope phase("the elements", "raise --max-area"); }
    throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
  }
  EXPECT_EQ(failed_allocation(), "the full solve: raise --max-area");
}

TEST(AllocationScope, NothingRecordedWithoutAnExceptionAndANewScopeForgetsAnOldRecord) {
  try {
    const AllocationScope s("the scene read from a.obj", "read a smaller scene");
    throw std::runtime_error("handled inside the work");
  } catch (const std::runtime_error&) {
  }
  ASSERT_FALSE(failed_allocation().empty());
  { const AllocationScope next("the 64 x 64 image at 1 samples per pixel", "render smaller"); }
  EXPECT_EQ(failed_allocation(), "");
}

TEST(AllocationScope, LongTextsAreCutNotOverrun) {
  const std::string what(1000, 'x');
  try {
    const AllocationScope s(what, "raise --aeps");
    throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
  }
  const std::string recorded = failed_allocation();
  EXPECT_GT(recorded.size(), 100u);
  EXPECT_LT(recorded.size(), 400u);
  EXPECT_EQ(recorded.find_first_not_of('x'), std::string::npos);
}

}  // namespace
}  // namespace hrad
