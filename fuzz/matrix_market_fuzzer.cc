// libFuzzer harness: the Matrix Market reader, sparse and dense
// (femup::ParseMatrixMarket, femup::ParseMatrixMarketDense), on arbitrary
// bytes. Each either returns or throws InputError; anything else (another
// exception, an abort, a sanitizer report, a hang, a huge allocation) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const femup::SparseMatrix a = femup::ParseMatrixMarket(text, "fuzz.mtx");
    (void)a;
  } catch (const femup::InputError&) {
  }
  try {
    const Eigen::MatrixXd a = femup::ParseMatrixMarketDense(text, "fuzz.mtx");
    (void)a;
  } catch (const femup::InputError&) {
  }
  return 0;
}
