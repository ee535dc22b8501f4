#pragma once

#include <gtest/gtest.h>

#include <string>

#include <sandphys/error.h>

namespace sandphys::analysis::testing {

// Runs `call`, expects InvalidArgument, and returns its message.
template <typename Call>
std::string errorOf(Call call) {
  try {
    call();
  } catch (const InvalidArgument& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InvalidArgument thrown";
  return {};
}

}  // namespace sandphys::analysis::testing
