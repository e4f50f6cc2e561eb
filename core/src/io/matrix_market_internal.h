// Private to femup_core: what the Matrix Market files share. SizeText is
// defined in matrix_market_import.cc and also quoted by the writer
// (matrix_market_write.cc).
#pragma once

#include <string>

#include "femup/core/fe/model.h"

namespace femup::matrix_market_internal {

std::string SizeText(const SparseMatrix& a);

}  // namespace femup::matrix_market_internal
