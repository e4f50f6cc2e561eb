// The tests run the BLAS as femup's entry points do: one thread per caller
// (femup/core/linalg/blas.h), so results do not depend on the machine's cores.
#include <gtest/gtest.h>

#include "femup/core/linalg/blas.h"

namespace {

class OneBlasThreadPerCaller : public ::testing::Environment {
 public:
  void SetUp() override { femup::UseOneBlasThreadPerCaller(); }
};

const ::testing::Environment* const kBlasEnvironment =
    ::testing::AddGlobalTestEnvironment(new OneBlasThreadPerCaller);

}  // namespace
